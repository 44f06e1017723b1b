// The "pte" kind (formerly "radar"): sim, run, eval, bench, demo and selftest for the multi-frame TBD
// comparison of He et al. 2015 (PTE-TBD, sliding DP-TBD, Kalman DBT) on range-time images.
#include <random>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

extern "C" {
#include "pft/pft_port_file.h"
}

#include "../common/campaign.hpp"
#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../common/output.hpp"
#include "../common/parallel.hpp"
#include "../common/plot.hpp"
#include "../common/progress.hpp"
#include "../common/registry.hpp"
#include "../common/scenario_dir.hpp"
#include "image.hpp"
#include "methods.hpp"
#include "metrics.hpp"
#include "scenario.hpp"
#include "sim.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pft::host::pte {

namespace {

using Clock = std::chrono::steady_clock;

Scenario load(const Options &o)
{
    Scenario s = parse_scenario(o.scenario, o.scenario_path);
    if (!o.filter_kind.empty() || o.particles || o.single || !o.preset.empty())
        throw InputError("kind \"pte\" takes no --filter/--particles/--single/--preset (methods come from "
                         "the scenario's eval.methods and methods settings)");
    return s;
}

std::string fmt(double v, int prec = 3)
{
    return fixed_text(v, prec, "-");
}

std::string describe(const Scenario &s)
{
    std::ostringstream os;
    os << (s.name.empty() ? s.file : s.name) << ": " << s.radar.cells << " range cells x " << s.frames
       << " frames (" << s.radar.frame_period * 1e3 << " ms), "
       << (s.clutter() ? "K-clutter SCNR " : "Gaussian noise SNR ") << fmt(s.snr_db, 1) << " dB, "
       << numeric_name() << " build";
    return os.str();
}

/** Runs one method over a sequence; per-frame reports and the summed update time. */
std::vector<std::vector<Report>> run_method(const MethodSpec &spec, const std::vector<std::vector<float>> &z,
                                            double *time_s, const std::vector<bool> *lost = nullptr)
{
    Method m(spec);
    std::vector<std::vector<Report>> out;
    out.reserve(z.size());
    double t = 0.0;
    for (std::size_t k = 0; k < z.size(); ++k) {
        if (lost && k > 0 && (*lost)[k]) {
            out.push_back(out.back());  // a lost frame is not fed: the last output is held
            continue;
        }
        auto t0 = Clock::now();
        const auto &r = m.update(z[k].data(), static_cast<uint32_t>(k));
        t += std::chrono::duration<double>(Clock::now() - t0).count();
        out.push_back(r);
    }
    if (time_s)
        *time_s = t;
    return out;
}

std::vector<MethodSpec> make_specs(const Scenario &s)
{
    std::vector<MethodSpec> v;
    for (const auto &n : s.eval.methods)
        v.push_back(make_spec(s, n));
    return v;
}

void print_table_header()
{
    std::printf("  %-14s %6s %9s %9s %9s %9s %10s\n", "method", "SNR", "Pd", "reliable3", "false", "RMSE",
                "us/frame");
}
void print_row(const std::string &label, double snr, const Counts &c)
{
    std::printf("  %-14s %6s %9s %9s %9s %9s %10s\n", label.c_str(), fmt(snr, 1).c_str(),
                fmt(c.detection_prob()).c_str(), fmt(c.reliable3_prob()).c_str(),
                fmt(c.false_track_prob()).c_str(), fmt(c.rmse()).c_str(), fmt(c.us_per_frame(), 1).c_str());
}

/** Grey-level range for pictures: about -2.5 sigma .. A + 2.5 sigma. */
void grey_range(const Scenario &s, double &lo, double &hi)
{
    lo = -2.5 * s.background.sigma;
    hi = std::max(s.amplitude(), s.background.sigma) + 2.5 * s.background.sigma;
}

/** truth.csv: one row per target and frame, frame,target,range_cell,range_rate_cells_per_frame,
 *  range_m,active (target 1, 2, ... in the scenario's order; active 0 outside the target's
 *  start_s..end_s). */
void write_truth_csv(const std::string &path, const std::vector<std::vector<Truth>> &trs)
{
    write_text_atomic(path, [&](std::ostream &os) {
        CsvWriter w(os);
        w.field("frame").field("target").field("range_cell").field("range_rate_cells_per_frame");
        w.field("range_m").field("active");
        w.end_row();
        std::size_t n = 0;
        for (const auto &tr : trs)
            n = std::max(n, tr.size());
        for (std::size_t k = 0; k < n; ++k)
            for (std::size_t t = 0; t < trs.size(); ++t) {
                if (k >= trs[t].size())
                    continue;
                const Truth &x = trs[t][k];
                w.field(static_cast<int>(k + 1)).field(static_cast<int>(t + 1)).field(x.r).field(x.rdot);
                w.field(x.range_m).field(x.active ? 1 : 0);
                w.end_row();
            }
    });
}

/** Reads truth.csv: the layout above, or the single-target layout of earlier versions
 *  (frame,range_cell,range_rate_cells_per_frame,range_m). Returns [target][frame]. */
std::vector<std::vector<Truth>> read_truth_csv(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open truth file");
    std::vector<std::vector<Truth>> v;
    std::string line;
    int ln = 0;
    bool multi = false;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (++ln == 1) {
            multi = line.rfind("frame,target,", 0) == 0;
            continue;
        }
        if (line.empty())
            continue;
        std::stringstream ss(line);
        std::vector<std::string> c;
        std::string x;
        while (std::getline(ss, x, ','))
            c.push_back(x);
        const std::string layout = multi ? "frame,target,range_cell,range_rate,range_m,active"
                                         : "frame,range_cell,range_rate,range_m";
        if (c.size() != (multi ? 6u : 4u))
            throw InputError(path + ":" + std::to_string(ln) + ": expected " + layout);
        try {
            const long frame = std::stol(c[0]);
            const long target = multi ? std::stol(c[1]) : 1;
            if (frame < 1 || frame > 100000000 || target < 1 || target > 64)
                throw InputError(path + ":" + std::to_string(ln) + ": frame must be 1.. and target 1..64");
            const std::size_t o = multi ? 1u : 0u;
            Truth t;
            t.r = std::stod(c[1 + o]);
            t.rdot = std::stod(c[2 + o]);
            t.range_m = std::stod(c[3 + o]);
            t.active = multi ? std::stol(c[5]) != 0 : true;
            if (v.size() < static_cast<std::size_t>(target))
                v.resize(static_cast<std::size_t>(target));
            auto &tv = v[static_cast<std::size_t>(target - 1)];
            if (tv.size() < static_cast<std::size_t>(frame)) {
                Truth absent;
                absent.active = false;
                absent.r = -1.0;
                tv.resize(static_cast<std::size_t>(frame), absent);
            }
            tv[static_cast<std::size_t>(frame - 1)] = t;
        } catch (const InputError &) {
            throw;
        } catch (const std::exception &) {
            throw InputError(path + ":" + std::to_string(ln) + ": expected " + layout);
        }
    }
    return v;
}

void write_tracks_csv(const std::string &path, const std::vector<std::string> &names,
                      const std::vector<std::vector<std::vector<Report>>> &outs)
{
    write_text_atomic(path, [&](std::ostream &os) {
        CsvWriter w(os);
        w.field("method").field("frame").field("track").field("detected").field("range_cell")
            .field("range_rate").field("variance").field("amplitude").field("score").field("age");
        w.end_row();
        for (std::size_t m = 0; m < names.size(); ++m)
            for (std::size_t k = 0; k < outs[m].size(); ++k)
                for (const Report &r : outs[m][k]) {
                    w.field(names[m]).field(static_cast<int>(k + 1)).field(static_cast<long long>(r.id))
                        .field(r.detected).field(r.pos).field(r.vel).field(r.var).field(r.amplitude)
                        .field(r.score).field(static_cast<long long>(r.age));
                    w.end_row();
                }
    });
}

/** Runs the scenario's methods over z, prints and returns per-method counts, writes the
 *  picture and tracks CSV when dir is not empty. */
json track_and_report(const Scenario &s, const std::vector<std::vector<float>> &z,
                      const std::vector<Truth> *truth, const std::string &dir, const std::string &caption,
                      bool quiet, const std::vector<std::vector<Truth>> *truths = nullptr)
{
    // several targets (a scenario's `targets`): scored together; the picture shows every one
    auto score = [&](const std::vector<std::vector<Report>> &o, bool coasting) {
        if (truths && truths->size() > 1)
            return score_runs(*truths, o, s.radar.cells, s.eval.d_c, coasting);
        return score_run(*truth, o, s.radar.cells, s.eval.d_c, nullptr, coasting);
    };
    std::vector<MethodSpec> specs = make_specs(s);
    std::vector<std::vector<std::vector<Report>>> outs;
    std::vector<std::string> names;
    json res = json::object();
    if (!quiet && truth)
        print_table_header();
    for (const auto &sp : specs) {
        double t = 0.0;
        outs.push_back(run_method(sp, z, &t));
        names.push_back(sp.name);
        json j = {{"label", sp.label()}, {"settings", sp.settings()},
                  {"us_per_frame", t * 1e6 / std::max<std::size_t>(1, z.size())}};
        if (truth) {
            Counts c = score(outs.back(), false);
            c.time_s = t;
            c.frames = static_cast<long long>(z.size());
            j["metrics"] = c.to_json();
            j["metrics_with_coasting"] = score(outs.back(), true).to_json();
            if (!quiet)
                print_row(sp.label(), s.snr_db, c);
        }
        std::map<uint32_t, int> ids;
        for (const auto &f : outs.back())
            for (const Report &r : f)
                ids[r.id]++;
        j["tracks"] = ids.size();
        res[sp.name] = j;
    }
    if (!dir.empty()) {
        double lo, hi;
        grey_range(s, lo, hi);
        std::vector<Panel> panels{{"range-time image", nullptr}};
        for (std::size_t m = 0; m < names.size(); ++m)
            panels.push_back({specs[m].label() + " (" + numeric_name() + ")", &outs[m]});
        std::vector<std::vector<Truth>> one;
        if (truth && !(truths && !truths->empty()))
            one.push_back(*truth);
        save_rangetime_png(join_path(dir, "tracked.png"), z, truths && !truths->empty() ? truths : (truth ? &one : nullptr),
                           panels, lo, hi, caption);
        write_tracks_csv(join_path(dir, "tracks.csv"), names, outs);
    }
    return res;
}

// ------------------------------------------------------------------------- eval helpers
struct SnrResult {
    double snr = 0.0;
    std::map<std::string, Counts> counts;     ///< declared = detected reports
    std::map<std::string, Counts> coasting;   ///< declared = every report
};

/** First SNR of the sweep from which the criterion holds at every higher SNR too. */
json first_reach(const std::vector<SnrResult> &res, const std::string &m,
                 const std::function<bool(const Counts &)> &ok)
{
    for (std::size_t i = 0; i < res.size(); ++i) {
        bool all = true;
        for (std::size_t j = i; j < res.size(); ++j)
            all = all && ok(res[j].counts.at(m));
        if (all)
            return res[i].snr;
    }
    return nullptr;
}

void fig5_plots(const std::string &dir, const Scenario &s, const std::vector<SnrResult> &res, unsigned runs,
                const std::map<std::string, std::string> &labels)
{
    struct Fig {
        const char *file, *title, *ylabel;
        std::function<double(const Counts &)> y;
        std::optional<double> ymax;
        double ref;
    };
    std::vector<Fig> figs = {
        {"fig5a_rmse.png", "(a) RMSE of correct points", "RMSE (range cells)",
         [](const Counts &c) { return c.rmse(); }, std::nullopt, 3.0},
        {"fig5b_detection.png", "(b) detection probability", "detection probability",
         [](const Counts &c) { return c.detection_prob(); }, 1.02, 0.9},
        {"fig5c_reliable3.png", "(c) 3-frame reliable tracking probability", "reliable tracking probability",
         [](const Counts &c) { return c.reliable3_prob(); }, 1.02, 0.9},
        {"fig5d_false.png", "(d) false-track probability", "false-track probability",
         [](const Counts &c) { return c.false_track_prob(); }, 1.02, 0.1}};
    for (const Fig &f : figs) {
        PlotSpec p;
        p.title = std::string(f.title) + " - " + (s.name.empty() ? "pte" : s.name) + ", " +
                  std::to_string(runs) + " runs, " + numeric_name();
        p.xlabel = s.clutter() ? "SCNR (dB)" : "SNR (dB)";
        p.ylabel = f.ylabel;
        p.ymin = 0.0;
        p.ymax = f.ymax;
        for (const auto &m : s.eval.methods) {
            PlotSeries ser;
            ser.label = labels.at(m);
            ser.markers = true;
            for (const auto &r : res) {
                ser.x.push_back(r.snr);
                ser.y.push_back(f.y(r.counts.at(m)));
            }
            p.series.push_back(ser);
        }
        PlotSeries ref;
        ref.label = "paper criterion";
        ref.dashed = true;
        ref.thickness = 1;
        ref.color = cv::Scalar(0, 0, 0);
        ref.x = {res.front().snr, res.back().snr};
        ref.y = {f.ref, f.ref};
        p.series.push_back(ref);
        save_plot_png(p, join_path(dir, f.file));
    }
}

/** gospa_per_frame.png: GOSPA per frame over the runs, one curve per method, at the SNR point
 *  of the sweep nearest the scenario's own SNR (declared points: the detected reports). */
void gospa_plot(const std::string &dir, const Scenario &s, const std::vector<SnrResult> &res, unsigned runs,
                const std::map<std::string, std::string> &labels)
{
    std::size_t at = 0;
    for (std::size_t i = 1; i < res.size(); ++i)
        if (std::fabs(res[i].snr - s.snr_db) < std::fabs(res[at].snr - s.snr_db))
            at = i;
    PlotSpec p;
    p.title = "GOSPA per frame - " + (s.name.empty() ? std::string("pte") : s.name) + ", " +
              (s.clutter() ? "SCNR " : "SNR ") + fmt(res[at].snr, 1) + " dB, " + std::to_string(runs) + " runs, " +
              numeric_name();
    p.xlabel = "frame";
    p.ylabel = "GOSPA (range cells)";
    p.ymin = 0.0;
    for (const auto &m : s.eval.methods) {
        const Counts &c = res[at].counts.at(m);
        PlotSeries ser;
        ser.label = labels.at(m);
        ser.thickness = 1;
        for (std::size_t k = 0; k < c.per_frame.frames(); ++k) {
            ser.x.push_back(static_cast<double>(k + 1));
            ser.y.push_back(c.per_frame.gospa_at(k));
        }
        p.series.push_back(ser);
    }
    save_plot_png(p, join_path(dir, "gospa_per_frame.png"));
}

// ------------------------------------------------------------------------- eval skeleton
/** The SNR points of an eval: the scenario's sweep, else its one SNR. */
std::vector<double> sweep(const Scenario &s)
{
    return s.eval.snr_db.empty() ? std::vector<double>{s.snr_db} : s.eval.snr_db;
}

/** One run (seed) of an eval: per SNR point and method, the counts with the detected reports
 *  as declared points (det) and with every report (all). A partial summary stores these. */
struct RunCounts {
    uint64_t seed = 0;
    std::vector<std::map<std::string, Counts>> det, all;  ///< [SNR point][method]

    json to_json() const
    {
        json pts = json::array();
        for (std::size_t i = 0; i < det.size(); ++i) {
            json p = json::object();
            for (const auto &kv : det[i])
                p[kv.first] = {{"detected", kv.second.raw()}, {"with_coasting", all[i].at(kv.first).raw()}};
            pts.push_back(p);
        }
        return {{"seed", seed}, {"snr_points", pts}};
    }
    static RunCounts from_json(const json &j)
    {
        RunCounts r;
        r.seed = j.at("seed").get<uint64_t>();
        for (const json &p : j.at("snr_points")) {
            r.det.emplace_back();
            r.all.emplace_back();
            for (auto it = p.begin(); it != p.end(); ++it) {
                r.det.back()[it.key()] = Counts::from_raw(it.value().at("detected"));
                r.all.back()[it.key()] = Counts::from_raw(it.value().at("with_coasting"));
            }
        }
        return r;
    }
};

void print_thresholds(const Scenario &s, const std::vector<MethodSpec> &specs)
{
    for (const auto &sp : specs)
        std::printf("  %-14s threshold %.3f%s\n", sp.label().c_str(), sp.threshold,
                    sp.threshold_from_mc ? (s.methods.threshold_background == "scenario"
                                                ? " (background-only Monte Carlo on the scenario's clutter)"
                                                : " (noise-only Monte Carlo)")
                                         : "");
}

/** The settings part of summary.json (the common header, then the pte fields); a partial
 *  summary carries the same, so pft merge can check that its shards belong together. */
json eval_head(const Options &o, const Scenario &s, const Campaign &c, const std::vector<MethodSpec> &specs,
               unsigned threads, const CampaignTiming &t, double mc_s)
{
    SummaryHead h;
    h.kind = "pte";
    h.scenario = s.name;
    h.scenario_file = s.file;
    h.description = s.description;
    h.tag = o.tag;
    h.scenario_json = s.raw;
    json head = summary_header(o, c, h, threads, t);
    json settings = json::object();
    for (const auto &sp : specs)
        settings[sp.name] = sp.settings();
    head["declared_points"] = "reports flagged detected (with_coasting: every report)";
    head["seeds"] = {c.base_seed, c.base_seed + c.runs - 1};  // first and last (every SNR point uses them all)
    head["snr_db"] = sweep(s);
    head["d_c"] = s.eval.d_c;
    head["frames"] = s.frames;
    head["cells"] = s.radar.cells;
    head["methods"] = s.eval.methods;
    head["settings"] = settings;
    head["timing"]["threshold_monte_carlo_s"] = mc_s;
    head["scenario_json"] = s.raw;
    if (!s.reference.is_null())
        head["reference"] = s.reference;
    return head;
}

/** The measures of the runs (summed in run order at every SNR point) added to the head;
 *  summary.json, the points/ files, the plots and the table. Shared by eval and merge, so
 *  both give the same summary from the same runs. */
int finish_eval(const Options &o, const Scenario &s, const std::vector<MethodSpec> &specs, json head,
                const std::vector<RunCounts> &recs, const std::string &out)
{
    const std::vector<double> snrs = sweep(s);
    const unsigned runs = static_cast<unsigned>(recs.size());
    std::vector<SnrResult> res(snrs.size());
    for (std::size_t i = 0; i < snrs.size(); ++i) {
        res[i].snr = snrs[i];
        for (const auto &m : s.eval.methods) {
            res[i].counts[m] = Counts{};
            res[i].coasting[m] = Counts{};
        }
        for (const RunCounts &r : recs) {
            if (r.det.size() != snrs.size())
                throw InputError("merge: a run record has " + std::to_string(r.det.size()) + " SNR points, the scenario " +
                                 std::to_string(snrs.size()));
            for (const auto &m : s.eval.methods) {
                res[i].counts[m].add(r.det[i].at(m));
                res[i].coasting[m].add(r.all[i].at(m));
            }
        }
    }
    json results = json::array(), reach = json::object();
    ensure_dir(join_path(out, "points"));
    std::map<std::string, std::string> labels;
    for (const auto &sp : specs)
        labels[sp.name] = sp.label();
    for (const auto &r : res)
        for (const auto &m : s.eval.methods) {
            json p = r.counts.at(m).to_json();
            p["with_coasting"] = r.coasting.at(m).to_json();
            p["method"] = m;
            p["label"] = labels.at(m);
            p["snr_db"] = r.snr;
            p["numeric"] = numeric_name();
            p["tag"] = labels.at(m) + (o.tag.empty() ? "" : " " + o.tag) + " (" + numeric_name() + ")";
            p["runs"] = runs;
            results.push_back(p);
            char name[64];
            std::snprintf(name, sizeof name, "%s_snr%05.1f.json", m.c_str(), r.snr);
            write_json_atomic(join_path(join_path(out, "points"), name), p);
        }
    for (const auto &m : s.eval.methods) {
        auto pd = [](const Counts &c) { return c.detection_prob() > 0.9; };
        auto rel = [](const Counts &c) { return c.reliable3_prob() > 0.9; };
        auto fa = [](const Counts &c) { return c.declared > 0 && c.false_track_prob() < 0.1; };
        auto rm = [](const Counts &c) { return std::isfinite(c.rmse()) && c.rmse() < 3.0; };
        auto all = [&](const Counts &c) { return pd(c) && rel(c) && fa(c) && rm(c); };
        reach[m] = {{"detection_prob_above_0.9", first_reach(res, m, pd)},
                    {"reliable3_above_0.9", first_reach(res, m, rel)},
                    {"false_track_below_0.1", first_reach(res, m, fa)},
                    {"rmse_below_3", first_reach(res, m, rm)},
                    {"all_four", first_reach(res, m, all)}};
    }
    head["results"] = results;
    head["first_snr_meeting"] = reach;
    write_json_atomic(join_path(out, "summary.json"), head);
    if (snrs.size() > 1)
        fig5_plots(out, s, res, runs, labels);
    if (runs > 0)
        gospa_plot(out, s, res, runs, labels);
    if (!o.quiet) {
        std::printf("\n");
        print_table_header();
        for (const auto &r : res)
            for (const auto &m : s.eval.methods)
                print_row(labels.at(m), r.snr, r.counts.at(m));
        std::printf("\n  first SNR from which the criterion holds (Pd>0.9, reliable>0.9, false<0.1, RMSE<3; all):\n");
        for (const auto &m : s.eval.methods) {
            auto v = [&](const char *k) {
                const json &x = reach[m][k];
                return x.is_null() ? std::string("never") : fmt(x.get<double>(), 1);
            };
            std::printf("  %-14s %6s %6s %6s %6s | %6s\n", labels.at(m).c_str(),
                        v("detection_prob_above_0.9").c_str(), v("reliable3_above_0.9").c_str(),
                        v("false_track_below_0.1").c_str(), v("rmse_below_3").c_str(), v("all_four").c_str());
        }
        std::printf("\n  %.1f s wall; wrote %s/summary.json, points/*.json, gospa_per_frame.png%s\n",
                    head["timing"]["wall_s"].get<double>(),
                    out.c_str(),
                    snrs.size() > 1 ? ", fig5a_rmse.png, fig5b_detection.png, fig5c_reliable3.png, fig5d_false.png" : "");
    }
    return 0;
}

// ------------------------------------------------------------------------- handler
class PteHandler : public KindHandler {
public:
    std::string default_scenario() const override
    {
        return scenario_file("pte/air_turn_6db.json");
    }

    int sim(const Options &o) override
    {
        Scenario s = load(o);
        if (o.out.empty())
            throw InputError("sim: --out DIR is required");
        std::string format = o.format.empty() ? s.output.format : o.format;
        uint64_t seed = o.seed ? *o.seed : s.eval.base_seed;
        ensure_dir(o.out);
        Sequence q = simulate(s, seed, o.frames ? static_cast<int>(o.frames) : 0);
        json side;
        long clipped = 0;
        if (format == "pgm") {
            std::vector<uint16_t> px(static_cast<std::size_t>(q.cells) * q.frames);
            for (int k = 0; k < q.frames; ++k)
                for (int u = 0; u < q.cells; ++u) {
                    double v = std::nearbyint(s.output.offset + s.output.gain * q.z[k][u]);
                    if (v < 0 || v > 65535) {
                        ++clipped;
                        v = std::clamp(v, 0.0, 65535.0);
                    }
                    px[static_cast<std::size_t>(k) * q.cells + u] = static_cast<uint16_t>(v);
                }
            if (q.frames > 65535)
                throw InputError("sim: PGM output holds at most 65535 frames (use --format raw)");
            pft_frame_t f{};
            f.data = px.data();
            f.width = static_cast<uint16_t>(q.cells);
            f.height = static_cast<uint16_t>(q.frames);
            f.stride_bytes = static_cast<uint32_t>(q.cells * 2);
            f.format = PFT_PIX_U16;
            f.bit_depth = 16;
            AtomicPath ap(join_path(o.out, "rangetime.pgm"));
            pft_status_t st = pft_pnm_write(ap.tmp().c_str(), &f);
            if (st != PFT_OK)
                throw InputError(ap.final_path() + ": cannot write PGM (" + pft_status_str(st) + ")");
            ap.commit();
            side = {{"format", "pgm16"}, {"file", "rangetime.pgm"}, {"raw_gain", s.output.gain},
                    {"raw_offset", s.output.offset}, {"pixel_gain", 1.0 / s.output.gain},
                    {"pixel_offset", -s.output.offset / s.output.gain}, {"clipped_pixels", clipped}};
        } else {
            AtomicPath ap(join_path(o.out, "rangetime.f32"));
            for (int k = 0; k < q.frames; ++k) {
                pft_frame_t f{};
                f.data = q.z[k].data();
                f.width = static_cast<uint16_t>(q.cells);
                f.height = 1;
                f.stride_bytes = static_cast<uint32_t>(q.cells * 4);
                f.format = PFT_PIX_F32;
                pft_status_t st = pft_raw_write(ap.tmp().c_str(), &f, k > 0);
                if (st != PFT_OK)
                    throw InputError(ap.final_path() + ": cannot write (" + pft_status_str(st) + ")");
            }
            ap.commit();
            side = {{"format", "raw_f32"}, {"file", "rangetime.f32"}, {"pixel_gain", 1.0}, {"pixel_offset", 0.0}};
        }
        write_truth_csv(join_path(o.out, "truth.csv"), q.truths.empty() ? std::vector<std::vector<Truth>>{q.truth}
                                                                        : q.truths);
        double lo, hi;
        grey_range(s, lo, hi);
        save_rangetime_png(join_path(o.out, "rangetime.png"), q.z, &q.truths, {{"range-time image", nullptr}},
                           lo, hi, describe(s));
        side["layout"] = "one row per frame (time), one column per range cell";
        side["cells"] = q.cells;
        side["frames"] = q.frames;
        side["amplitude"] = q.amplitude;
        side["truth"] = "truth.csv";
        side["seed"] = seed;
        side["snr_db"] = s.snr_db;
        side["generator"] = "pft sim (std::mt19937_64 from seed)";
        side["scenario_file"] = s.file;
        side["scenario"] = s.raw;
        write_json_atomic(join_path(o.out, "sequence.json"), side);
        if (!o.quiet)
            std::printf("pft sim: %s\n  seed %llu -> %s: rangetime.%s (%d x %d), truth.csv, rangetime.png, "
                        "sequence.json%s\n",
                        describe(s).c_str(), static_cast<unsigned long long>(seed), o.out.c_str(),
                        format == "pgm" ? "pgm 16-bit" : "f32", q.cells, q.frames,
                        clipped ? (", " + std::to_string(clipped) + " pixels clipped").c_str() : "");
        return 0;
    }

    /** Reads a range-time image written by `pft sim` (or a 16-bit PGM with --scenario). */
    static std::vector<std::vector<float>> read_rangetime(const std::string &path, double gain, double offset)
    {
        std::vector<std::vector<float>> z;
        if (path.size() > 4 && path.substr(path.size() - 4) == ".f32")
            throw InputError(path + ": raw input needs the sidecar (run on the pft sim directory)");
        std::ifstream in(path, std::ios::binary | std::ios::ate);
        if (!in)
            throw InputError(path + ": cannot open");
        std::size_t bytes = static_cast<std::size_t>(in.tellg()) + 64;
        std::vector<uint8_t> buf(bytes);
        pft_frame_t f{};
        pft_status_t st = pft_pnm_read(path.c_str(), buf.data(), buf.size(), &f, nullptr);
        if (st != PFT_OK)
            throw InputError(path + ": cannot read PGM (" + pft_status_str(st) + ")");
        if (f.format != PFT_PIX_U16 && f.format != PFT_PIX_U8)
            throw InputError(path + ": expected a grey PGM");
        z.assign(f.height, std::vector<float>(f.width));
        for (uint32_t k = 0; k < f.height; ++k) {
            const uint8_t *row = pft_frame_row(&f, k);
            for (uint32_t u = 0; u < f.width; ++u) {
                double raw;
                if (f.format == PFT_PIX_U16) {
                    uint16_t v;
                    std::memcpy(&v, row + 2 * u, 2);
                    raw = v;
                } else {
                    raw = row[u];
                }
                z[k][u] = static_cast<float>(gain * raw + offset);
            }
        }
        return z;
    }

    int run(const Options &o) override
    {
        if (o.sequence.empty())
            throw InputError("run: --sequence PATH is required (pft sim directory or a 16-bit range-time PGM)");
        json side = json::object();
        std::string dir = o.sequence, img_path;
        bool is_dir = fs::is_directory(o.sequence);
        if (is_dir) {
            side = load_json_file(join_path(dir, "sequence.json"));
            img_path = join_path(dir, side.value("file", std::string("rangetime.pgm")));
        } else {
            img_path = o.sequence;
        }
        json scen = o.scenario;
        std::string scen_path = o.scenario_path;
        if (scen.is_null()) {
            if (!side.contains("scenario"))
                throw InputError("run: --scenario FILE.json is required for " + o.sequence);
            scen = side["scenario"];
            scen_path = dir + "/sequence.json:scenario";
        }
        Options o2 = o;
        o2.scenario = scen;
        o2.scenario_path = scen_path;
        Scenario s = load(o2);
        if (side.contains("snr_db"))
            s.snr_db = side["snr_db"].get<double>();
        std::vector<std::vector<float>> z;
        if (side.value("format", std::string()) == "raw_f32") {
            std::ifstream in(img_path, std::ios::binary);
            if (!in)
                throw InputError(img_path + ": cannot open");
            int cells = side["cells"].get<int>(), frames = side["frames"].get<int>();
            z.assign(frames, std::vector<float>(cells));
            for (auto &r : z)
                if (!in.read(reinterpret_cast<char *>(r.data()), static_cast<std::streamsize>(cells * 4)))
                    throw InputError(img_path + ": file shorter than the sidecar says");
        } else {
            double g = side.value("pixel_gain", 1.0 / s.output.gain);
            double off = side.value("pixel_offset", -s.output.offset / s.output.gain);
            z = read_rangetime(img_path, g, off);
        }
        if (z.empty() || static_cast<int>(z[0].size()) != s.radar.cells)
            throw InputError(img_path + ": " + std::to_string(z.empty() ? 0 : z[0].size()) +
                             " range cells, the scenario has " + std::to_string(s.radar.cells));
        if (o.frames && z.size() > o.frames)
            z.resize(o.frames);
        std::vector<std::vector<Truth>> truths;
        std::string tpath = !o.truth.empty() ? o.truth : (is_dir ? join_path(dir, "truth.csv") : "");
        bool have_truth = !tpath.empty() && fs::exists(tpath);
        if (!o.truth.empty() && !have_truth)
            throw InputError(o.truth + ": no such truth file");
        if (have_truth) {
            truths = read_truth_csv(tpath);
            for (auto &tr : truths) {
                Truth absent;
                absent.active = false;
                absent.r = -1.0;
                tr.resize(z.size(), absent);  // frames past the file's: absent
            }
            have_truth = !truths.empty();
        }
        std::string out = o.out.empty() ? "pft_run_pte" : o.out;
        ensure_dir(out);
        if (!o.quiet)
            std::printf("pft run: %s (%zu frames)\n  %s\n", img_path.c_str(), z.size(), describe(s).c_str());
        json res = track_and_report(s, z, have_truth ? &truths[0] : nullptr, out, describe(s), o.quiet,
                                    have_truth ? &truths : nullptr);
        json j = {{"tool", "pft run"}, {"kind", "pte"}, {"sequence", img_path}, {"numeric", numeric_name()},
                  {"frames", z.size()}, {"d_c", s.eval.d_c}, {"methods", res}};
        write_json_atomic(join_path(out, "summary.json"), j);
        if (!o.quiet)
            std::printf("  wrote %s/tracks.csv, tracked.png, summary.json\n", out.c_str());
        return 0;
    }

    int eval(const Options &o) override
    {
        Scenario s = load(o);
        Campaign c = make_campaign(o.runs ? o.runs : s.eval.runs, o.seed ? *o.seed : s.eval.base_seed, o.shard);
        unsigned threads = resolve_threads(o.threads);
        std::vector<double> snrs = sweep(s);
        std::string out = o.out.empty() ? "pft_eval_" + (s.name.empty() ? std::string("pte") : s.name) + "_" +
                                              numeric_name()
                                        : o.out;
        ensure_dir(out);
        auto t_mc = Clock::now();
        std::vector<MethodSpec> specs = make_specs(s);
        double mc_s = std::chrono::duration<double>(Clock::now() - t_mc).count();
        if (!o.quiet) {
            std::printf("pft eval: %s\n  %zu runs x %zu SNR points, seeds %llu..%llu (the same seeds at every SNR)%s, "
                        "%u threads\n",
                        describe(s).c_str(), c.count(), snrs.size(), static_cast<unsigned long long>(c.seed(c.first)),
                        static_cast<unsigned long long>(c.seed(c.end - 1)),
                        c.partial() ? (" (shard " + std::to_string(c.shard) + "/" + std::to_string(c.shards) +
                                       " of " + std::to_string(c.runs) + " runs)").c_str()
                                    : "",
                        threads);
            print_thresholds(s, specs);
        }
        const double gc = o.gospa_c ? *o.gospa_c : 0.0, gp = o.gospa_p ? *o.gospa_p : 2.0;
        std::vector<RunCounts> recs(c.count());
        CampaignTiming t = run_campaign(c, threads, progress_wanted(o.progress), "eval", [&](std::size_t run, uint64_t seed) {
            RunCounts &r = recs[run - c.first];
            r.seed = seed;
            r.det.resize(snrs.size());
            r.all.resize(snrs.size());
            for (std::size_t si = 0; si < snrs.size(); ++si) {
                Scenario sc = s;
                sc.snr_db = snrs[si];
                Sequence q = simulate(sc, seed);
                // lost frames (eval.drop_prob): drawn from the run seed alone, so every method
                // and mode loses the same frames; a lost frame is not fed and its output is the
                // method's last one (the metrics count it)
                std::vector<bool> lost(q.z.size(), false);
                if (sc.eval.drop_prob > 0.0) {
                    std::mt19937_64 gen(seed ^ 0x9E3779B97F4A7C15ull);
                    std::uniform_real_distribution<double> u(0.0, 1.0);
                    for (std::size_t k = 1; k < lost.size(); ++k)
                        lost[k] = u(gen) < sc.eval.drop_prob;
                }
                for (const auto &sp : specs) {
                    double tm = 0.0;
                    auto outp = run_method(sp, q.z, &tm, &lost);
                    Counts cd = score_runs(q.truths, outp, sc.radar.cells, sc.eval.d_c, false, gc, gp);
                    Counts ca = score_runs(q.truths, outp, sc.radar.cells, sc.eval.d_c, true, gc, gp);
                    cd.time_s = ca.time_s = tm;
                    cd.frames = ca.frames = q.frames;
                    r.det[si][sp.name] = cd;
                    r.all[si][sp.name] = ca;
                }
            }
        });
        json head = eval_head(o, s, c, specs, threads, t, mc_s);
        if (c.partial()) {
            json rj = json::array();
            for (const RunCounts &r : recs)
                rj.push_back(r.to_json());
            std::string path = write_partial(out, head, o, c, rj);
            if (!o.quiet)
                std::printf("  %.1f s wall; wrote %s (pft merge combines the shards)\n", t.wall_s, path.c_str());
            return 0;
        }
        return finish_eval(o, s, specs, head, recs, out);
    }

    int merge(const Options &o, const MergedRuns &m) override
    {
        Options eo = m.eval_options(o);
        Scenario s = load(eo);
        std::vector<RunCounts> recs;
        for (const json &r : m.runs)
            recs.push_back(RunCounts::from_json(r));
        ensure_dir(o.out);
        auto t_mc = Clock::now();
        std::vector<MethodSpec> specs = make_specs(s);  // the thresholds (the same Monte Carlo as the shards')
        double mc_s = std::chrono::duration<double>(Clock::now() - t_mc).count();
        json head = eval_head(eo, s, m.campaign, specs, m.threads, m.timing, mc_s);
        add_merge_fields(head, m);
        if (!o.quiet) {
            std::printf("pft merge: %s\n  %u runs from %zu shards\n", describe(s).c_str(), m.campaign.runs,
                        m.shards.size());
            print_thresholds(s, specs);
        }
        return finish_eval(eo, s, specs, head, recs, o.out);
    }

    int bench(const Options &o) override
    {
        Scenario s = load(o);
        int frames = o.frames ? static_cast<int>(o.frames) : s.frames;
        unsigned reps = o.runs ? o.runs : 1;
        uint64_t seed = o.seed ? *o.seed : s.eval.base_seed;
        std::vector<MethodSpec> specs = make_specs(s);
        json jm = json::object();
        if (!o.quiet)
            std::printf("pft bench: %s\n  %u x %d frames per method, seed %llu\n", describe(s).c_str(), reps, frames,
                        static_cast<unsigned long long>(seed));
        for (const auto &sp : specs) {
            std::vector<double> times;
            std::size_t ws = 0;
            for (unsigned r = 0; r < reps; ++r) {
                Sequence q = simulate(s, seed + r, frames);
                Method m(sp);
                ws = m.workspace_bytes();
                for (int k = 0; k < q.frames; ++k) {
                    auto t0 = Clock::now();
                    m.update(q.z[k].data());
                    times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
                }
            }
            std::vector<double> st = times;
            std::sort(st.begin(), st.end());
            double sum = 0;
            for (double t : times)
                sum += t;
            double med = st[st.size() / 2], p90 = st[std::min(st.size() - 1, st.size() * 9 / 10)];
            jm[sp.name] = {{"label", sp.label()}, {"workspace_bytes", ws},
                           {"median_us_per_frame", med * 1e6}, {"mean_us_per_frame", sum / times.size() * 1e6},
                           {"p90_us_per_frame", p90 * 1e6}, {"max_us_per_frame", st.back() * 1e6},
                           {"settings", sp.settings()}};
            if (!o.quiet)
                std::printf("  %-14s workspace %7zu B   per frame: median %8.1f us, mean %8.1f us, p90 %8.1f us, "
                            "max %8.1f us\n",
                            sp.label().c_str(), ws, med * 1e6, sum / times.size() * 1e6, p90 * 1e6,
                            st.back() * 1e6);
        }
        if (!o.out.empty()) {
            ensure_dir(o.out);
            write_json_atomic(join_path(o.out, "bench.json"),
                              {{"tool", "pft bench"}, {"kind", "pte"}, {"scenario", s.name},
                               {"numeric", numeric_name()}, {"frames", frames}, {"repeats", reps},
                               {"snr_db", s.snr_db}, {"methods", jm}});
        }
        return 0;
    }

    int demo(const Options &o) override
    {
        Scenario s = load(o);
        if (!o.sequence.empty()) {
            Options o2 = o;
            if (o2.out.empty())
                o2.out = "pft_demo_pte";
            return run(o2);
        }
        uint64_t seed = o.seed ? *o.seed : s.eval.base_seed;
        Sequence q = simulate(s, seed);
        std::printf("pft demo: %s\n  simulated in memory with seed %llu; truth range %.1f -> %.1f cells\n\n",
                    describe(s).c_str(), static_cast<unsigned long long>(seed), q.truth.front().r, q.truth.back().r);
        std::string dir = o.out.empty() ? "pft_demo_pte" : o.out;
        ensure_dir(dir);
        track_and_report(s, q.z, &q.truth, dir, describe(s) + ", seed " + std::to_string(seed), false, &q.truths);
        std::printf("\n  wrote %s/tracked.png and tracks.csv; Monte Carlo: pft eval --scenario %s\n", dir.c_str(),
                    s.file.c_str());
        return 0;
    }

    int selftest(const Options &o) override
    {
        int fails = 0;
        auto check = [&](const char *what, bool ok) {
            fails += ok ? 0 : 1;
            if (!o.quiet || !ok)
                std::printf("  %-4s %s\n", ok ? "ok" : "FAIL", what);
        };
        std::printf("pte selftest: scenario geometry (docs/algorithms.md 5.6) and measures (6)\n");
        json j = {{"kind", "pte"}, {"target", {{"motion", "air_turn"}}}};
        Scenario s = parse_scenario(j, "<selftest>");
        auto r = [&](double t) { return slant_range(s.radar, target_position(s.motion, t)) / 1000.0; };
        check("air target R(0) = 105.00 km", std::fabs(r(0) - 105.00) < 0.005);
        check("air target R(10 s) = 105.02 km", std::fabs(r(10) - 105.02) < 0.005);
        check("air target R(20 s) = 104.62 km", std::fabs(r(20) - 104.62) < 0.005);
        check("air target R(30 s) = 103.98 km", std::fabs(r(30) - 103.98) < 0.005);
        check("turn radius 1273 m (speed / rate)", std::fabs(s.motion.speed / s.motion.turn_rate - 1273.2) < 0.1);
        auto tr = simulate_truth(s, 300);
        check("150 cells: R = 105 km is cell 100", std::fabs(tr[0].r - 100.01) < 0.01);
        // a perfect tracker from frame 10 on, 0.5 cells off, plus one false point at frame 20
        std::vector<std::vector<Report>> out(300);
        for (int k = 9; k < 300; ++k) {
            Report p;
            p.pos = tr[k].r + 0.5;
            p.detected = true;
            out[k].push_back(p);
        }
        Report f;
        f.pos = tr[19].r + 10.0;
        f.detected = true;
        out[19].push_back(f);
        out[100].clear();
        Report coast;  // a coasting report far off: ignored unless with_coasting
        coast.pos = tr[30].r - 20.0;
        out[30].push_back(coast);
        Counts c = score_run(tr, out, 150, 3.0);
        check("measures: Pd = 290/300", c.correct == 290 && c.true_frames == 300);
        check("measures: reliable = (298 - 9 - 3) / 298", c.rel_den == 298 && c.rel_num == 298 - 9 - 3 &&
                                                            std::fabs(c.reliable3_prob() - 286.0 / 298.0) < 1e-12);
        check("measures: false = 1 / 291", c.false_points == 1 && c.declared == 291);
        check("measures: RMSE 0.5", std::fabs(c.rmse() - 0.5) < 1e-9);
        Counts cc = score_run(tr, out, 150, 3.0, nullptr, true);
        check("measures with coasting: false = 2 / 292", cc.false_points == 2 && cc.declared == 292);
        {
            // GOSPA / OSPA (c = 3 cells, p = 2) on four frames, truth at cell 10: a report 0.5
            // off (localisation 0.25), none (missed 9/2), an exact one plus one at 30 (false 9/2),
            // one at 20 (a missed and a false point, 9). OSPA^2: 0.25, 9, 9/2, 9.
            std::vector<Truth> t4(4);
            for (auto &t : t4)
                t.r = 10.0;
            std::vector<std::vector<Report>> o4(4);
            auto rep = [](double pos) { Report q; q.pos = pos; q.detected = true; return q; };
            o4[0] = {rep(10.5)};
            o4[2] = {rep(10.0), rep(30.0)};
            o4[3] = {rep(20.0)};
            Counts g = score_run(t4, o4, 150, 3.0);
            check("GOSPA over 4 frames = sqrt(18.25 / 4)", std::fabs(g.set.gospa() - std::sqrt(18.25 / 4.0)) < 1e-12);
            check("GOSPA parts: 2 missed, 2 false points",
                  std::fabs(g.set.missed_count() * 4.0 - 2.0) < 1e-12 &&
                      std::fabs(g.set.false_count() * 4.0 - 2.0) < 1e-12 &&
                      std::fabs(std::pow(g.set.localisation(), 2.0) * 4.0 - 0.25) < 1e-12);
            check("OSPA over 4 frames = sqrt(22.75 / 4)", std::fabs(g.set.ospa() - std::sqrt(22.75 / 4.0)) < 1e-12);
            Counts g1 = score_runs({t4}, o4, 150, 3.0, false, 5.0, 1.0);
            check("GOSPA c = 5, p = 1: (0.5 + 2.5 + 2.5 + 5) / 4",
                  std::fabs(g1.set.gospa() - 10.5 / 4.0) < 1e-12 && g1.gospa_c == 5.0);
        }
        {
            // truth.csv keeps every target (and whether it is active) through a write and a read
            std::vector<std::vector<Truth>> two(2, std::vector<Truth>(3));
            for (int k = 0; k < 3; ++k) {
                two[0][k].r = 10.0 + k;
                two[1][k].r = 50.0 - 0.5 * k;
                two[1][k].active = k > 0;
            }
            const std::string tp =
                (fs::temp_directory_path() / (std::string("pft_pte_truth_selftest_") + numeric_name() + ".csv")).string();
            write_truth_csv(tp, two);
            auto back = read_truth_csv(tp);
            std::error_code ec;
            fs::remove(tp, ec);
            check("truth.csv round trip: 2 targets x 3 frames, positions and activity",
                  back.size() == 2 && back[0].size() == 3 && back[1].size() == 3 && back[0][2].r == 12.0 &&
                      back[1][1].r == 49.5 && !back[1][0].active && back[1][2].active);
        }
        Counts c1 = score_runs({tr}, out, 150, 3.0);
        check("several targets, one given: the single-target counts",
              c1.correct == c.correct && c1.false_points == c.false_points && c1.declared == c.declared &&
                  c1.rel_num == c.rel_num && c1.rel_den == c.rel_den && c1.sq == c.sq);
        {
            // targets A at cell 20 (frames 0..9) and B at cell 22 (from frame 5); reports at
            // 19.5 and 21.2 every frame: A <- 19.5 (0.5), B <- 21.2 (0.8) once B exists, else
            // 21.2 is false. Frame 9: one report at 20.6 (0.6 from A, 1.4 from B) goes to A,
            // the closer pair; B is missed there (one report serves one target).
            std::vector<std::vector<Truth>> tt(2, std::vector<Truth>(10));
            for (int k = 0; k < 10; ++k) {
                tt[0][k].r = 20.0;
                tt[1][k].r = 22.0;
                tt[1][k].active = k >= 5;
            }
            std::vector<std::vector<Report>> o2(10);
            for (int k = 0; k < 9; ++k)
                for (double pos : {19.5, 21.2}) {
                    Report p;
                    p.pos = pos;
                    p.detected = true;
                    o2[k].push_back(p);
                }
            Report one;
            one.pos = 20.6;
            one.detected = true;
            o2[9].push_back(one);
            Counts m = score_runs(tt, o2, 150, 3.0);
            check("two targets: 15 target-frames, 14 correct, 5 false of 19 declared",
                  m.true_frames == 15 && m.correct == 14 && m.false_points == 5 && m.declared == 19);
            check("two targets: squared errors 9 x 0.25 + 4 x 0.64 + 0.36",
                  std::fabs(m.sq - (9 * 0.25 + 4 * 0.64 + 0.36)) < 1e-9);
            check("two targets: reliable per target (A 8 of 8, B 2 of 3)", m.rel_den == 11 && m.rel_num == 10);
            json mt = {{"kind", "pte"},
                       {"targets", {{{"motion", "line"}, {"start_m", {104000, 0, 0}}, {"velocity_mps", {40, 0, 0}}},
                                    {{"motion", "line"}, {"start_m", {104400, 0, 0}}, {"velocity_mps", {70, 0, 0}},
                                     {"start_s", 10}}}}};
            Scenario sm = parse_scenario(mt, "<selftest>");
            auto tm = simulate_truths(sm, 300);
            check("targets list: two truths, the second from frame 100 at cell 70",
                  tm.size() == 2 && !tm[1][99].active && tm[1][100].active && std::fabs(tm[1][100].r - 70.0) < 1e-6 &&
                      std::fabs(tm[1][200].r - 105.0) < 1e-6 && std::fabs(tm[0][100].r - 70.0) < 1e-6);
            bool refused = false;
            try {
                json both = mt;
                both["target"] = {{"motion", "line"}};
                parse_scenario(both, "<selftest>");
            } catch (const std::exception &) {
                refused = true;
            }
            check("target and targets together are refused", refused);
        }
        json b = {{"kind", "pte"}, {"target", {{"motion", "circle"}}}, {"background", {{"type", "k_clutter"}, {"shape", 1.0}}}};
        Scenario sb = parse_scenario(b, "<selftest>");
        Sequence q = simulate(sb, 3, 400);
        double s2 = 0.0, s4 = 0.0;
        long n = 0;
        for (int k = 0; k < 400; ++k)
            for (int u = 0; u < sb.radar.cells; ++u) {
                if (std::fabs(u - q.truth[k].r) < 6)
                    continue;
                double v = q.z[k][u];
                s2 += v * v;
                s4 += v * v * v * v;
                ++n;
            }
        double m2 = s2 / n, kurt = s4 / n / (m2 * m2);
        // compound Gaussian with Gamma(1) texture: E z^4 / (E z^2)^2 = 3 (1 + 1/nu) = 6 (CNR 20 dB: ~5.9)
        check("K-clutter: power ~ 1 (0.8..1.2)", m2 > 0.8 && m2 < 1.2);
        check("K-clutter: kurtosis ~ 6 for nu = 1 (4.5..7.5, Gaussian gives 3)", kurt > 4.5 && kurt < 7.5);
        std::printf("pte selftest: %s (%d failure%s)\n", fails ? "FAILED" : "passed", fails, fails == 1 ? "" : "s");
        return fails ? 1 : 0;
    }
};

}  // namespace

PFT_REGISTER_KIND("pte", PteHandler);
PFT_REGISTER_KIND_ALIAS("radar", "pte", pte_radar);

}  // namespace pft::host::pte
