// The "pf_bearings" kind (formerly "bearings", still accepted): sim, run, eval, bench, demo and
// selftest for the Gordon-Salmond-Smith
// bearings-only benchmark with the SIS / SIR / APF engines of lib/include/pft/pft_pf.h
// (Wang 2010's comparison, docs/algorithms.md 3).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "../common/campaign.hpp"
#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../common/output.hpp"
#include "../common/parallel.hpp"
#include "../common/plot.hpp"
#include "../common/progress.hpp"
#include "../common/registry.hpp"
#include "../common/set_metrics.hpp"
#include "../tbd/tracker.hpp"
#include "pf_bearings.hpp"

using nlohmann::json;

namespace pft::host::pf {

namespace {

using tbd::from_real;
using tbd::numeric_name;
using tbd::to_real;

BearingsScenario load(const Options &o)
{
    if (!o.filter_kind.empty() || o.single || !o.preset.empty())
        throw InputError("kind \"bearings\": --filter, --single and --preset do not apply "
                         "(the scenario's \"filters\" list the engines)");
    BearingsScenario s = parse_bearings(o.scenario, o.scenario_path);
    if (o.particles) {
        s.particles = {o.particles};
        s.table_particles = o.particles;
    }
    if (std::find(s.particles.begin(), s.particles.end(), s.table_particles) == s.particles.end())
        s.particles.push_back(s.table_particles);
    std::sort(s.particles.begin(), s.particles.end());
    s.particles.erase(std::unique(s.particles.begin(), s.particles.end()), s.particles.end());
    return s;
}

/** GOSPA/OSPA settings of a bearings eval: one truth and one estimate per step, so GOSPA is the
 *  radial error cut at c (a miss and a false point beyond it). Default c = lost_radius. */
struct SetMetricParams {
    double c, p;
};
SetMetricParams set_params(const Options &o, const BearingsScenario &s)
{
    return {o.gospa_c ? *o.gospa_c : s.lost_radius, o.gospa_p ? *o.gospa_p : 2.0};
}

std::string fmt(double v, int prec = 4)
{
    return fixed_text(v, prec, "-");
}

std::string fmt_e(double v)
{
    if (!std::isfinite(v))
        return "-";
    char b[40];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

double median(std::vector<double> v)
{
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string describe(const BearingsScenario &s)
{
    std::ostringstream os;
    os << (s.name.empty() ? s.file : s.name) << ": bearings-only CV, " << s.steps
       << " steps, sqrt(q) " << s.q_sd << ", sqrt(r) " << s.r_sd << ", scale " << s.scale
       << ", " << numeric_name() << "; filters";
    for (const auto &f : s.filters)
        os << " " << f.label;
    os << "; N";
    for (auto n : s.particles)
        os << " " << n;
    return os.str();
}

/** Per (filter, N) aggregate over runs. */
struct Agg {
    std::string label, engine;
    uint32_t n = 0;
    std::vector<double> sx, sy;  ///< per step: sum over runs of squared errors
    std::vector<double> sref;    ///< per step: sum over runs of squared distance to the reference
    std::vector<double> run_mse; ///< per run: mean squared radial error
    std::vector<double> off;     ///< per step: runs whose estimate's bearing is > 5 r_sd off the truth's
    double ns = 0, ess = 0, ess_first = 0, resamples = 0;
    std::vector<double> run_rms;  ///< per run: RMS radial error over the steps
    int lost = 0;
    std::size_t ws = 0;
    metrics::SetMetricSums set{0, 1.0, 2.0};  ///< GOSPA/OSPA per step over the runs
};

std::vector<double> gospa_steps(const metrics::SetMetricSums &m)
{
    std::vector<double> v(m.frames());
    for (std::size_t k = 0; k < v.size(); ++k)
        v[k] = m.gospa_at(k);
    return v;
}

json agg_json(const Agg &a, unsigned runs, int steps)
{
    json rx = json::array(), ry = json::array(), rr = json::array();
    double tx = 0, ty = 0;
    for (int k = 0; k < steps; ++k) {
        rx.push_back(std::sqrt(a.sx[k] / runs));
        ry.push_back(std::sqrt(a.sy[k] / runs));
        rr.push_back(std::sqrt((a.sx[k] + a.sy[k]) / runs));
        tx += a.sx[k];
        ty += a.sy[k];
    }
    double cnt = static_cast<double>(runs) * steps;
    // standard error of the RMSE over runs (delta method on the per-run mean squared errors)
    double mm = 0, mv = 0;
    for (double v : a.run_mse)
        mm += v / runs;
    for (double v : a.run_mse)
        mv += (v - mm) * (v - mm) / (runs > 1 ? runs - 1 : 1);
    double rmse = std::sqrt((tx + ty) / cnt);
    double se = rmse > 0 ? std::sqrt(mv / runs) / (2.0 * rmse) : 0.0;
    json dref = json::array();
    double tref = 0;
    for (std::size_t k = 0; k < a.sref.size(); ++k) {
        dref.push_back(std::sqrt(a.sref[k] / runs));
        tref += a.sref[k];
    }
    json j = {
        {"label", a.label},
        {"engine", a.engine},
        {"particles", a.n},
        {"runs", runs},
        {"rmse_x", std::sqrt(tx / cnt)},
        {"rmse_y", std::sqrt(ty / cnt)},
        {"rmse", rmse},
        {"rmse_se", se},
        {"rmse_to_reference", a.sref.empty() ? json(nullptr) : json(std::sqrt(tref / cnt))},
        {"rmse_to_reference_per_step", a.sref.empty() ? json(nullptr) : dref},
        {"ns_per_step", a.ns / cnt},
        {"median_run_rmse", median(a.run_rms)},
        {"far_final_runs", a.lost},
        {"bearing_off_final_runs", a.off.empty() ? 0.0 : a.off.back()},
        {"bearing_off_runs_per_step", a.off},
        {"mean_ess_ratio", a.ess / cnt},
        {"mean_ess_first_ratio", a.ess_first / cnt},
        {"resample_fraction", a.resamples / cnt},
        {"workspace_bytes", a.ws},
        {"rmse_x_per_step", rx},
        {"rmse_y_per_step", ry},
        {"rmse_per_step", rr},
        {"gospa_per_step", nums_or_null(gospa_steps(a.set))},
    };
    j.update(metrics::set_metric_fields(a.set));
    return j;
}

void plots(const BearingsScenario &s, const json &sum, const std::string &dir)
{
    const json &fl = sum["filters"];
    std::string tail = " - " + (s.name.empty() ? std::string("pf_bearings") : s.name) + ", " +
                       numeric_name() + ", " + std::to_string(sum["runs"].get<unsigned>()) + " runs";
    // Table 1: RMSE per step at the table N
    for (const char *axis : {"x", "y"}) {
        PlotSpec p;
        p.title = std::string("RMSE in ") + axis + " per step, N = " +
                  std::to_string(s.table_particles) + tail;
        p.xlabel = "step k";
        p.ylabel = std::string("RMSE ") + axis;
        p.ymin = 0.0;
        for (const json &f : fl) {
            if (f["particles"].get<uint32_t>() != s.table_particles)
                continue;
            PlotSeries ser;
            ser.label = f["label"].get<std::string>();
            auto v = f[std::string("rmse_") + axis + "_per_step"].get<std::vector<double>>();
            for (std::size_t k = 0; k < v.size(); ++k) {
                ser.x.push_back(static_cast<double>(k + 1));
                ser.y.push_back(v[k]);
            }
            p.series.push_back(ser);
        }
        save_plot_png(p, join_path(dir, std::string("rmse_") + axis + "_per_step.png"));
    }
    // Table 3 and 2: RMSE and time against N, and RMSE against time (equal compute)
    struct Fig {
        const char *file, *title, *xl, *yl, *xkey, *ykey;
        bool logx;
    };
    const Fig figs[] = {
        {"rmse_vs_particles.png", "RMSE against particle count", "log10 N", "RMSE (radial)", "particles", "rmse", true},
        {"time_vs_particles.png", "Time per step against particle count", "log10 N", "us per step", "particles", "ns_per_step", true},
        {"rmse_vs_time.png", "RMSE against time per step (equal compute)", "log10 us per step", "RMSE (radial)", "ns_per_step", "rmse", true},
        {"ref_dev_vs_particles.png", "RMS distance to the reference posterior mean", "log10 N", "RMS distance", "particles", "rmse_to_reference", true},
    };
    for (const Fig &g : figs) {
        if (!fl.empty() && !fl[0][g.ykey].is_number())
            continue;  // no reference filter in this scenario
        PlotSpec p;
        p.title = g.title + tail;
        p.xlabel = g.xl;
        p.ylabel = g.yl;
        p.ymin = 0.0;
        for (const auto &spec : s.filters) {
            PlotSeries ser;
            ser.label = spec.label;
            ser.markers = true;
            for (const json &f : fl) {
                if (f["label"].get<std::string>() != spec.label)
                    continue;
                double x = f[g.xkey].get<double>();
                if (std::string(g.xkey) == "ns_per_step")
                    x /= 1000.0;
                double y = f[g.ykey].get<double>();
                if (std::string(g.ykey) == "ns_per_step")
                    y /= 1000.0;
                ser.x.push_back(g.logx ? std::log10(x) : x);
                ser.y.push_back(y);
                // error bars: one standard error of the RMSE over the runs
                ser.err.push_back(std::string(g.ykey) == "rmse" ? f["rmse_se"].get<double>() : NAN);
            }
            p.series.push_back(ser);
        }
        save_plot_png(p, join_path(dir, g.file));
    }
}

void print_tables(const BearingsScenario &s, const json &sum)
{
    const json &fl = sum["filters"];
    std::vector<const json *> at_table;
    for (const json &f : fl)
        if (f["particles"].get<uint32_t>() == s.table_particles)
            at_table.push_back(&f);
    std::printf("\n  RMSE per step at N = %u (x / y, benchmark units)\n  %4s", s.table_particles, "k");
    for (auto *f : at_table)
        std::printf("  %19s", (*f)["label"].get<std::string>().c_str());
    std::printf("\n");
    for (int k = 0; k < s.steps; ++k) {
        std::printf("  %4d", k + 1);
        for (auto *f : at_table)
            std::printf("  %9s/%-9s", fmt((*f)["rmse_x_per_step"][k].get<double>()).c_str(),
                        fmt((*f)["rmse_y_per_step"][k].get<double>()).c_str());
        std::printf("\n");
    }
    std::printf("\n  %-10s %6s %8s %8s %8s %7s %8s %8s %5s %5s %9s %7s %7s %8s\n", "filter", "N", "RMSE x", "RMSE y",
                "RMSE", "+-se", "to ref", "median", "far", "brg", "us/step", "ESS/N", "ESS1/N", "GOSPA");
    for (const json &f : fl)
        std::printf("  %-10s %6u %8s %8s %8s %7s %8s %8s %5d %5.0f %9s %7s %7s %8s\n", f["label"].get<std::string>().c_str(),
                    f["particles"].get<uint32_t>(), fmt(f["rmse_x"].get<double>()).c_str(),
                    fmt(f["rmse_y"].get<double>()).c_str(), fmt(f["rmse"].get<double>()).c_str(),
                    fmt(f["rmse_se"].get<double>()).c_str(),
                    f["rmse_to_reference"].is_number() ? fmt(f["rmse_to_reference"].get<double>()).c_str() : "-",
                    fmt(f["median_run_rmse"].get<double>()).c_str(), f["far_final_runs"].get<int>(),
                    f["bearing_off_final_runs"].get<double>(),
                    fmt(f["ns_per_step"].get<double>() / 1000.0, 1).c_str(),
                    fmt(f["mean_ess_ratio"].get<double>(), 3).c_str(),
                    fmt(f["mean_ess_first_ratio"].get<double>(), 3).c_str(),
                    fmt(f["gospa"].is_number() ? f["gospa"].get<double>() : NAN).c_str());
    std::printf("  GOSPA: per step, truth and estimate as one-point sets, c = %s, p = %s (radial error cut at c)\n",
                fmt(sum["gospa_c"].get<double>(), 3).c_str(), fmt(sum["gospa_p"].get<double>(), 1).c_str());
    if (sum["reference_filter"].is_object())
        std::printf("  reference %s N=%u: RMSE to truth %s (the floor the others approach)\n",
                    sum["reference_filter"]["label"].get<std::string>().c_str(),
                    sum["reference_filter"]["particles"].get<uint32_t>(),
                    fmt(sum["reference_filter"]["rmse"].get<double>()).c_str());
    if (sum.contains("paired")) {
        std::printf("\n  paired: fraction of runs where A's run RMSE < B's (same sequences)\n");
        for (const json &p : sum["paired"])
            std::printf("  N=%-6u %-8s < %-8s %s\n", p["particles"].get<uint32_t>(),
                        p["a"].get<std::string>().c_str(), p["b"].get<std::string>().c_str(),
                        fmt(p["fraction"].get<double>(), 3).c_str());
    }
}

/** Every filter at every particle count on every run's sequence (and the reference filter). */
struct EvalRuns {
    std::vector<std::vector<PassResult>> res;  ///< res[run][filter * nn + n], the campaign's runs
    std::vector<std::size_t> ws;               ///< workspace bytes per filter and N
    std::vector<double> ref_se;                ///< reference filter: squared radial error per run
    std::vector<uint64_t> seeds;               ///< seed of each run
};

/** Workspace bytes of every filter and N (deterministic; taken once, not inside the runs). */
std::vector<std::size_t> workspaces(const BearingsScenario &s)
{
    std::vector<std::size_t> ws;
    for (const auto &f : s.filters)
        for (uint32_t n : s.particles)
            ws.push_back(BearingsFilter(s, f, n).workspace_bytes());
    return ws;
}

/** One run: every filter at every N on the sequence of `seed`, and the reference filter. */
void run_one(const BearingsScenario &s, uint64_t seed, std::vector<PassResult> &res, double &ref_se)
{
    const std::size_t nf = s.filters.size(), nn = s.particles.size();
    res.assign(nf * nn, PassResult());
    BearingsSequence q = simulate_bearings(s, seed);
    for (std::size_t f = 0; f < nf; ++f)
        for (std::size_t n = 0; n < nn; ++n) {
            BearingsFilter bf(s, s.filters[f], s.particles[n]);
            res[f * nn + n] = bf.pass(q, seed);
        }
    ref_se = 0.0;
    if (s.has_reference_filter) {
        // the reference runs with its own seed stream (not shared with the filters)
        BearingsFilter rf(s, s.reference_filter, s.reference_filter.particles);
        PassResult pr = rf.pass(q, seed ^ 0x5245465245465245ull);
        for (int k = 0; k < s.steps; ++k)
            ref_se += pr.ex[k] * pr.ex[k] + pr.ey[k] * pr.ey[k];
        for (auto &p : res) {
            p.dref.resize(s.steps);
            for (int k = 0; k < s.steps; ++k) {
                double dx = p.est[k][0] - pr.est[k][0], dy = p.est[k][2] - pr.est[k][2];
                p.dref[k] = dx * dx + dy * dy;
            }
        }
    }
}

/** A run's record in a partial summary, and back. */
json run_to_json(const std::vector<PassResult> &res, double ref_se, uint64_t seed)
{
    json passes = json::array();
    for (const PassResult &p : res) {
        json est = json::array();
        for (const auto &e : p.est)
            est.push_back(e);
        passes.push_back({{"ex", p.ex}, {"ey", p.ey}, {"dref", p.dref}, {"est", est}, {"ns", p.ns},
                          {"ess_sum", p.ess_sum}, {"ess_first_sum", p.ess_first_sum}, {"resamples", p.resamples}});
    }
    return {{"seed", seed}, {"ref_se", ref_se}, {"passes", passes}};
}

void run_from_json(const json &j, std::vector<PassResult> &res, double &ref_se, uint64_t &seed)
{
    seed = j.at("seed").get<uint64_t>();
    ref_se = j.at("ref_se").get<double>();
    res.clear();
    for (const json &x : j.at("passes")) {
        PassResult p;
        p.ex = x.at("ex").get<std::vector<double>>();
        p.ey = x.at("ey").get<std::vector<double>>();
        p.dref = x.at("dref").get<std::vector<double>>();
        for (const json &e : x.at("est"))
            p.est.push_back(e.get<std::array<double, 4>>());
        p.ns = x.at("ns").get<double>();
        p.ess_sum = x.at("ess_sum").get<double>();
        p.ess_first_sum = x.at("ess_first_sum").get<double>();
        p.resamples = x.at("resamples").get<int>();
        res.push_back(std::move(p));
    }
}

/** Adds one run's pass to the aggregate of its filter and N. */
void add_pass(const BearingsScenario &s, const PassResult &p, Agg &a)
{
    double se = 0;
    for (int k = 0; k < s.steps; ++k) {
        a.sx[k] += p.ex[k] * p.ex[k];
        a.sy[k] += p.ey[k] * p.ey[k];
        se += p.ex[k] * p.ex[k] + p.ey[k] * p.ey[k];
    }
    a.run_rms.push_back(std::sqrt(se / s.steps));
    a.run_mse.push_back(se / s.steps);
    for (int k = 0; k < s.steps; ++k) {
        // the truth from the estimate and the error (both benchmark units)
        double xe = p.est[k][0], ye = p.est[k][2];
        double xt = xe - p.ex[k], yt = ye - p.ey[k];
        double d = wrap_pi(std::atan2(ye, xe) - std::atan2(yt, xt));
        a.off[k] += std::fabs(d) > 5.0 * s.r_sd ? 1.0 : 0.0;
    }
    if (!p.dref.empty()) {
        if (a.sref.empty())
            a.sref.assign(s.steps, 0.0);
        for (int k = 0; k < s.steps; ++k)
            a.sref[k] += p.dref[k];
    }
    double fin = std::hypot(p.ex.back(), p.ey.back());
    a.lost += fin > s.lost_radius ? 1 : 0;
    for (int k = 0; k < s.steps; ++k)
        a.set.add(static_cast<std::size_t>(k),
                  metrics::frame_metrics({{0.0, 0.0}}, {{p.ex[k], p.ey[k]}}, a.set.c(), a.set.p()));
    a.ns += p.ns;
    a.ess += p.ess_sum;
    a.ess_first += p.ess_first_sum;
    a.resamples += p.resamples;
}

std::vector<Agg> aggregate(const BearingsScenario &s, const EvalRuns &er, unsigned runs, SetMetricParams sp)
{
    const std::size_t nf = s.filters.size(), nn = s.particles.size();
    std::vector<Agg> agg(nf * nn);
    for (std::size_t f = 0; f < nf; ++f)
        for (std::size_t n = 0; n < nn; ++n) {
            Agg &a = agg[f * nn + n];
            a.label = s.filters[f].label;
            a.engine = s.filters[f].engine;
            a.n = s.particles[n];
            a.sx.assign(s.steps, 0.0);
            a.sy.assign(s.steps, 0.0);
            a.off.assign(s.steps, 0.0);
            a.ws = er.ws[f * nn + n];
            a.set = metrics::SetMetricSums(static_cast<std::size_t>(s.steps), sp.c, sp.p);
            for (unsigned r = 0; r < runs; ++r)
                add_pass(s, er.res[r][f * nn + n], a);
        }
    return agg;
}

/** Paired comparisons on the same sequences: APF against the others, SIR against SIS. */
json paired_json(const BearingsScenario &s, const std::vector<Agg> &agg, unsigned runs)
{
    const std::size_t nf = s.filters.size(), nn = s.particles.size();
    json paired = json::array();
    for (std::size_t n = 0; n < nn; ++n)
        for (std::size_t fa = 0; fa < nf; ++fa)
            for (std::size_t fb = 0; fb < nf; ++fb) {
                if (fa == fb)
                    continue;
                const std::string &ea = s.filters[fa].engine, &eb = s.filters[fb].engine;
                bool want = (ea == "apf" && eb != "apf") || (ea == "sir" && eb == "sis");
                if (!want)
                    continue;
                int wins = 0;
                for (unsigned r = 0; r < runs; ++r)
                    wins += agg[fa * nn + n].run_rms[r] < agg[fb * nn + n].run_rms[r] ? 1 : 0;
                paired.push_back({{"particles", s.particles[n]}, {"a", s.filters[fa].label},
                                  {"b", s.filters[fb].label},
                                  {"fraction", static_cast<double>(wins) / runs}});
            }
    return paired;
}

/** Estimates at the table N, per filter, run and step ([x, y]), so that builds (float, q16,
 *  scales) can be compared sequence by sequence. */
json estimates_json(const BearingsScenario &s, const EvalRuns &er, unsigned runs)
{
    const std::size_t nf = s.filters.size(), nn = s.particles.size();
    json est_dump = json::object();
    for (std::size_t f = 0; f < nf; ++f)
        for (std::size_t n = 0; n < nn; ++n) {
            if (s.particles[n] != s.table_particles)
                continue;
            json per_run = json::array();
            for (unsigned r = 0; r < runs; ++r) {
                json steps = json::array();
                for (const auto &e : er.res[r][f * nn + n].est)
                    steps.push_back({e[0], e[2]});
                per_run.push_back(steps);
            }
            est_dump[s.filters[f].label] = per_run;
        }
    return est_dump;
}

/** The settings part of summary.json (common header, then the bearings settings). */
json bearings_head(const Options &o, const BearingsScenario &s, const Campaign &c, unsigned threads,
                   const CampaignTiming &t)
{
    SummaryHead h;
    h.kind = "pf_bearings";
    h.scenario = s.name;
    h.scenario_file = s.file;
    h.description = s.description;
    h.tag = o.tag.empty() ? std::string("bearings ") + numeric_name() : o.tag;
    h.scenario_json = s.raw;
    json head = summary_header(o, c, h, threads, t);
    head["timing"]["note"] = "ns_per_step: steady_clock around pft_pf_update, measured inside the threaded eval "
                             "(use bench for timing)";
    json engines = json::array();
    for (const auto &e : s.filters)
        engines.push_back(engine_json(e));
    SetMetricParams sp = set_params(o, s);
    head["steps"] = s.steps;
    head["scale"] = s.scale;
    head["ll_clip"] = s.ll_clip;
    head["lost_radius"] = s.lost_radius;
    head["table_particles"] = s.table_particles;
    head["particle_counts"] = s.particles;
    head["engines"] = engines;
    head["gospa_c"] = sp.c;
    head["gospa_p"] = sp.p;
    head["gospa_alpha"] = 2;
    head["scenario_json"] = s.raw;
    if (!s.reference.is_null())
        head["reference"] = s.reference;
    return head;
}

/** The measures (contract names) added to the head. */
json eval_summary(const Options &o, const BearingsScenario &s, const EvalRuns &er, const std::vector<Agg> &agg,
                  json head)
{
    const unsigned runs = static_cast<unsigned>(er.res.size());
    json filters = json::array();
    for (const Agg &a : agg)
        filters.push_back(agg_json(a, runs, s.steps));
    json ref_json = nullptr;
    if (s.has_reference_filter) {
        ref_json = engine_json(s.reference_filter);
        ref_json["particles"] = s.reference_filter.particles;
        double t = 0;
        for (double v : er.ref_se)
            t += v;
        ref_json["rmse"] = std::sqrt(t / (static_cast<double>(runs) * s.steps));
    }
    (void)o;
    head["reference_filter"] = ref_json;
    head["filters"] = filters;
    head["paired"] = paired_json(s, agg, runs);
    head["estimates_at_table_particles"] = estimates_json(s, er, runs);
    return head;
}

/** Rows of a CSV file of numbers with a header line and `cols` columns. */
std::vector<std::vector<double>> read_csv(const std::string &path, std::size_t cols)
{
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open file");
    std::vector<std::vector<double>> rows;
    std::string line;
    std::getline(in, line);  // header
    int ln = 1;
    while (std::getline(in, line)) {
        ++ln;
        if (line.empty())
            continue;
        std::vector<double> r;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ','))
            try {
                r.push_back(std::stod(cell));
            } catch (const std::exception &) {
                throw InputError(path + ":" + std::to_string(ln) + ": not a number: " + cell);
            }
        if (r.size() != cols)
            throw InputError(path + ":" + std::to_string(ln) + ": expected " +
                             std::to_string(cols) + " columns");
        rows.push_back(r);
    }
    return rows;
}

/** A `pft sim` sequence directory: bearings.csv and, when present, truth.csv (zeros else). */
BearingsSequence read_sequence(const std::string &dir, bool &have_truth)
{
    BearingsSequence q;
    for (auto &r : read_csv(join_path(dir, "bearings.csv"), 2))
        q.z.push_back(r[1]);
    have_truth = std::ifstream(join_path(dir, "truth.csv")).good();
    if (have_truth) {
        for (auto &r : read_csv(join_path(dir, "truth.csv"), 5))
            q.truth.push_back({r[1], r[2], r[3], r[4]});
        if (q.truth.size() != q.z.size())
            throw InputError(dir + ": truth.csv and bearings.csv differ in length");
    } else {
        q.truth.assign(q.z.size(), {0, 0, 0, 0});
    }
    return q;
}

/** Aggregates, writes summary.json and the plots, prints the tables (eval and merge). */
int finish(const Options &o, const BearingsScenario &s, const EvalRuns &er, json head, const std::string &out_dir)
{
    const unsigned runs = static_cast<unsigned>(er.res.size());
    std::vector<Agg> agg = aggregate(s, er, runs, set_params(o, s));
    json sum = eval_summary(o, s, er, agg, head);
    write_json_atomic(join_path(out_dir, "summary.json"), sum);
    plots(s, sum, out_dir);
    if (!o.quiet) {
        print_tables(s, sum);
        std::printf("\n  %.1f s wall; wrote %s/summary.json and plots (rmse_x_per_step.png, "
                    "rmse_y_per_step.png, rmse_vs_particles.png, time_vs_particles.png, rmse_vs_time.png)\n",
                    sum["timing"]["wall_s"].get<double>(), out_dir.c_str());
    }
    return 0;
}

class BearingsHandler : public KindHandler {
public:
    int eval(const Options &o) override
    {
        BearingsScenario s = load(o);
        Campaign c = make_campaign(o.runs ? o.runs : s.runs, o.seed ? *o.seed : s.base_seed, o.shard);
        unsigned threads = resolve_threads(o.threads);
        std::string out_dir = o.out.empty() ? "pft_eval_" + (s.name.empty() ? std::string("pf_bearings") : s.name) +
                                                  "_" + numeric_name()
                                            : o.out;
        ensure_dir(out_dir);
        if (!o.quiet)
            std::printf("pft eval: %s\n  %zu runs, seeds %llu..%llu, %u threads\n", describe(s).c_str(), c.count(),
                        static_cast<unsigned long long>(c.seed(c.first)),
                        static_cast<unsigned long long>(c.seed(c.end - 1)), threads);
        EvalRuns er;
        er.res.resize(c.count());
        er.ref_se.assign(c.count(), 0.0);
        er.seeds.resize(c.count());
        er.ws = workspaces(s);
        CampaignTiming t = run_campaign(c, threads, progress_wanted(o.progress), "eval", [&](std::size_t run, uint64_t seed) {
            std::size_t i = run - c.first;
            run_one(s, seed, er.res[i], er.ref_se[i]);
            er.seeds[i] = seed;
        });
        json head = bearings_head(o, s, c, threads, t);
        if (c.partial()) {
            json recs = json::array();
            for (std::size_t i = 0; i < er.res.size(); ++i)
                recs.push_back(run_to_json(er.res[i], er.ref_se[i], er.seeds[i]));
            std::string path = write_partial(out_dir, head, o, c, recs);
            if (!o.quiet)
                std::printf("  %.1f s wall; wrote %s (pft merge combines the shards)\n", t.wall_s, path.c_str());
            return 0;
        }
        return finish(o, s, er, head, out_dir);
    }

    int merge(const Options &o, const MergedRuns &m) override
    {
        Options eo = m.eval_options(o);
        BearingsScenario s = load(eo);
        EvalRuns er;
        er.res.resize(m.runs.size());
        er.ref_se.resize(m.runs.size());
        er.seeds.resize(m.runs.size());
        for (std::size_t i = 0; i < m.runs.size(); ++i)
            run_from_json(m.runs[i], er.res[i], er.ref_se[i], er.seeds[i]);
        er.ws = workspaces(s);
        ensure_dir(o.out);
        json head = bearings_head(eo, s, m.campaign, m.threads, m.timing);
        add_merge_fields(head, m);
        return finish(eo, s, er, head, o.out);
    }

    int bench(const Options &o) override
    {
        BearingsScenario s = load(o);
        unsigned runs = o.runs ? o.runs : 5;
        int steps = o.frames ? static_cast<int>(o.frames) : s.steps;
        uint64_t base = o.seed ? *o.seed : s.base_seed;
        json entries = json::array();
        if (!o.quiet)
            std::printf("pft bench: %s\n  %u timed runs of %d steps each, one thread; the filters take turns "
                        "within each run (round robin), so load changes hit them alike\n\n  %-10s %6s %12s %12s %12s %14s %10s\n",
                        describe(s).c_str(), runs, steps, "filter", "N", "us/step min", "us/step med",
                        "us/step mean", "ns/particle", "workspace");
        // every filter and N built once; run r: the same sequence through each of them in turn
        std::vector<std::unique_ptr<BearingsFilter>> bfs;
        std::vector<std::pair<const EngineSpec *, uint32_t>> cfgs;
        for (const auto &spec : s.filters)
            for (uint32_t n : s.particles) {
                bfs.push_back(std::make_unique<BearingsFilter>(s, spec, n));
                cfgs.push_back({&spec, n});
            }
        std::vector<std::vector<double>> per(bfs.size());
        Progress bar(static_cast<std::size_t>(runs) * bfs.size(), "bench", progress_wanted(o.progress));
        for (unsigned r = 0; r < runs; ++r) {
            BearingsSequence q = simulate_bearings(s, base + r, steps);
            for (std::size_t i = 0; i < bfs.size(); ++i) {
                PassResult p = bfs[i]->pass(q, base + r);
                per[i].push_back(p.ns / steps);
                bar.tick();
            }
        }
        bar.finish();
        for (std::size_t i = 0; i < bfs.size(); ++i) {
            const EngineSpec &spec = *cfgs[i].first;
            uint32_t n = cfgs[i].second;
            double tot = 0;
            for (double v : per[i])
                tot += v;
            double med = median(per[i]), mean = tot / runs;
            double mn = *std::min_element(per[i].begin(), per[i].end());
            entries.push_back({{"label", spec.label}, {"engine", spec.engine}, {"particles", n},
                               {"steps", steps}, {"runs", runs}, {"ns_per_step_median", med},
                               {"ns_per_step_mean", mean}, {"ns_per_step_min", mn},
                               {"ns_per_particle_step", med / n}, {"ns_per_particle_step_min", mn / n},
                               {"workspace_bytes", bfs[i]->workspace_bytes()}});
            if (!o.quiet)
                std::printf("  %-10s %6u %12s %12s %12s %14s %10zu\n", spec.label.c_str(), n,
                            fmt(mn / 1000.0, 1).c_str(), fmt(med / 1000.0, 1).c_str(),
                            fmt(mean / 1000.0, 1).c_str(), fmt(mn / n, 1).c_str(), bfs[i]->workspace_bytes());
        }
        if (!o.quiet && !s.reference.is_null())
            std::printf("\n  paper [P2] Table 2 (2 frames, its video experiment and hardware): %s\n",
                        s.reference.dump().c_str());
        if (!o.out.empty()) {
            ensure_dir(o.out);
            json j = {{"tool", "pft bench"}, {"kind", "pf_bearings"}, {"scenario", s.name},
                      {"numeric", numeric_name()}, {"runs", runs}, {"steps", steps},
                      {"base_seed", base}, {"order", "round robin: run r passes one sequence through every filter in turn"},
                      {"entries", entries}};
            write_json_atomic(join_path(o.out, "bench.json"), j);
        }
        return 0;
    }

    int sim(const Options &o) override
    {
        BearingsScenario s = load(o);
        uint64_t seed = o.seed ? *o.seed : s.base_seed;
        Progress bar(1, "sim", progress_wanted(o.progress));
        BearingsSequence q = simulate_bearings(s, seed);
        bar.tick();
        bar.finish();
        ensure_dir(o.out);
        write_text_atomic(join_path(o.out, "truth.csv"), [&](std::ostream &os) {
            CsvWriter w(os);
            w.field("k").field("x").field("vx").field("y").field("vy").end_row();
            for (std::size_t k = 0; k < q.truth.size(); ++k) {
                w.field(static_cast<int>(k + 1));
                for (double v : q.truth[k])
                    w.field(v);
                w.end_row();
            }
        });
        write_text_atomic(join_path(o.out, "bearings.csv"), [&](std::ostream &os) {
            CsvWriter w(os);
            w.field("k").field("z").end_row();
            for (std::size_t k = 0; k < q.z.size(); ++k)
                w.field(static_cast<int>(k + 1)).field(q.z[k]).end_row();
        });
        write_json_atomic(join_path(o.out, "sequence.json"),
                          {{"scenario", s.raw}, {"seed", seed}, {"steps", s.steps},
                           {"measurements", "bearings.csv"}, {"truth", "truth.csv"}});
        if (!o.quiet)
            std::printf("pft sim: %d bearings (seed %llu) -> %s/bearings.csv, truth.csv, sequence.json\n",
                        s.steps, static_cast<unsigned long long>(seed), o.out.c_str());
        return 0;
    }

    int run(const Options &o) override
    {
        // the sequence: a `pft sim` directory (bearings.csv, optional truth.csv)
        std::string dir = o.sequence;
        BearingsScenario s = load(o);
        uint64_t seed = o.seed ? *o.seed : s.base_seed;
        std::string side = join_path(dir, "sequence.json");
        if (std::ifstream(side).good()) {
            json sj = load_json_file(side);
            if (!o.seed && sj.contains("seed"))
                seed = sj["seed"].get<uint64_t>();
        }
        bool have_truth = false;
        BearingsSequence q = read_sequence(dir, have_truth);
        std::string out = o.out.empty() ? "pft_run_out" : o.out;
        ensure_dir(out);
        uint32_t n = s.table_particles;
        std::printf("pft run: %zu bearings from %s, N = %u, filter seed %llu, %s\n", q.z.size(), dir.c_str(), n,
                    static_cast<unsigned long long>(seed), numeric_name());
        Progress bar(s.filters.size(), "run", progress_wanted(o.progress));
        for (const auto &spec : s.filters) {
            BearingsFilter bf(s, spec, n);
            PassResult p = bf.pass(q, seed);
            bar.tick();
            std::string file = join_path(out, "estimates_" + spec.label + ".csv");
            write_text_atomic(file, [&](std::ostream &os) {
                CsvWriter w(os);
                w.field("k").field("x").field("vx").field("y").field("vy").end_row();
                for (std::size_t k = 0; k < p.est.size(); ++k) {
                    w.field(static_cast<int>(k + 1));
                    for (double v : p.est[k])
                        w.field(v);
                    w.end_row();
                }
            });
            double se = 0;
            for (std::size_t k = 0; k < p.ex.size(); ++k)
                se += p.ex[k] * p.ex[k] + p.ey[k] * p.ey[k];
            std::printf("  %-10s -> %s", spec.label.c_str(), file.c_str());
            if (have_truth)
                std::printf("   RMS radial error %s", fmt(std::sqrt(se / p.ex.size())).c_str());
            std::printf("\n");
        }
        return 0;
    }

    int demo(const Options &o) override
    {
        BearingsScenario s = load(o);
        uint64_t seed = o.seed ? *o.seed : s.base_seed;
        BearingsSequence q = simulate_bearings(s, seed);
        uint32_t n = s.table_particles;
        std::printf("pft demo: %s\n  seed %llu, N = %u\n\n  %3s %8s %8s", describe(s).c_str(),
                    static_cast<unsigned long long>(seed), n, "k", "x", "y");
        std::vector<PassResult> res;
        {
            Progress bar(s.filters.size(), "demo", progress_wanted(o.progress));
            for (const auto &spec : s.filters) {
                BearingsFilter bf(s, spec, n);
                res.push_back(bf.pass(q, seed));
                bar.tick();
            }
        }
        for (const auto &spec : s.filters)
            std::printf(" %17s", (spec.label + " x/y").c_str());
        std::printf("\n");
        for (int k = 0; k < s.steps; ++k) {
            std::printf("  %3d %8s %8s", k + 1, fmt(q.truth[k][0]).c_str(), fmt(q.truth[k][2]).c_str());
            for (const auto &r : res)
                std::printf(" %8s %8s", fmt(r.est[k][0]).c_str(), fmt(r.est[k][2]).c_str());
            std::printf("\n");
        }
        return 0;
    }

    int selftest(const Options &) override
    {
        int fails = 0;
        auto check = [&](bool ok, const std::string &what) {
            if (!ok) {
                std::printf("pf_bearings selftest: FAIL: %s\n", what.c_str());
                ++fails;
            }
        };
        // 1. the library's innovation and log-likelihood against double formulas
        BearingsScenario s;
        pft_pf_bearings_config_t c = bearings_config(s, 0.0);
        pft_pf_bearings_model_t m;
        pft_pf_model_t iface;
        check(pft_pf_bearings_model_init(&m, &c, &iface) == PFT_OK, "model init");
#ifdef PFT_NUMERIC_Q16
        const double tol_e = 1e-4;
#else
        const double tol_e = 2e-6;
#endif
        std::mt19937_64 rng(123);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        double worst_e = 0, worst_l = 0;
        for (int i = 0; i < 2000; ++i) {
            double x = 800 * u(rng), y = 800 * u(rng), z = 3.14159 * u(rng);
            pft_real_t st[4] = {to_real(x), 0, to_real(y), 0};
            double xr = from_real(st[0]), yr = from_real(st[2]), zr = from_real(to_real(z));
            double e_ref = wrap_pi(zr - std::atan2(yr, xr));
            double e = from_real(pft_pf_bearings_innovation(st, to_real(z)));
            double d = std::fabs(e - e_ref);
            d = std::min(d, std::fabs(d - 2 * 3.14159265358979323846));
            worst_e = std::max(worst_e, d);
            double sd = std::fabs(e_ref) / s.r_sd;
            double l_ref = sd <= s.ll_clip ? -0.5 * sd * sd : -(s.ll_clip * sd - 0.5 * s.ll_clip * s.ll_clip);
            double l = from_real(pft_pf_bearings_loglik(&m, st, to_real(z)));
            double tol_l = 3e-3 * std::fabs(l_ref) + (numeric_name() == std::string("q16") ? 0.02 * (sd + 1) : 1e-4);
            worst_l = std::max(worst_l, std::fabs(l - l_ref) / tol_l);
        }
        check(worst_e <= tol_e, "innovation error " + fmt_e(worst_e) + " > " + fmt_e(tol_e));
        check(worst_l <= 1.0, "log-likelihood error ratio " + fmt_e(worst_l));
        // 2. the default scenario gives the library's default configuration exactly
        pft_pf_bearings_config_t d;
        pft_pf_bearings_config_default(&d, 1000);
        bool same = d.q_sd == c.q_sd && d.r_sd == c.r_sd && d.ll_clip == c.ll_clip;
        for (int i = 0; i < 4; ++i)
            same = same && d.prior_mean[i] == c.prior_mean[i] && d.prior_sd[i] == c.prior_sd[i];
        check(same, "default scenario != pft_pf_bearings_config_default(1000)");
        // 3. noise-free truth is the straight line
        BearingsScenario s2;
        s2.truth_noise = false;
        BearingsSequence q = simulate_bearings(s2, 1);
        check(std::fabs(q.truth.back()[0] - (s2.x0[0] + 24 * s2.x0[1])) < 1e-12 &&
                  std::fabs(q.truth.back()[2] - (s2.x0[2] + 24 * s2.x0[3])) < 1e-12,
              "noise-free truth");
        // 4. determinism of the simulator
        BearingsSequence a = simulate_bearings(s, 5), b = simulate_bearings(s, 5);
        check(a.z == b.z, "simulator determinism");
        std::printf("pf_bearings selftest: %s (innovation err %s rad, loglik err/tol %s)\n",
                    fails ? "FAILED" : "passed", fmt_e(worst_e).c_str(), fmt_e(worst_l).c_str());
        return fails;
    }
};

PFT_REGISTER_KIND("pf_bearings", BearingsHandler);
PFT_REGISTER_KIND_ALIAS("bearings", "pf_bearings", pf_bearings);

}  // namespace

}  // namespace pft::host::pf
