// The "pf_tbd" kind (formerly "apf_tbd", still accepted): the particle-filter engines of
// pft_pf.h over the TBD pixel likelihood
// (pft_pf_tbd_model_t) on a single-target TBD scenario of the tbd module, against each other and
// against the tbd module's RBPF-TBD, at equal particle counts and at equal compute.
//
// Scenario file:
//   {"kind": "pf_tbd", "name": ..., "description": ...,
//    "base": "../tbd/single_5db.json",          // a "tbd" scenario (relative to this file)
//    "filters": [{"label": "APF-TBD 6000", "engine": "apf", "particles": 6000},
//                {"label": "PF-TBD eq. time", "engine": "sir", "match_time_of": "APF-TBD 6000"},
//                {"label": "RBPF-TBD 6000", "engine": "rbpf", "particles": 6000}, ...],
//    "calibration_runs": 3,                       // sequences timed for "match_time_of"
//    "eval": {"runs": 100, "base_seed": 1}}
// The sequences, the truth, the decision rule (P > theta1; a track is a maximal run of such
// frames) and the metrics are the tbd module's (tbd::simulate, tbd::evaluate_run,
// tbd::summarize), so the numbers are comparable with `pft eval` of the base scenario.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "../common/campaign.hpp"
#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../common/output.hpp"
#include "../common/parallel.hpp"
#include "../common/plot.hpp"
#include "../common/progress.hpp"
#include "../common/registry.hpp"
#include "../tbd/metrics.hpp"
#include "../tbd/scenario.hpp"
#include "../tbd/sim.hpp"
#include "../tbd/tracker.hpp"
#include "pf_runner.hpp"

extern "C" {
#include "pft/pft_pf_models.h"
}

using nlohmann::json;
namespace fs = std::filesystem;

namespace pft::host::pf {

namespace {

using tbd::from_real;
using tbd::numeric_name;

struct PfTbdScenario {
    std::string file, name, description, base_file;
    tbd::Scenario base;
    std::vector<EngineSpec> filters;
    unsigned calibration_runs = 3;
    unsigned runs = 100;
    uint64_t base_seed = 1;
    json raw;
};

PfTbdScenario parse(const json &j, const std::string &file)
{
    Field root(j, file);
    root.only({"kind", "name", "description", "base", "filters", "calibration_runs", "eval"});
    PfTbdScenario s;
    s.file = file;
    s.raw = j;
    s.name = root.string_or("name", "");
    s.description = root.string_or("description", "");
    std::string b = root.string("base");
    fs::path bp(b);
    if (bp.is_relative())
        bp = fs::path(file).parent_path() / bp;
    s.base_file = bp.lexically_normal().string();
    s.base = tbd::parse_scenario(load_json_file(s.base_file), s.base_file);
    if (s.base.targets.size() != 1)
        root.at("base").fail("a single-target tbd scenario is needed");
    s.base.filter.mode = "single";
    Field fl = root.at("filters");
    for (std::size_t i = 0; i < fl.size(); ++i)
        s.filters.push_back(parse_engine(fl.at(i), true));
    if (s.filters.empty())
        fl.fail("at least one filter");
    for (std::size_t i = 0; i < s.filters.size(); ++i) {
        for (std::size_t k = 0; k < i; ++k)
            if (s.filters[i].label == s.filters[k].label)
                fl.at(i).fail("duplicate label \"" + s.filters[i].label + "\"");
        const std::string &m = s.filters[i].match_time_of;
        if (!m.empty()) {
            auto it = std::find_if(s.filters.begin(), s.filters.end(),
                                   [&](const EngineSpec &e) { return e.label == m; });
            bool ok = false;
            for (std::size_t k = 0; k < s.filters.size(); ++k)
                ok = ok || (s.filters[k].label == m && s.filters[k].particles > 0);
            if (!ok)
                fl.at(i).fail("match_time_of: no filter labelled \"" + m + "\" with a particle count");
            (void)it;
        }
    }
    s.calibration_runs = static_cast<unsigned>(root.integer_in("calibration_runs", 10, 1, 1000));
    if (root.has("eval")) {
        Field e = root.at("eval");
        e.only({"runs", "base_seed"});
        s.runs = static_cast<unsigned>(e.integer_in("runs", 100, 1, 10000000));
        s.base_seed = static_cast<uint64_t>(e.integer_in("base_seed", 1, 0, INT64_MAX));
    }
    return s;
}

/** One filter of the comparison bound to a particle count; runs whole sequences. */
class TbdFilter {
public:
    TbdFilter(const tbd::Scenario &s, const EngineSpec &e, uint32_t n) : s_(s), e_(e), n_(n) {}

    /** Filters the sequence (filter seed = the tbd module's for this run); adds the update
     *  time to ns. */
    std::vector<tbd::FrameOut> pass(const tbd::Sequence &q, uint64_t seed, double &ns)
    {
        std::vector<tbd::FrameOut> out;
        out.reserve(q.frames);
        if (e_.engine == "rbpf") {
            tbd::Scenario s2 = s_;
            s2.filter.kind = "rbpf";
            s2.filter.mode = "single";
            s2.filter.particles = n_;
            tbd::Tracker tr(tbd::make_config(s2, seed), true);
            for (int k = 0; k < q.frames; ++k) {
                auto t0 = std::chrono::steady_clock::now();
                out.push_back(tr.update_f32(q.images[k].data(), static_cast<uint32_t>(k + 1)));
                ns += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
            }
            return out;
        }
        pft_tbd_config_t cfg = tbd::make_config(s_, seed);
        if (!model_) {
            model_ = std::make_unique<pft_pf_tbd_model_t>();
            mwork_.assign(pft_pf_tbd_model_workspace_size(&cfg) / 8 + 1, 0);
            if (pft_pf_tbd_model_init(model_.get(), &cfg, mwork_.data(), mwork_.size() * 8, &iface_) != PFT_OK)
                throw InputError("pft_pf_tbd_model_init refused the configuration of " + s_.file);
            (void)pft_pf_tbd_model_set_budget(model_.get(), e_.budget);
            runner_ = std::make_unique<PfRunner>(engine_config(e_, n_, cfg.seed), iface_);
        }
        runner_->reset(cfg.seed); // also the model's reset hook: frame 1 is a first frame again
        bool present = false;
        uint32_t next_id = 1, cur_id = 0, cur_first = 0;
        const double theta1 = from_real(cfg.theta1);
        for (int k = 0; k < q.frames; ++k) {
            pft_frame_t f{};
            f.data = q.images[k].data();
            f.width = static_cast<uint16_t>(q.width);
            f.height = static_cast<uint16_t>(q.height);
            f.stride_bytes = static_cast<uint32_t>(q.width) * 4u;
            f.format = PFT_PIX_F32;
            f.seq = static_cast<uint32_t>(k + 1);
            auto t0 = std::chrono::steady_clock::now();
            runner_->update(&f);
            ns += std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
            std::vector<double> e = runner_->estimate();
            // the single-filter decision rule of tbd::Tracker: a track is a run of P > theta1
            tbd::FrameOut o;
            uint32_t fr = static_cast<uint32_t>(k + 1);
            o.frame = fr;
            o.search_p = e[PFT_PF_TBD_E];
            o.search_x = e[PFT_PF_TBD_X];
            o.search_y = e[PFT_PF_TBD_Y];
            o.search_valid = true;
            bool now = o.search_p > theta1;
            if (now && !present) {
                cur_id = next_id++;
                cur_first = fr;
                o.events.push_back({PFT_TBD_EV_CONFIRMED, cur_id, fr, o.search_x, o.search_y});
            } else if (!now && present) {
                o.events.push_back({PFT_TBD_EV_ENDED, cur_id, fr, o.search_x, o.search_y});
            }
            present = now;
            if (now) {
                tbd::TrackOut t;
                t.id = cur_id;
                t.x = o.search_x;
                t.y = o.search_y;
                t.vx = e[PFT_PF_TBD_VX];
                t.vy = e[PFT_PF_TBD_VY];
                t.intensity = e[PFT_PF_TBD_I];
                t.p_exist = o.search_p;
                t.first_frame = cur_first;
                o.tracks.push_back(t);
            }
            out.push_back(o);
        }
        return out;
    }
    std::size_t workspace_bytes() const
    {
        return runner_ ? runner_->workspace_bytes() + mwork_.size() * 8 : 0;
    }

private:
    const tbd::Scenario &s_;
    EngineSpec e_;
    uint32_t n_;
    std::unique_ptr<pft_pf_tbd_model_t> model_;
    std::vector<uint64_t> mwork_;
    pft_pf_model_t iface_{};
    std::unique_ptr<PfRunner> runner_;
};

std::string fmt(double v, int prec = 3)
{
    return fixed_text(v, prec, "-");
}

double jnum(const json &j, const char *key)
{
    auto it = j.find(key);
    return (it != j.end() && it->is_number()) ? it->get<double>() : NAN;
}

double median_of(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n == 0 ? NAN : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/** Median time per frame of two filters measured alternately (A, B, A, B, ... one sequence
 *  each), so that load changes on a shared machine hit both alike. */
std::pair<double, double> paired_times(const PfTbdScenario &s, const EngineSpec &a, uint32_t na,
                                       const EngineSpec &b, uint32_t nb, unsigned runs)
{
    TbdFilter fa(s.base, a, na), fb(s.base, b, nb);
    std::vector<double> ta, tb;
    for (unsigned r = 0; r < runs; ++r) {
        tbd::Sequence q = tbd::simulate(s.base, s.base_seed + 1000 + r);
        double x = 0, y = 0;
        fa.pass(q, s.base_seed + 1000 + r, x);
        fb.pass(q, s.base_seed + 1000 + r, y);
        ta.push_back(x / q.frames);
        tb.push_back(y / q.frames);
    }
    return {median_of(ta), median_of(tb)};
}

/** Fills the particle counts of "match_time_of" filters: N = N_ref t_ref / t_this(N_ref),
 *  then one refinement at that N (time is not exactly linear in N). */
json calibrate(PfTbdScenario &s, bool quiet)
{
    json cal = json::object();
    for (auto &e : s.filters) {
        if (e.match_time_of.empty())
            continue;
        const EngineSpec *ref = nullptr;
        for (const auto &r : s.filters)
            if (r.label == e.match_time_of)
                ref = &r;
        auto [t_ref, t_this] = paired_times(s, *ref, ref->particles, e, ref->particles, s.calibration_runs);
        double n = std::round(ref->particles * t_ref / t_this);
        uint32_t n1 = static_cast<uint32_t>(std::clamp(n, 1.0, static_cast<double>(PFT_CFG_MAX_PARTICLES)));
        auto [t_ref2, t_new] = paired_times(s, *ref, ref->particles, e, n1, s.calibration_runs);
        n = std::round(n1 * t_ref2 / t_new);
        e.particles = static_cast<uint32_t>(std::clamp(n, 1.0, static_cast<double>(PFT_CFG_MAX_PARTICLES)));
        cal[e.label] = {{"match_time_of", ref->label}, {"reference_particles", ref->particles},
                        {"reference_ns_per_frame", t_ref}, {"ns_per_frame_at_reference_n", t_this},
                        {"first_guess_particles", n1}, {"reference_ns_per_frame_2", t_ref2},
                        {"ns_per_frame_at_first_guess", t_new}, {"particles", e.particles},
                        {"calibration_runs", s.calibration_runs},
                        {"method", "median per-frame time over calibration_runs sequences, the two filters alternating"}};
        if (!quiet)
            std::printf("  equal compute: %s ~ %s: %.0f vs %.0f us/frame at N=%u -> N = %u\n", e.label.c_str(),
                        ref->label.c_str(), t_ref / 1000.0, t_this / 1000.0, ref->particles, e.particles);
    }
    return cal;
}

void plots(const PfTbdScenario &s, const json &sum, const std::string &dir)
{
    std::string tail = " - " + (s.name.empty() ? std::string("pf_tbd") : s.name) + ", " + numeric_name() +
                       ", " + std::to_string(sum["runs"].get<unsigned>()) + " runs";
    const tbd::Target &tg = s.base.targets[0];
    for (int fig = 0; fig < 2; ++fig) {
        PlotSpec p;
        p.title = (fig == 0 ? std::string("Mean existence probability") : std::string("RMSE per frame (correct points)")) + tail;
        p.xlabel = "frame";
        p.ylabel = fig == 0 ? "P(E = 1)" : "RMSE (px)";
        p.ymin = 0.0;
        if (fig == 0)
            p.ymax = 1.05;
        for (const json &f : sum["filters"]) {
            PlotSeries ser;
            ser.label = f["label"].get<std::string>() + " (N=" + std::to_string(f["particles"].get<uint32_t>()) + ")";
            const json &arr = f[fig == 0 ? "existence_probability" : "rmse_per_frame"];
            for (std::size_t k = 0; k < arr.size(); ++k) {
                ser.x.push_back(static_cast<double>(k + 1));
                ser.y.push_back(arr[k].is_number() ? arr[k].get<double>() : NAN);
            }
            p.series.push_back(ser);
        }
        PlotSeries tr;
        tr.color = cv::Scalar(150, 150, 150);
        tr.dashed = true;
        tr.thickness = 1;
        if (fig == 0) {
            tr.label = "truth present";
            for (int k = 1; k <= s.base.frames; ++k) {
                tr.x.push_back(k);
                tr.y.push_back(k >= tg.birth && k <= tg.death ? 1.0 : 0.0);
            }
        } else {
            tr.label = "PCRLB";
            const json &f0 = sum["filters"][0]["pcrlb_per_frame"];
            for (std::size_t k = 0; k < f0.size(); ++k) {
                tr.x.push_back(static_cast<double>(k + 1));
                tr.y.push_back(f0[k].is_number() ? f0[k].get<double>() : NAN);
            }
        }
        p.series.push_back(tr);
        save_plot_png(p, join_path(dir, fig == 0 ? "existence.png" : "rmse.png"));
    }
}

/** Every filter of the comparison on every run's sequence. */
struct TbdEvalRuns {
    std::vector<std::vector<tbd::RunEval>> res;  ///< res[filter][run]
    std::vector<std::vector<double>> ns;         ///< update time per filter and run
};

/** One run (the sequence of `seed`) through every filter: results into column i. */
void run_one(const PfTbdScenario &s, uint64_t seed, std::size_t i, TbdEvalRuns &er)
{
    tbd::Sequence q = tbd::simulate(s.base, seed);
    for (std::size_t f = 0; f < s.filters.size(); ++f) {
        TbdFilter flt(s.base, s.filters[f], s.filters[f].particles);
        std::vector<tbd::FrameOut> out = flt.pass(q, seed, er.ns[f][i]);
        er.res[f][i] = tbd::evaluate_run(s.base, q.truth, out, true);
        er.res[f][i].seed = seed;
    }
}

/** Run i's record in a partial summary (every filter's tbd record and update time), and back. */
json run_to_json(const TbdEvalRuns &er, std::size_t i)
{
    json fl = json::array();
    for (std::size_t f = 0; f < er.res.size(); ++f) {
        json r = tbd::run_to_json(er.res[f][i]);
        r["ns"] = er.ns[f][i];
        fl.push_back(r);
    }
    return {{"filters", fl}};
}

void run_from_json(const json &j, std::size_t i, TbdEvalRuns &er)
{
    const json &fl = j.at("filters");
    if (fl.size() != er.res.size())
        throw InputError("merge: a run record has " + std::to_string(fl.size()) + " filters, the scenario " +
                         std::to_string(er.res.size()));
    for (std::size_t f = 0; f < er.res.size(); ++f) {
        er.res[f][i] = tbd::run_from_json(fl[f]);
        er.ns[f][i] = fl[f].at("ns").get<double>();
    }
}

/** Mean and standard error of the mean (NaN when undefined). */
std::pair<double, double> mean_se(const std::vector<double> &v)
{
    double m = 0, q = 0;
    for (double x : v)
        m += x / v.size();
    for (double x : v)
        q += (x - m) * (x - m);
    double se = v.size() > 1 ? std::sqrt(q / (v.size() - 1) / v.size()) : NAN;
    return std::make_pair(v.empty() ? NAN : m, se);
}

/** The summary of filter f: the tbd measures, time per frame, standard errors and the paired
 *  differences against filter 0 on the same sequences. */
json filter_json(const PfTbdScenario &s, const TbdEvalRuns &er, std::size_t f, unsigned runs)
{
    std::vector<double> app, cor, dcor, dapp;
    for (unsigned r = 0; r < runs; ++r) {
        const tbd::TargetRun &t = er.res[f][r].targets[0];
        const tbd::TargetRun &t0 = er.res[0][r].targets[0];
        cor.push_back(t.correct);
        dcor.push_back(static_cast<double>(t.correct) - t0.correct);
        if (t.detected)
            app.push_back(t.appear_delay);
        if (t.detected && t0.detected)
            dapp.push_back(t.appear_delay - t0.appear_delay);
    }
    auto [app_m, app_se] = mean_se(app);
    auto [cor_m, cor_se] = mean_se(cor);
    auto [dcor_m, dcor_se] = mean_se(dcor);
    auto [dapp_m, dapp_se] = mean_se(dapp);
    (void)app_m;
    (void)cor_m;
    json sm = tbd::summarize(s.base, er.res[f], true);
    const json &t = sm["targets"][0];
    const json &av = sm["averaged"];
    double tot = 0;
    for (double v : er.ns[f])
        tot += v;
    return {
        {"label", s.filters[f].label},
        {"engine", s.filters[f].engine},
        {"particles", s.filters[f].particles},
        {"runs", runs},
        {"matched_time_of", s.filters[f].match_time_of.empty() ? json(nullptr) : json(s.filters[f].match_time_of)},
        {"appearance_delay", t["appearance_delay"]},
        {"detected_runs", t["detected_runs"]},
        {"disappearance_delay", t["disappearance_delay"]},
        {"correct_frames", t["correct_frames"]},
        {"true_frames", t["true_frames"]},
        {"rmse", t["rmse"]},
        {"rmse_all_assigned", t["rmse_all_assigned"]},
        {"pcrlb", t["pcrlb"]},
        {"pcrlb_matched", t["pcrlb_matched"]},
        {"false_tracks", sm["averaged"]["false_tracks"]},
        {"false_point_fraction", sm["averaged"]["false_point_fraction"]},
        {"ns_per_step", tot / (static_cast<double>(runs) * s.base.frames)},
        {"existence_probability", t["existence_probability"]},
        {"rmse_per_frame", t["rmse_per_frame"]},
        {"pcrlb_per_frame", t["pcrlb_per_frame"]},
        {"appearance_delay_se", std::isfinite(app_se) ? json(app_se) : json(nullptr)},
        {"correct_frames_se", std::isfinite(cor_se) ? json(cor_se) : json(nullptr)},
        {"paired_vs", s.filters[0].label},
        {"correct_frames_minus_first", f ? json(dcor_m) : json(nullptr)},
        {"correct_frames_minus_first_se", f && std::isfinite(dcor_se) ? json(dcor_se) : json(nullptr)},
        {"appearance_delay_minus_first", f && std::isfinite(dapp_m) ? json(dapp_m) : json(nullptr)},
        {"appearance_delay_minus_first_se", f && std::isfinite(dapp_se) ? json(dapp_se) : json(nullptr)},
        {"engine_settings", s.filters[f].engine == "rbpf" ? json(nullptr) : engine_json(s.filters[f])},
        {"detection_rate", t["detection_rate"]},
        {"appearance_delay_all_runs", t["appearance_delay_all_runs"]},
        {"gospa", av["gospa"]},
        {"gospa_localisation", av["gospa_localisation"]},
        {"gospa_missed", av["gospa_missed"]},
        {"gospa_false", av["gospa_false"]},
        {"gospa_missed_count", av["gospa_missed_count"]},
        {"gospa_false_count", av["gospa_false_count"]},
        {"ospa", av["ospa"]},
        {"gospa_per_frame", av["gospa_per_frame"]},
        {"ospa_per_frame", av["ospa_per_frame"]},
    };
}

/** The console table of `pft eval`. */
void print_eval(const PfTbdScenario &s, const json &filters)
{
    // appear: over detecting runs; app.all: over all runs, a miss counting the whole life;
    // det.: detection rate; GOSPA (c, p of the summary) over all frames and runs
    std::printf("\n  %-22s %6s %8s %8s %6s %8s %8s %8s %8s %7s %7s %10s\n", "filter", "N", "appear", "app.all",
                "det.", "correct", "RMSE", "PCRLB", "matched", "false", "GOSPA", "us/frame");
    for (const json &f : filters)
        std::printf("  %-22s %6u %8s %8s %6s %8s %8s %8s %8s %7s %7s %10s\n", f["label"].get<std::string>().c_str(),
                    f["particles"].get<uint32_t>(), fmt(jnum(f, "appearance_delay"), 2).c_str(),
                    fmt(jnum(f, "appearance_delay_all_runs"), 2).c_str(), fmt(jnum(f, "detection_rate"), 2).c_str(),
                    fmt(jnum(f, "correct_frames"), 2).c_str(),
                    fmt(jnum(f, "rmse")).c_str(), fmt(jnum(f, "pcrlb")).c_str(),
                    fmt(jnum(f, "pcrlb_matched")).c_str(), fmt(jnum(f, "false_tracks"), 2).c_str(),
                    fmt(jnum(f, "gospa")).c_str(), fmt(jnum(f, "ns_per_step") / 1000.0, 0).c_str());
    std::printf("\n  paired against %s (same sequences; mean difference +- standard error):\n",
                s.filters[0].label.c_str());
    for (std::size_t f = 1; f < s.filters.size(); ++f) {
        const json &j = filters[f];
        std::printf("  %-22s correct frames %+.2f +- %.2f, appearance delay %s +- %s\n",
                    j["label"].get<std::string>().c_str(), jnum(j, "correct_frames_minus_first"),
                    jnum(j, "correct_frames_minus_first_se"),
                    fmt(jnum(j, "appearance_delay_minus_first"), 2).c_str(),
                    fmt(jnum(j, "appearance_delay_minus_first_se"), 2).c_str());
    }
}

/** The settings part of summary.json (common header, then the pf_tbd settings). `cal` is the
 *  equal-compute calibration (measured; empty when every filter has a fixed count). */
json pf_tbd_head(const Options &o, const PfTbdScenario &s, const Campaign &c, unsigned threads,
                 const CampaignTiming &t, const json &cal)
{
    SummaryHead h;
    h.kind = "pf_tbd";
    h.scenario = s.name;
    h.scenario_file = s.file;
    h.description = s.description;
    h.tag = o.tag.empty() ? s.name + " " + numeric_name() : o.tag;
    h.scenario_json = s.raw;
    json head = summary_header(o, c, h, threads, t);
    head["timing"]["note"] = "ns_per_step: per frame, steady_clock around the filter update inside the threaded eval";
    head["base_scenario_file"] = s.base_file;
    head["snr_db"] = s.base.snr_db;
    head["noise_sigma"] = s.base.noise_sigma;
    head["frames"] = s.base.frames;
    head["calibration"] = cal;
    json particles = json::array();
    for (const auto &e : s.filters)
        particles.push_back({{"label", e.label}, {"particles", e.particles}});
    head["filter_particles"] = particles;
    head["gospa_c"] = tbd::gospa_cutoff(s.base);
    head["gospa_p"] = s.base.eval.gospa_p;
    head["gospa_alpha"] = 2;
    head["tbd_filter_settings"] = tbd::config_to_json(tbd::make_config(s.base, c.base_seed));
    head["scenario_json"] = s.raw;
    return head;
}

/** Measures of every filter, summary.json, plots and table (eval and merge). */
int finish(const Options &o, const PfTbdScenario &s, const TbdEvalRuns &er, json head, const std::string &out_dir)
{
    const unsigned runs = static_cast<unsigned>(er.res.empty() ? 0 : er.res[0].size());
    json filters = json::array();
    for (std::size_t f = 0; f < s.filters.size(); ++f)
        filters.push_back(filter_json(s, er, f, runs));
    head["filters"] = filters;
    write_json_atomic(join_path(out_dir, "summary.json"), head);
    plots(s, head, out_dir);
    if (!o.quiet) {
        print_eval(s, filters);
        std::printf("\n  %.1f s wall; wrote %s/summary.json, existence.png, rmse.png\n",
                    head["timing"]["wall_s"].get<double>(), out_dir.c_str());
    }
    return 0;
}

class PfTbdHandler : public KindHandler {
    PfTbdScenario load(const Options &o)
    {
        if (!o.filter_kind.empty() || !o.preset.empty())
            throw InputError("kind \"pf_tbd\": --filter and --preset do not apply (the scenario's \"filters\" list them)");
        PfTbdScenario s = parse(o.scenario, o.scenario_path);
        if (o.gospa_c)
            s.base.eval.gospa_c = *o.gospa_c;
        if (o.gospa_p)
            s.base.eval.gospa_p = *o.gospa_p;
        if (o.particles)
            for (auto &e : s.filters)
                if (e.match_time_of.empty())
                    e.particles = o.particles;
        return s;
    }

public:
    int eval(const Options &o) override
    {
        PfTbdScenario s = load(o);
        Campaign c = make_campaign(o.runs ? o.runs : s.runs, o.seed ? *o.seed : s.base_seed, o.shard);
        unsigned threads = resolve_threads(o.threads);
        std::string out_dir = o.out.empty() ? "pft_eval_" + (s.name.empty() ? std::string("pf_tbd") : s.name) +
                                                  "_" + numeric_name()
                                            : o.out;
        if (c.partial())
            for (const auto &e : s.filters)
                if (!e.match_time_of.empty())
                    throw InputError("--shard: filter \"" + e.label + "\" has match_time_of, whose particle count is "
                                     "calibrated by timing and would differ between shards; calibrate once "
                                     "(pft bench prints the counts) and give \"particles\"");
        ensure_dir(out_dir);
        if (!o.quiet)
            std::printf("pft eval: %s (base %s, SNR %.1f dB, sigma %.3f, %d frames, target frames %d-%d), %s\n",
                        s.name.c_str(), s.base_file.c_str(), s.base.snr_db, s.base.noise_sigma, s.base.frames,
                        s.base.targets[0].birth, s.base.targets[0].death, numeric_name());
        json cal = calibrate(s, o.quiet);
        const std::size_t nf = s.filters.size();
        if (!o.quiet)
            std::printf("  %zu runs, seeds %llu..%llu, %u threads\n", c.count(),
                        static_cast<unsigned long long>(c.seed(c.first)),
                        static_cast<unsigned long long>(c.seed(c.end - 1)), threads);
        TbdEvalRuns er;
        er.res.assign(nf, std::vector<tbd::RunEval>(c.count()));
        er.ns.assign(nf, std::vector<double>(c.count(), 0.0));
        CampaignTiming t = run_campaign(c, threads, progress_wanted(o.progress), "eval",
                                        [&](std::size_t run, uint64_t seed) { run_one(s, seed, run - c.first, er); });
        json head = pf_tbd_head(o, s, c, threads, t, cal);
        if (c.partial()) {
            json recs = json::array();
            for (std::size_t i = 0; i < c.count(); ++i)
                recs.push_back(run_to_json(er, i));
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
        PfTbdScenario s = load(eo);
        TbdEvalRuns er;
        er.res.assign(s.filters.size(), std::vector<tbd::RunEval>(m.runs.size()));
        er.ns.assign(s.filters.size(), std::vector<double>(m.runs.size(), 0.0));
        for (std::size_t i = 0; i < m.runs.size(); ++i)
            run_from_json(m.runs[i], i, er);
        ensure_dir(o.out);
        json head = pf_tbd_head(eo, s, m.campaign, m.threads, m.timing, json::object());
        add_merge_fields(head, m);
        return finish(eo, s, er, head, o.out);
    }

    int bench(const Options &o) override
    {
        PfTbdScenario s = load(o);
        unsigned runs = o.runs ? o.runs : 3;
        int frames = o.frames ? static_cast<int>(o.frames) : s.base.frames;
        json cal = calibrate(s, o.quiet);
        json entries = json::array();
        if (!o.quiet)
            std::printf("pft bench: %s, %u runs of %d frames, one thread, %s; the filters take turns within each "
                        "run (round robin)\n  %-22s %6s %12s %12s %14s\n", s.name.c_str(),
                        runs, frames, numeric_name(), "filter", "N", "us/frame min", "us/frame med", "ns/particle");
        // round robin: each run's sequence goes through every filter in turn, so load changes on a
        // shared machine hit them alike; min and median over the runs per filter
        std::vector<std::unique_ptr<TbdFilter>> fl;
        for (const auto &e : s.filters)
            fl.push_back(std::make_unique<TbdFilter>(s.base, e, e.particles));
        std::vector<std::vector<double>> per(fl.size());
        Progress bar(static_cast<std::size_t>(runs) * fl.size(), "bench", progress_wanted(o.progress));
        for (unsigned r = 0; r < runs; ++r) {
            tbd::Sequence q = tbd::simulate(s.base, s.base_seed + 1000 + r, frames);
            for (std::size_t i = 0; i < fl.size(); ++i) {
                double ns = 0;
                fl[i]->pass(q, s.base_seed + 1000 + r, ns);
                per[i].push_back(ns / q.frames);
                bar.tick();
            }
        }
        bar.finish();
        for (std::size_t i = 0; i < fl.size(); ++i) {
            const EngineSpec &e = s.filters[i];
            double t = median_of(per[i]), mn = *std::min_element(per[i].begin(), per[i].end());
            entries.push_back({{"label", e.label}, {"engine", e.engine}, {"particles", e.particles},
                               {"ns_per_frame", t}, {"ns_per_frame_min", mn},
                               {"ns_per_particle_frame", t / e.particles}});
            if (!o.quiet)
                std::printf("  %-22s %6u %12s %12s %14s\n", e.label.c_str(), e.particles, fmt(mn / 1000.0, 1).c_str(),
                            fmt(t / 1000.0, 1).c_str(), fmt(t / e.particles, 1).c_str());
        }
        if (!o.out.empty()) {
            ensure_dir(o.out);
            write_json_atomic(join_path(o.out, "bench.json"),
                              {{"tool", "pft bench"}, {"kind", "pf_tbd"}, {"scenario", s.name},
                               {"numeric", numeric_name()}, {"runs", runs}, {"frames", frames},
                               {"order", "round robin: run r passes one sequence through every filter in turn"},
                               {"calibration", cal}, {"entries", entries}});
        }
        return 0;
    }
};

PFT_REGISTER_KIND("pf_tbd", PfTbdHandler);
PFT_REGISTER_KIND_ALIAS("apf_tbd", "pf_tbd", pf_tbd);

}  // namespace

}  // namespace pft::host::pf
