// The "tsa" kind (formerly "vis"): sim / run / eval / bench / demo / selftest for the
// semi-synthetic airborne sequences, and the `pft track` subcommand (TSA-AK, docs/algorithms.md 4).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <sstream>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "../common/campaign.hpp"
#include "../common/errors.hpp"
#include "../common/set_metrics.hpp"
#include "../common/json_field.hpp"
#include "../common/real.hpp"
#include "../common/output.hpp"
#include "../common/parallel.hpp"
#include "../common/plot.hpp"
#include "../common/progress.hpp"
#include "../common/registry.hpp"
#include "track.hpp"
#include "tsa_scene.hpp"
#include "tsa_trackers.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pft::host::tsa {

namespace {

struct Scenario {
    std::string name, description, file;
    SceneSpec scene;
    PftParams tracker;
    std::vector<std::string> eval_trackers{"tsa", "ncv", "ncv200", "ts"};
    std::vector<std::string> bench_trackers{"tsa", "ncv", "ncv200", "ts", "kcf", "csrt", "mosse", "mil"};
    int runs = 50;
    double iou_thr = 0.5, center_thr = 10.0, run_min_fraction = 0.9;
    double gospa_c = 0.0, gospa_p = 2.0;  ///< GOSPA/OSPA cut-off (0: center_thr) and order
    json reference;
};

Scenario load_scenario(const Options &o)
{
    Scenario s;
    s.file = o.scenario_path;
    Field r(o.scenario, o.scenario_path);
    r.only({"kind", "name", "description", "scene", "tracker", "eval", "bench", "reference"});
    s.name = r.string_or("name", fs::path(o.scenario_path).stem().string());
    s.description = r.string_or("description", "");
    s.scene = parse_scene(o.scenario, o.scenario_path);
    if (r.has("tracker"))
        s.tracker = parse_pft_params(o.scenario.at("tracker"), o.scenario_path, "tracker");
    auto names = [&](const Field &f, std::vector<std::string> &v) {
        if (!f.has("trackers"))
            return;
        Field t = f.at("trackers");
        v.clear();
        for (std::size_t i = 0; i < t.size(); ++i)
            v.push_back(t.at(i).as_string());
    };
    if (r.has("eval")) {
        Field e = r.at("eval");
        e.only({"trackers", "runs", "iou", "center_px", "run_min_fraction"});
        names(e, s.eval_trackers);
        s.runs = (int)e.integer_in("runs", s.runs, 1, 100000);
        s.iou_thr = e.number_in("iou", s.iou_thr, 0, 1);
        s.center_thr = e.number_in("center_px", s.center_thr, 0, 10000);
        s.run_min_fraction = e.number_in("run_min_fraction", s.run_min_fraction, 0, 1);
    }
    if (r.has("bench")) {
        Field b = r.at("bench");
        b.only({"trackers"});
        names(b, s.bench_trackers);
    }
    if (r.has("reference"))
        s.reference = o.scenario.at("reference");
    if (o.particles)
        s.tracker.particles = (int)o.particles;
    if (o.gospa_c)
        s.gospa_c = *o.gospa_c;
    if (o.gospa_p)
        s.gospa_p = *o.gospa_p;
    return s;
}

double iou(const cv::Rect2d &a, const cv::Rect2d &b)
{
    const double i = (a & b).area();
    const double u = a.area() + b.area() - i;
    return u > 0 ? i / u : 0.0;
}

std::vector<cv::Point> box_poly(const cv::Rect2d &b)
{
    const int x0 = (int)std::floor(b.x), y0 = (int)std::floor(b.y);
    const int x1 = (int)std::ceil(b.x + b.width), y1 = (int)std::ceil(b.y + b.height);
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

void draw_overlay(cv::Mat &img, const TrackOut &t, const cv::Rect2d *truth, int frame, const std::string &label)
{
    if (truth)
        cv::rectangle(img, *truth, cv::Scalar(255, 255, 255), 1);
    for (const auto &p : t.particles)
        cv::circle(img, cv::Point((int)std::lround(p.x), (int)std::lround(p.y)), 1, cv::Scalar(0, 0, 255), -1);
    if (!t.contour.empty())
        cv::polylines(img, t.contour, true, cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
    else
        cv::rectangle(img, t.box, cv::Scalar(0, 255, 0), 1);
    if (!std::isnan(t.pioneer.x))
        cv::drawMarker(img, cv::Point((int)std::lround(t.pioneer.x), (int)std::lround(t.pioneer.y)),
                       cv::Scalar(255, 128, 0), cv::MARKER_CROSS, 9, 2);
    cv::drawMarker(img, cv::Point((int)std::lround(t.center.x), (int)std::lround(t.center.y)), cv::Scalar(0, 255, 255),
                   cv::MARKER_TILTED_CROSS, 7, 1);
    char buf[160];
    if (!std::isnan(t.rho))
        std::snprintf(buf, sizeof buf, "%s #%d rho %.2f beta %.2f alive %d", label.c_str(), frame, t.rho, t.beta, t.alive);
    else
        std::snprintf(buf, sizeof buf, "%s #%d", label.c_str(), frame);
    cv::putText(img, buf, cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3);
    cv::putText(img, buf, cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1);
}

/* Several trackers on one frame: each one's contour (pftrack) or box (OpenCV) and centre in its
 * colour, its name beside it, and a legend. */
void draw_compare(cv::Mat &img, const std::vector<TrackOut> &outs, const std::vector<std::string> &names, int frame)
{
    static const cv::Scalar colours[] = {{0, 255, 0}, {0, 200, 255}, {255, 128, 0}, {255, 0, 255}, {0, 0, 255},
                                         {255, 255, 0}, {128, 128, 255}, {255, 255, 255}};
    std::string legend = "#" + std::to_string(frame);
    for (std::size_t i = 0; i < outs.size(); ++i) {
        const TrackOut &t = outs[i];
        const cv::Scalar c = colours[i % 8];
        if (!t.contour.empty())
            cv::polylines(img, t.contour, true, c, 2, cv::LINE_AA);
        else
            cv::rectangle(img, t.box, c, 2);
        cv::drawMarker(img, cv::Point((int)std::lround(t.center.x), (int)std::lround(t.center.y)), c,
                       cv::MARKER_TILTED_CROSS, 9, 2);
        const cv::Point at((int)std::lround(t.box.x), (int)std::lround(t.box.y) - 4 - 12 * (int)(i % 2));
        cv::putText(img, names[i], at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3);
        cv::putText(img, names[i], at, cv::FONT_HERSHEY_SIMPLEX, 0.45, c, 1);
        legend += "  " + names[i];
    }
    cv::putText(img, legend, cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3);
    cv::putText(img, legend, cv::Point(6, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(255, 255, 255), 1);
}

// ------------------------------------------------------------------------------ evaluation
// CPU time of the calling thread, microseconds (the trackers run on the thread that calls them;
// OpenCV's own worker threads are switched off in evaluate(), see there).
double thread_cpu_us()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e6 + (double)ts.tv_nsec * 1e-3;
}

// A frame succeeds when IoU > iou and the centre error < center_px (the scenario's criterion);
// the project's own criterion (docs/algorithms.md 6) is IoU > 0.5 and centre error < 10 px. Blank
// frames (forced loss) are not scored; after them the re-acquisition delay is the number of
// frames from the first frame after the blank to the first of REACQ_RUN consecutive successful
// frames (0: tracking at once; -1: never).
constexpr int REACQ_RUN = 3;
constexpr double PROJECT_CENTER_PX = 10.0, PROJECT_IOU = 0.5;

struct RunTrace {
    std::vector<double> err, iou, us, cpu_us, beta, x;
    metrics::SetMetricSums set{1, 10.0, 2.0};  ///< GOSPA / OSPA over the run's frames (one slot)
    metrics::SetMetricSums per_frame{0, 10.0, 2.0};  ///< the same, one slot per update (curves)
    std::vector<int> ok, ok_project, scored, state;
    bool success = false, success_project = false;
    int reacquire = -2;  // -2: no forced loss in the scenario
    std::size_t memory = 0;  ///< the tracker's workspace bytes

    /** Every member exactly (a run's record in a partial summary of `pft eval --shard`). */
    json to_json(const std::string &tracker) const
    {
        return {{"tracker", tracker}, {"err", nums_or_null(err)}, {"iou", nums_or_null(iou)},
                {"us", nums_or_null(us)}, {"cpu_us", nums_or_null(cpu_us)}, {"beta", nums_or_null(beta)},
                {"x", nums_or_null(x)}, {"set", set.raw()}, {"per_frame", per_frame.raw()}, {"ok", ok}, {"ok_project", ok_project},
                {"scored", scored}, {"state", state}, {"success", success}, {"success_project", success_project},
                {"reacquire", reacquire}, {"memory", memory}};
    }
    static RunTrace from_json(const json &j)
    {
        RunTrace r;
        r.err = nulls_to_nan(j.at("err"));
        r.iou = nulls_to_nan(j.at("iou"));
        r.us = nulls_to_nan(j.at("us"));
        r.cpu_us = nulls_to_nan(j.at("cpu_us"));
        r.beta = nulls_to_nan(j.at("beta"));
        r.x = nulls_to_nan(j.at("x"));
        r.set = metrics::SetMetricSums::from_raw(j.at("set"));
        r.per_frame = metrics::SetMetricSums::from_raw(j.at("per_frame"));
        r.ok = j.at("ok").get<std::vector<int>>();
        r.ok_project = j.at("ok_project").get<std::vector<int>>();
        r.scored = j.at("scored").get<std::vector<int>>();
        r.state = j.at("state").get<std::vector<int>>();
        r.success = j.at("success").get<bool>();
        r.success_project = j.at("success_project").get<bool>();
        r.reacquire = j.at("reacquire").get<int>();
        r.memory = j.at("memory").get<std::size_t>();
        const std::size_t n = r.err.size();
        if (r.iou.size() != n || r.us.size() != n || r.cpu_us.size() != n || r.ok.size() != n ||
            r.ok_project.size() != n || r.scored.size() != n)
            throw InputError("tsa run record: per-frame arrays of different lengths");
        return r;
    }
};

struct Agg {
    std::string name;
    metrics::SetMetricSums set{1, 10.0, 2.0};
    metrics::SetMetricSums per_frame{0, 10.0, 2.0};
    double err_sum = 0, us_sum = 0, cpu_sum = 0;
    long frames = 0, ok_frames = 0, ok_project = 0, timed = 0;
    int runs = 0, runs_ok = 0, runs_ok_project = 0;
    std::vector<long> iou_ge = std::vector<long>(21, 0);  // frames with IoU >= t/20
    std::vector<double> errs;                             // every scored frame's centre error
    std::vector<double> run_success;                      // per run: fraction of successful frames
    std::vector<int> reacquire;                           // per run (forced-loss scenarios)
    std::size_t memory = 0;
    std::vector<RunTrace> traces;                          // kept for plots (first runs)
};

RunTrace run_one(Tracker &t, const std::vector<cv::Mat> &frames, const std::vector<TruthRow> &truth,
                 const Scenario &s)
{
    RunTrace r;
    t.init(frames[0], box_poly(truth[0].box));
    long good = 0, good_p = 0, scored = 0;
    for (std::size_t k = 1; k < frames.size(); ++k) {
        TrackOut out;
        const double c0 = thread_cpu_us();
        auto t0 = std::chrono::steady_clock::now();
        t.update(frames[k], out);
        auto t1 = std::chrono::steady_clock::now();
        const double c1 = thread_cpu_us();
        const double e = std::hypot(out.center.x - truth[k].cx, out.center.y - truth[k].cy);
        const double ov = iou(out.box, truth[k].box);
        const int sc = s.scene.blank((int)k) ? 0 : 1;
        const int ok = sc && ov > s.iou_thr && e < s.center_thr;
        const int okp = sc && ov > PROJECT_IOU && e < PROJECT_CENTER_PX;
        {
            // GOSPA / OSPA: the target's centre while it is in view (not a blank frame), the
            // tracker's centre while it reports success
            std::vector<metrics::Point> tp, ep;
            if (sc)
                tp.push_back({truth[k].cx, truth[k].cy});
            if (out.ok)
                ep.push_back({out.center.x, out.center.y});
            const double gc = s.gospa_c > 0 ? s.gospa_c : s.center_thr;
            if (r.set.added() == 0) {
                r.set = metrics::SetMetricSums(1, gc, s.gospa_p);
                r.per_frame = metrics::SetMetricSums(frames.size() - 1, gc, s.gospa_p);
            }
            const metrics::FrameMetrics fm = metrics::frame_metrics(tp, ep, gc, s.gospa_p);
            r.set.add(0, fm);
            r.per_frame.add(k - 1, fm);
        }
        r.err.push_back(e);
        r.iou.push_back(ov);
        r.us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
        r.cpu_us.push_back(c1 - c0);
        r.beta.push_back(out.beta);
        r.x.push_back(out.center.x);
        r.ok.push_back(ok);
        r.ok_project.push_back(okp);
        r.scored.push_back(sc);
        r.state.push_back(out.state);
        good += ok;
        good_p += okp;
        scored += sc;
    }
    r.success = scored > 0 && good >= (long)std::ceil(s.run_min_fraction * (double)scored);
    r.success_project = scored > 0 && good_p >= (long)std::ceil(s.run_min_fraction * (double)scored);
    if (s.scene.blank_frame >= 1 && s.scene.blank_frames > 0) {
        // r.ok[i] is frame i + 1
        const int first = s.scene.blank_frame + s.scene.blank_frames;
        r.reacquire = -1;
        for (int k = first; k + REACQ_RUN - 1 < (int)frames.size(); ++k) {
            bool run = true;
            for (int j = 0; j < REACQ_RUN && run; ++j)
                run = r.ok[(std::size_t)(k + j - 1)] != 0;
            if (run) {
                r.reacquire = k - first;
                break;
            }
        }
    }
    return r;
}

struct EvalResult {
    std::vector<Agg> aggs;
    std::vector<double> truth0_cx;  // truth of the first run: the target's centre x per frame
};

/** One run (seed): every tracker's trace on the same frames; the first run of the campaign
 *  also keeps the truth's x for the trajectory plot. A partial summary stores these. */
struct RunRecord {
    uint64_t seed = 0;
    std::vector<std::string> names;
    std::vector<RunTrace> traces;
    std::vector<double> truth_cx;  ///< run 0 only

    json to_json() const
    {
        json t = json::array();
        for (std::size_t j = 0; j < traces.size(); ++j)
            t.push_back(traces[j].to_json(names[j]));
        json r = {{"seed", seed}, {"trackers", t}};
        if (!truth_cx.empty())
            r["truth_cx"] = nums_or_null(truth_cx);
        return r;
    }
    static RunRecord from_json(const json &j)
    {
        RunRecord r;
        r.seed = j.at("seed").get<uint64_t>();
        for (const json &t : j.at("trackers")) {
            r.names.push_back(t.at("tracker").get<std::string>());
            r.traces.push_back(RunTrace::from_json(t));
        }
        if (j.contains("truth_cx"))
            r.truth_cx = nulls_to_nan(j["truth_cx"]);
        return r;
    }
};

/** Every tracker of `names` on the runs of campaign c (one record per run, in run order). */
std::vector<RunRecord> run_traces(const Scenario &s, const std::vector<std::string> &names, const Campaign &c,
                                  unsigned threads, int max_frames, bool progress, CampaignTiming *timing)
{
    // OpenCV's trackers and image functions run on the calling thread, so the thread CPU time
    // measures them completely and `threads` bounds the cores used
    cv::setNumThreads(0);
    std::vector<RunRecord> recs(c.count());
    CampaignTiming t = run_campaign(c, threads, progress, "tsa " + s.name, [&](std::size_t run, uint64_t seed) {
        std::vector<cv::Mat> frames;
        std::vector<TruthRow> truth;
        render_sequence(s.scene, seed, frames, truth, max_frames);
        RunRecord &r = recs[run - c.first];
        r.seed = seed;
        r.names = names;
        r.traces.resize(names.size());
        for (std::size_t j = 0; j < names.size(); ++j) {
            PftParams p = s.tracker;
            p.seed = seed;
            auto tr = make_tracker(names[j], p, s.scene.width, s.scene.height);
            r.traces[j] = run_one(*tr, frames, truth, s);
            r.traces[j].memory = tr->memory_bytes();
        }
        if (run == 0)
            for (const TruthRow &row : truth)
                r.truth_cx.push_back(row.cx);
    });
    if (timing)
        *timing = t;
    return recs;
}

/** The measures over the runs, in run order; the traces of the first keep_traces runs are kept
 *  for the plots. */
EvalResult aggregate(const std::vector<std::string> &names, const std::vector<RunRecord> &recs,
                     std::size_t keep_traces)
{
    EvalResult res;
    for (auto &n : names) {
        Agg a;
        a.name = n;
        res.aggs.push_back(a);
    }
    for (const RunRecord &rec : recs)
        if (rec.names != names)
            throw InputError("tsa run record of seed " + std::to_string(rec.seed) +
                             ": other trackers than this build evaluates");
    for (std::size_t j = 0; j < names.size(); ++j) {
        Agg &a = res.aggs[j];
        a.memory = recs.empty() ? 0 : recs[0].traces[j].memory;
        for (std::size_t i = 0; i < recs.size(); ++i) {
            const RunTrace &r = recs[i].traces[j];
            a.runs++;
            a.set.merge(r.set);
            if (a.per_frame.frames() == 0)
                a.per_frame = r.per_frame;
            else
                a.per_frame.merge(r.per_frame);
            a.runs_ok += r.success;
            a.runs_ok_project += r.success_project;
            long ok = 0, n = 0;
            for (std::size_t k = 0; k < r.err.size(); ++k) {
                a.us_sum += r.us[k];
                a.cpu_sum += r.cpu_us[k];
                a.timed++;
                if (!r.scored[k])
                    continue;
                a.err_sum += r.err[k];
                a.errs.push_back(r.err[k]);
                a.ok_frames += r.ok[k];
                a.ok_project += r.ok_project[k];
                a.frames++;
                ok += r.ok[k];
                ++n;
                for (int t = 0; t <= 20; ++t)
                    a.iou_ge[t] += r.iou[k] >= t / 20.0;
            }
            a.run_success.push_back(n ? (double)ok / n : 0.0);
            if (r.reacquire != -2)
                a.reacquire.push_back(r.reacquire);
            if (i < keep_traces)
                a.traces.push_back(r);
        }
    }
    if (!recs.empty())
        res.truth0_cx = recs[0].truth_cx;
    return res;
}

/** The measures of every tracker (the summary's "trackers"). */
json trackers_json(const Scenario &s, const EvalResult &r)
{
    json trk = json::array();
    for (const auto &a : r.aggs) {
        std::vector<double> curve;
        for (int t = 0; t <= 20; ++t)
            curve.push_back(a.frames ? (double)a.iou_ge[t] / a.frames : 0.0);
        std::vector<double> e = a.errs;
        std::sort(e.begin(), e.end());
        json t = {{"tracker", a.name},
                  {"success_rate", a.frames ? (double)a.ok_frames / a.frames : 0.0},
                  {"success_rate_project", a.frames ? (double)a.ok_project / a.frames : 0.0},
                  {"mean_center_error", a.frames ? a.err_sum / a.frames : 0.0},
                  {"median_center_error", e.empty() ? 0.0 : e[e.size() / 2]},
                  {"us_per_frame", a.timed ? a.us_sum / a.timed : 0.0},
                  {"cpu_us_per_frame", a.timed ? a.cpu_sum / a.timed : 0.0},
                  {"runs_succeeded", a.runs_ok},
                  {"runs_succeeded_project", a.runs_ok_project},
                  {"runs", a.runs},
                  {"frames", a.frames},
                  {"workspace_bytes", a.memory},
                  {"run_success", a.run_success},
                  {"success_vs_iou", curve}};
        // power means over every frame of every run (docs/host_tools.md, GOSPA and OSPA)
        t.update(metrics::set_metric_fields(a.set));
        {
            std::vector<double> g, os;
            for (std::size_t k = 0; k < a.per_frame.frames(); ++k) {
                g.push_back(a.per_frame.gospa_at(k));
                os.push_back(a.per_frame.ospa_at(k));
            }
            t["gospa_per_frame"] = nums_or_null(g);  // frame k + 2 (the first update is frame 2)
            t["ospa_per_frame"] = nums_or_null(os);
        }
        t["gospa_c"] = s.gospa_c > 0 ? s.gospa_c : s.center_thr;
        t["gospa_p"] = s.gospa_p;
        t["gospa_alpha"] = 2;
        if (!a.reacquire.empty()) {
            int within = 0;
            for (int q : a.reacquire)
                within += q >= 0 && q <= 15;
            t["reacquire_frames"] = a.reacquire;
            t["reacquired_within_15"] = within;
        }
        trk.push_back(t);
    }
    return trk;
}

/** The settings part of a summary (everything but "trackers"). */
json settings_json(const Scenario &s, int runs, uint64_t seed_base, const std::string &what)
{
    return {{"kind", "tsa"}, {"command", what}, {"scenario", s.name}, {"scenario_file", s.file},
            {"numeric", numeric_name()}, {"runs", runs}, {"seed_first", seed_base},
            {"seed_last", seed_base + (uint64_t)runs - 1}, {"frames_per_run", s.scene.frames},
            {"success", {{"iou", s.iou_thr}, {"center_px", s.center_thr}, {"run_min_fraction", s.run_min_fraction},
                         {"project_iou", PROJECT_IOU}, {"project_center_px", PROJECT_CENTER_PX},
                         {"reacquire_run", REACQ_RUN}}},
            {"tracker_params", pft_params_json(s.tracker)}, {"scene", scene_to_json(s.scene)},
            {"reference", s.reference}};
}

json summary_json(const Scenario &s, const EvalResult &r, int runs, uint64_t seed_base, const std::string &what)
{
    json j = settings_json(s, runs, seed_base, what);
    j["trackers"] = trackers_json(s, r);
    return j;
}

void write_plots(const Scenario &s, const EvalResult &r, const std::string &out)
{
    PlotSpec sp;
    sp.title = s.name + ": success rate vs IoU threshold";
    sp.xlabel = "IoU threshold";
    sp.ylabel = "fraction of frames";
    sp.ymin = 0;
    sp.ymax = 1;
    for (const auto &a : r.aggs) {
        PlotSeries ps;
        ps.label = a.name;
        for (int t = 0; t <= 20; ++t) {
            ps.x.push_back(t / 20.0);
            ps.y.push_back(a.frames ? (double)a.iou_ge[t] / a.frames : 0.0);
        }
        sp.series.push_back(ps);
    }
    save_plot_png(sp, join_path(out, "success_iou.png"));

    PlotSpec ce;
    ce.title = s.name + ": centre error, first run";
    ce.xlabel = "frame";
    ce.ylabel = "centre error (px)";
    ce.ymin = 0;
    ce.ymax = 60;
    for (const auto &a : r.aggs) {
        if (a.traces.empty())
            continue;
        PlotSeries ps;
        ps.label = a.name;
        for (std::size_t k = 0; k < a.traces[0].err.size(); ++k) {
            ps.x.push_back((double)k + 1);
            ps.y.push_back(std::min(a.traces[0].err[k], 60.0));
        }
        ce.series.push_back(ps);
    }
    save_plot_png(ce, join_path(out, "center_error.png"));

    PlotSpec gp;
    gp.title = s.name + ": GOSPA per frame over the runs";
    gp.xlabel = "frame";
    gp.ylabel = "GOSPA (px)";
    gp.ymin = 0;
    for (const auto &a : r.aggs) {
        PlotSeries ps;
        ps.label = a.name;
        ps.thickness = 1;
        for (std::size_t k = 0; k < a.per_frame.frames(); ++k) {
            ps.x.push_back((double)k + 2);
            ps.y.push_back(a.per_frame.gospa_at(k));
        }
        gp.series.push_back(ps);
    }
    save_plot_png(gp, join_path(out, "gospa_per_frame.png"));

    PlotSpec tx;
    tx.title = s.name + ": x trajectory, first run (Fig. 7a / 9a)";
    tx.xlabel = "frame";
    tx.ylabel = "x (px)";
    {
        PlotSeries ps;
        ps.label = "truth";
        ps.color = cv::Scalar(0, 0, 0);
        ps.dashed = true;
        for (std::size_t k = 1; k < r.truth0_cx.size(); ++k) {
            ps.x.push_back((double)k);
            ps.y.push_back(r.truth0_cx[k]);
        }
        tx.series.push_back(ps);
    }
    for (const auto &a : r.aggs) {
        if (a.traces.empty())
            continue;
        PlotSeries ps;
        ps.label = a.name;
        ps.thickness = 1;
        for (std::size_t k = 0; k < a.traces[0].x.size(); ++k) {
            ps.x.push_back((double)k + 1);
            ps.y.push_back(a.traces[0].x[k]);
        }
        tx.series.push_back(ps);
    }
    save_plot_png(tx, join_path(out, "trajectory_x.png"));

    for (const auto &a : r.aggs) {
        if (a.name != "tsa" || a.traces.empty())
            continue;
        PlotSpec bp;
        bp.title = s.name + ": TSA beta per frame (Fig. 7-like)";
        bp.xlabel = "frame";
        bp.ylabel = "beta";
        bp.ymin = 0;
        bp.ymax = 6.2;
        const std::size_t nshow = std::min<std::size_t>(a.traces.size(), 3);
        for (std::size_t i = 0; i < nshow; ++i) {
            PlotSeries ps;
            ps.label = "run " + std::to_string(i);
            ps.thickness = 1;
            for (std::size_t k = 0; k < a.traces[i].beta.size(); ++k) {
                ps.x.push_back((double)k + 1);
                ps.y.push_back(a.traces[i].beta[k]);
            }
            bp.series.push_back(ps);
        }
        PlotSeries mean;
        mean.label = "mean over runs";
        mean.color = cv::Scalar(0, 0, 0);
        for (std::size_t k = 0; k < a.traces[0].beta.size(); ++k) {
            double sum = 0;
            int n = 0;
            for (const auto &t : a.traces)
                if (k < t.beta.size()) {
                    sum += t.beta[k];
                    ++n;
                }
            mean.x.push_back((double)k + 1);
            mean.y.push_back(n ? sum / n : NAN);
        }
        bp.series.push_back(mean);
        save_plot_png(bp, join_path(out, "beta.png"));
    }
}

void print_table(const Scenario &s, const json &sum)
{
    std::printf("%s (%s build): %d runs x %d frames, seeds %llu..%llu; frame success = IoU > %.2f and centre error < %.0f px"
                " (project: IoU > %.1f and < %.0f px); a run succeeds on >= %.0f%% of its frames\n",
                s.name.c_str(), numeric_name(), sum["runs"].get<int>(), s.scene.frames,
                (unsigned long long)sum["seed_first"].get<uint64_t>(), (unsigned long long)sum["seed_last"].get<uint64_t>(),
                s.iou_thr, s.center_thr, PROJECT_IOU, PROJECT_CENTER_PX, 100 * s.run_min_fraction);
    std::printf("%-8s %9s %9s %9s %9s %10s %10s %10s %10s %s\n", "tracker", "runs ok", "(project)", "frames ok",
                "(project)", "mean err", "median err", "us/frame", "cpu us", "re-acquired <= 15");
    for (const auto &t : sum["trackers"]) {
        std::string re = "-";
        if (t.contains("reacquired_within_15"))
            re = std::to_string(t["reacquired_within_15"].get<int>()) + "/" + std::to_string(t["runs"].get<int>());
        std::printf("%-8s %5d/%-3d %5d/%-3d %9.3f %9.3f %10.2f %10.2f %10.0f %10.0f %s\n",
                    t["tracker"].get<std::string>().c_str(), t["runs_succeeded"].get<int>(), t["runs"].get<int>(),
                    t["runs_succeeded_project"].get<int>(), t["runs"].get<int>(), t["success_rate"].get<double>(),
                    t["success_rate_project"].get<double>(), t["mean_center_error"].get<double>(),
                    t["median_center_error"].get<double>(), t["us_per_frame"].get<double>(),
                    t["cpu_us_per_frame"].get<double>(), re.c_str());
    }
}

// ------------------------------------------------------------------------- colour sequences
class ColourInput {
public:
    explicit ColourInput(const std::string &path)
    {
        if (fs::is_directory(path)) {
            for (auto &e : fs::directory_iterator(path)) {
                std::string ext = e.path().extension().string();
                std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
                if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".ppm" || ext == ".tif")
                    files_.push_back(e.path().string());
            }
            std::sort(files_.begin(), files_.end());
            if (files_.empty())
                throw InputError(path + ": no images in the folder");
        } else {
            std::string p = path;
            if (!fs::exists(p)) {
                try {
                    p = find_data_file(path);  // e.g. "vtest.avi" from opencv-doc
                } catch (const InputError &) {
                    throw InputError(path + ": no such file or directory");
                }
            }
            if (!cap_.open(p))
                throw InputError(p + ": cannot open video");
            fps_ = cap_.get(cv::CAP_PROP_FPS);
        }
    }
    bool next(cv::Mat &bgr)
    {
        if (!files_.empty()) {
            if (idx_ >= files_.size())
                return false;
            bgr = cv::imread(files_[idx_++], cv::IMREAD_COLOR);
            if (bgr.empty())
                throw InputError(files_[idx_ - 1] + ": cannot read image");
            return true;
        }
        return cap_.read(bgr) && !bgr.empty();
    }
    double fps() const { return fps_ > 0 ? fps_ : 25.0; }
    /** Frames in the sequence (a video's own count, which may be approximate), or -1. */
    long count() const
    {
        if (!files_.empty())
            return (long)files_.size();
        const double n = cap_.get(cv::CAP_PROP_FRAME_COUNT);
        return n > 0 ? (long)n : -1;
    }

private:
    std::vector<std::string> files_;
    std::size_t idx_ = 0;
    cv::VideoCapture cap_;
    double fps_ = 0;
};

std::vector<cv::Point> parse_points(const std::string &text, bool is_box, const std::string &what)
{
    std::vector<double> v;
    std::string t = text;
    for (char &c : t)
        if (c == ',' || c == ';' || c == '[' || c == ']' || c == '(' || c == ')')
            c = ' ';
    std::istringstream is(t);
    double d;
    while (is >> d)
        v.push_back(d);
    if (!is.eof())
        throw InputError(what + ": expected numbers, got \"" + text + "\"");
    if (is_box) {
        if (v.size() != 4 || v[2] <= 0 || v[3] <= 0)
            throw InputError(what + ": expected x,y,w,h with w, h > 0");
        return box_poly(cv::Rect2d(v[0], v[1], v[2], v[3]));
    }
    if (v.size() < 6 || v.size() % 2)
        throw InputError(what + ": expected at least 3 x,y pairs");
    std::vector<cv::Point> p;
    for (std::size_t i = 0; i < v.size(); i += 2)
        p.emplace_back((int)std::lround(v[i]), (int)std::lround(v[i + 1]));
    return p;
}

struct TrackRun {
    std::vector<cv::Point> init;
    PftParams params;
    std::string label = "tsa";
    std::vector<std::string> compare;  // more trackers on the same frames (names of make_tracker)
    std::string out;
    int frames = 0;
    bool video = true;
    int snapshots = 4;             // evenly spaced over the run (needs the frame count)
    std::vector<int> snapshot_at;  // and these frames (1-based)
    std::string snapshot_format = "png";
    double snapshot_scale = 1.0;
    bool quiet = false;
    std::vector<TruthRow> truth;  // optional
};

/* The frames to write snapshots of: n evenly spaced over 1..total (the last included) and the
 * listed ones. With an unknown total (a stream) every 100th frame, at most n. */
std::vector<int> snapshot_frames(const TrackRun &tr, long total)
{
    std::vector<int> v = tr.snapshot_at;
    if (tr.snapshots > 0) {
        for (int i = 0; i < tr.snapshots; ++i)
            v.push_back(total > 0 ? (int)std::max<long>(1, total * (i + 1) / tr.snapshots) : 100 * (i + 1));
    }
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

void write_snapshot(const TrackRun &tr, const cv::Mat &ov, int frame)
{
    cv::Mat img = ov;
    if (tr.snapshot_scale != 1.0)
        cv::resize(ov, img, cv::Size(), tr.snapshot_scale, tr.snapshot_scale, cv::INTER_AREA);
    char name[64];
    std::snprintf(name, sizeof name, "snap_%04d.%s", frame, tr.snapshot_format.c_str());
    AtomicPath p(join_path(tr.out, name));
    std::vector<int> opt;
    if (tr.snapshot_format == "jpg")
        opt = {cv::IMWRITE_JPEG_QUALITY, 85};
    if (!cv::imwrite(p.tmp(), img, opt))
        throw InputError(p.final_path() + ": cannot write");
    p.commit();
}

double median_of(std::vector<double> v)
{
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double mean_of(const std::vector<double> &v)
{
    return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / (double)v.size();
}

/* Tracks the sequence: tracks.csv, tracks.json, and (when asked) overlay.avi and snapshots.
 * Overlays are drawn only for the video and the snapshot frames, and no frame is kept. */
int do_track(ColourInput &in, const TrackRun &tr, const std::string &source)
{
    ensure_dir(tr.out);
    cv::setNumThreads(0);  // OpenCV's trackers on this thread: their thread CPU time is complete
    cv::Mat f0;
    if (!in.next(f0))
        throw InputError(source + ": no frames");
    std::vector<std::string> names = {tr.label};
    for (const auto &n : tr.compare)
        if (std::find(names.begin(), names.end(), n) == names.end())
            names.push_back(n);
    std::vector<std::unique_ptr<Tracker>> trk;
    for (const auto &n : names) {
        trk.push_back(make_tracker(n, tr.params, f0.cols, f0.rows));
        trk.back()->init(f0, tr.init);
    }
    const std::size_t nt = trk.size();
    AtomicPath vid(join_path(tr.out, "overlay.avi"));
    cv::VideoWriter vw;
    if (tr.video) {
        vw.open(vid.tmp(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), in.fps(), f0.size());
        if (!vw.isOpened())
            throw InputError(vid.final_path() + ": cannot write video");
    }
    const long known = in.count();
    const long total = tr.frames > 0 ? (known > 0 ? std::min<long>(known, tr.frames) : tr.frames) : known;
    const std::vector<int> snaps = snapshot_frames(tr, total);
    std::size_t next_snap = 0;
    std::vector<std::vector<std::string>> rows(nt);
    std::vector<std::vector<double>> us(nt), cpu(nt);
    std::vector<std::map<int, int>> states(nt);
    int k = 0;
    cv::Mat f;
    if (tr.video || (!snaps.empty() && snaps[0] == 1)) {
        cv::Mat ov = f0.clone();
        cv::polylines(ov, tr.init, true, cv::Scalar(0, 255, 0), 1);
        if (tr.video)
            vw.write(ov);
        if (!snaps.empty() && snaps[0] == 1) {
            write_snapshot(tr, ov, 1);
            ++next_snap;
        }
    }
    std::vector<TrackOut> outs(nt);
    while ((tr.frames <= 0 || k + 1 < tr.frames) && in.next(f)) {
        ++k;
        for (std::size_t i = 0; i < nt; ++i) {
            TrackOut &o = outs[i];
            o = TrackOut();
            const double c0 = thread_cpu_us();
            auto t0 = std::chrono::steady_clock::now();
            trk[i]->update(f, o);
            auto t1 = std::chrono::steady_clock::now();
            cpu[i].push_back(thread_cpu_us() - c0);
            us[i].push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
            states[i][o.state]++;
            char buf[320];
            std::snprintf(buf, sizeof buf,
                          "%d,%.3f,%.3f,%.1f,%.1f,%.1f,%.1f,%.4f,%.4f,%.4f,%d,%d,%d,%.1f,%.2f,%.2f,%.1f", k + 1,
                          o.center.x, o.center.y, o.box.x, o.box.y, o.box.width, o.box.height, o.rho, o.rho_pioneer,
                          o.beta, o.state, o.alive, o.template_updated ? 1 : 0, us[i].back(), o.pioneer.x,
                          o.pioneer.y, cpu[i].back());
            rows[i].push_back(buf);
        }
        while (next_snap < snaps.size() && snaps[next_snap] < k + 1)
            ++next_snap;
        const bool snap = next_snap < snaps.size() && snaps[next_snap] == k + 1;
        if (tr.video || snap) {
            cv::Mat ov = f.clone();
            if (nt == 1) {
                const cv::Rect2d *tb = (std::size_t)k < tr.truth.size() ? &tr.truth[k].box : nullptr;
                draw_overlay(ov, outs[0], tb, k + 1, trk[0]->name());
            } else {
                if ((std::size_t)k < tr.truth.size())
                    cv::rectangle(ov, tr.truth[k].box, cv::Scalar(255, 255, 255), 1);
                draw_compare(ov, outs, names, k + 1);
            }
            if (tr.video)
                vw.write(ov);
            if (snap) {
                write_snapshot(tr, ov, k + 1);
                ++next_snap;
            }
        }
    }
    if (tr.video) {
        vw.release();
        vid.commit();
    }
    static const char *header = "frame,x,y,box_x,box_y,box_w,box_h,rho,rho_pioneer,beta,state,alive,"
                                "template_updated,us,pioneer_x,pioneer_y,cpu_us\n";
    static const char *state_names[] = {"idle", "tracking", "pioneer_only", "weak", "lost", "out_of_view",
                                        "reacquired"};
    json per = json::array();
    for (std::size_t i = 0; i < nt; ++i) {
        auto write_rows = [&](std::ostream &os) {
            os << header;
            for (auto &r : rows[i])
                os << r << "\n";
        };
        if (i == 0)
            write_text_atomic(join_path(tr.out, "tracks.csv"), write_rows);
        if (nt > 1)
            write_text_atomic(join_path(tr.out, "tracks_" + names[i] + ".csv"), write_rows);
        json st = json::object();
        for (auto &kv : states[i])
            st[kv.first >= 0 && kv.first <= 6 ? state_names[kv.first] : "other"] = kv.second;
        per.push_back({{"tracker", trk[i]->name()}, {"us_per_frame_mean", mean_of(us[i])},
                       {"us_per_frame_median", median_of(us[i])}, {"cpu_us_per_frame_mean", mean_of(cpu[i])},
                       {"cpu_us_per_frame_median", median_of(cpu[i])}, {"states", st},
                       {"workspace_bytes", trk[i]->memory_bytes()}});
    }
    const json &p0 = per[0];
    json j = {{"source", source}, {"tracker", trk[0]->name()}, {"numeric", numeric_name()},
              {"frames", k + 1}, {"width", f0.cols}, {"height", f0.rows},
              {"us_per_frame_mean", p0["us_per_frame_mean"]}, {"us_per_frame_median", p0["us_per_frame_median"]},
              {"cpu_us_per_frame_mean", p0["cpu_us_per_frame_mean"]},
              {"cpu_us_per_frame_median", p0["cpu_us_per_frame_median"]},
              {"fps_equivalent", p0["us_per_frame_mean"].get<double>() > 0 ? 1e6 / p0["us_per_frame_mean"].get<double>() : 0.0},
              {"states", p0["states"]}, {"workspace_bytes", p0["workspace_bytes"]},
              {"params", pft_params_json(tr.params)}};
    if (nt > 1)
        j["trackers"] = per;
    write_json_atomic(join_path(tr.out, "tracks.json"), j);
    if (!tr.quiet)
        for (const auto &t : per)
            std::printf("pft track: %s, %d frames %dx%d, %s: %.0f us/frame wall mean (%.0f median), %.0f us CPU mean "
                        "(%.0f median), states %s -> %s\n",
                        source.c_str(), k + 1, f0.cols, f0.rows, t["tracker"].get<std::string>().c_str(),
                        t["us_per_frame_mean"].get<double>(), t["us_per_frame_median"].get<double>(),
                        t["cpu_us_per_frame_mean"].get<double>(), t["cpu_us_per_frame_median"].get<double>(),
                        t["states"].dump().c_str(), tr.out.c_str());
    return 0;
}

// --------------------------------------------------------------------------- the handler
class TsaHandler : public KindHandler {
public:
    int sim(const Options &o) override
    {
        Scenario s = load_scenario(o);
        const uint64_t seed = o.seed.value_or(s.scene.seed_base);
        std::vector<cv::Mat> frames;
        std::vector<TruthRow> truth;
        render_sequence(s.scene, seed, frames, truth, o.frames ? (int)o.frames : -1);
        ensure_dir(o.out);
        for (std::size_t k = 0; k < frames.size(); ++k) {
            char name[64];
            std::snprintf(name, sizeof name, "frame_%04zu.png", k + 1);
            AtomicPath p(join_path(o.out, name));
            if (!cv::imwrite(p.tmp(), frames[k]))
                throw InputError(p.final_path() + ": cannot write");
            p.commit();
        }
        write_text_atomic(join_path(o.out, "truth.csv"), [&](std::ostream &os) {
            CsvWriter w(os);
            for (const char *h : {"frame", "cx", "cy", "box_x", "box_y", "box_w", "box_h", "camera_vx", "gain", "blur_px",
                                  "reversal"})
                w.field(h);
            w.end_row();
            for (auto &t : truth) {
                w.field(t.frame + 1).field(t.cx).field(t.cy).field(t.box.x).field(t.box.y).field(t.box.width)
                    .field(t.box.height).field(t.cam_vx).field(t.gain).field(t.blur_px).field(t.reversal ? 1 : 0);
                w.end_row();
            }
        });
        json side = {{"scenario", o.scenario}, {"seed", seed}, {"frames", frames.size()},
                     {"format", "png"}, {"pattern", "frame_%04u.png"}, {"truth", "truth.csv"}};
        write_json_atomic(join_path(o.out, "sequence.json"), side);
        if (!o.quiet)
            std::printf("pft sim (tsa): %zu frames %dx%d, seed %llu -> %s\n", frames.size(), s.scene.width,
                        s.scene.height, (unsigned long long)seed, o.out.c_str());
        return 0;
    }

    int run(const Options &o) override
    {
        Scenario s = load_scenario(o);
        TrackRun tr;
        tr.params = s.tracker;
        tr.label = s.tracker.motion;
        tr.out = o.out.empty() ? "pft_run_out" : o.out;
        tr.frames = (int)o.frames;
        tr.video = !o.no_video;
        tr.quiet = o.quiet;
        // truth: the sim sidecar, else --truth
        std::string truth_csv = o.truth;
        if (truth_csv.empty() && fs::exists(join_path(o.sequence, "truth.csv")))
            truth_csv = join_path(o.sequence, "truth.csv");
        if (truth_csv.empty())
            throw InputError("tsa run needs a `pft sim` directory (truth.csv gives the initial box) or --truth CSV; "
                             "for a video with a box use `pft track`");
        std::ifstream is(truth_csv);
        if (!is)
            throw InputError(truth_csv + ": cannot open");
        std::string line;
        std::getline(is, line);
        while (std::getline(is, line)) {
            std::vector<double> v;
            std::string cell;
            std::istringstream ls(line);
            while (std::getline(ls, cell, ','))
                v.push_back(std::atof(cell.c_str()));
            if (v.size() < 7)
                throw InputError(truth_csv + ": expected frame,cx,cy,box_x,box_y,box_w,box_h");
            tr.truth.push_back({(int)v[0] - 1, v[1], v[2], cv::Rect2d(v[3], v[4], v[5], v[6]), v.size() > 7 ? v[7] : 0});
        }
        if (tr.truth.empty())
            throw InputError(truth_csv + ": no rows");
        tr.init = box_poly(tr.truth[0].box);
        ColourInput in(o.sequence);
        return do_track(in, tr, o.sequence);
    }

    int track(const Options &o) override
    {
        TrackCli t;
        t.sequence = o.sequence;
        t.box = o.track.box;
        t.polygon = o.track.polygon;
        t.init = o.track.init;
        t.out = o.out.empty() ? "pft_track_out" : o.out;
        t.scenario = o.scenario_path;
        t.motion = o.track.motion;
        t.particles = (int)o.particles;
        t.set = o.track.set;
        t.compare = o.track.compare;
        t.frames = (int)o.frames;
        t.snapshots = o.track.snapshots;
        t.max_target = o.track.max_target;
        t.snapshot_at = o.track.snapshot_at;
        t.snapshot_format = o.track.snapshot_format;
        t.snapshot_scale = o.track.snapshot_scale;
        t.video = o.track.video;
        t.no_video = o.no_video;
        t.quiet = o.quiet;
        return run_track(t);
    }

    int eval(const Options &o) override { return evaluate_cmd(o, false); }
    int bench(const Options &o) override { return evaluate_cmd(o, true); }

    int demo(const Options &o) override
    {
        Options d = o;
        d.runs = 1;
        return evaluate_cmd(d, false);
    }

    int selftest(const Options &) override
    {
        int fails = 0;
        // sim determinism and truth sanity on a short sequence (needs opencv-doc's aero1.jpg)
        try {
            SceneSpec s;
            s.frames = 12;
            s.swing_speed = 4;
            s.swing_accel = 1;
            std::vector<cv::Mat> a, b;
            std::vector<TruthRow> ta, tb;
            render_sequence(s, 3, a, ta);
            render_sequence(s, 3, b, tb);
            bool same = a.size() == b.size();
            for (std::size_t k = 0; same && k < a.size(); ++k)
                same = cv::norm(a[k], b[k], cv::NORM_INF) == 0;
            if (!same) {
                std::printf("FAIL: tsa sim is not deterministic for a fixed seed\n");
                ++fails;
            }
            for (auto &t : ta)
                if (t.box.width < 20 || t.box.width > 40 || t.box.height < 20 || t.box.height > 40 ||
                    std::abs(t.cx - (t.box.x + t.box.width / 2)) > 1.0) {
                    std::printf("FAIL: tsa truth box implausible at frame %d\n", t.frame);
                    ++fails;
                    break;
                }
            // the TSA tracker follows the first frames of the default scene
            PftParams p;
            auto trk = make_tracker("tsa", p, s.width, s.height);
            Scenario sc;
            sc.scene = s;
            RunTrace r = run_one(*trk, a, ta, sc);
            double worst = *std::max_element(r.err.begin(), r.err.end());
            if (worst > 8.0) {
                std::printf("FAIL: TSA centre error %.1f px on the first frames of the default scene\n", worst);
                ++fails;
            }
        } catch (const std::exception &e) {
            std::printf("FAIL: tsa selftest: %s\n", e.what());
            ++fails;
        }
        std::printf("tsa selftest: %s\n", fails ? "FAILED" : "passed");
        return fails ? 1 : 0;
    }

private:
    /** The trackers of `names` this build has (OpenCV's need the contrib tracking module). */
    static std::vector<std::string> usable(const std::vector<std::string> &names, bool quiet)
    {
        std::vector<std::string> use;
        for (auto &n : names) {
            const std::string b = n.substr(0, n.find('+'));  // a variant NAME+field=value of make_tracker
            if ((b == n && make_cv_tracker(n)) || b == "tsa" || b == "ts" || b == "ncv" || b == "ncv100" ||
                b == "ncv200" || b == "tsa_paper")
                use.push_back(n);
            else if (!quiet)
                std::printf("(skipping %s: OpenCV contrib tracking module not built in)\n", n.c_str());
        }
        return use;
    }

    /** The settings part of summary.json (the common header, then the tsa fields); a partial
     *  summary carries the same, so pft merge can check that its shards belong together. */
    static json eval_head(const Options &o, const Scenario &s, const Campaign &c, unsigned threads,
                          const CampaignTiming &t)
    {
        SummaryHead h;
        h.kind = "tsa";
        h.scenario = s.name;
        h.scenario_file = s.file;
        h.description = s.description;
        h.tag = o.tag;
        h.scenario_json = o.scenario;
        json head = summary_header(o, c, h, threads, t);
        head.update(settings_json(s, (int)c.runs, c.base_seed, "eval"));
        return head;
    }

    int evaluate_cmd(const Options &o, bool bench)
    {
        Scenario s = load_scenario(o);
        const std::vector<std::string> use = usable(bench ? s.bench_trackers : s.eval_trackers, o.quiet);
        const unsigned runs = o.runs ? o.runs : (bench ? 1u : (unsigned)s.runs);
        Campaign c = make_campaign(runs, o.seed.value_or(s.scene.seed_base), bench ? std::string() : o.shard);
        if (c.partial() && o.out.empty())
            throw InputError("eval --shard " + o.shard + ": --out DIR is required (the partial summary goes there)");
        // bench times trackers one run after another on one thread; eval runs in parallel
        const unsigned threads = bench ? 1u : resolve_threads(o.threads);
        CampaignTiming t;
        std::vector<RunRecord> recs = run_traces(s, use, c, threads, o.frames ? (int)o.frames + 1 : -1,
                                                 progress_wanted(o.progress) && !o.quiet, &t);
        if (bench) {
            json sum = summary_json(s, aggregate(use, recs, 8), (int)runs, c.base_seed, "bench");
            if (!o.tag.empty())
                sum["tag"] = o.tag;
            return finish(o, s, use, sum, recs, true);
        }
        json head = eval_head(o, s, c, threads, t);
        if (c.partial()) {
            json rj = json::array();
            for (const RunRecord &r : recs)
                rj.push_back(r.to_json());
            ensure_dir(o.out);
            std::string path = write_partial(o.out, head, o, c, rj);
            if (!o.quiet)
                std::printf("tsa eval: runs %zu..%zu of %u (shard %u/%u), %.1f s wall; wrote %s (pft merge combines "
                            "the shards)\n",
                            c.first, c.end - 1, c.runs, c.shard, c.shards, t.wall_s, path.c_str());
            return 0;
        }
        return finish(o, s, use, head, recs, false);
    }

public:
    int merge(const Options &o, const MergedRuns &m) override
    {
        Options eo = m.eval_options(o);
        Scenario s = load_scenario(eo);
        const std::vector<std::string> use = usable(s.eval_trackers, true);
        std::vector<RunRecord> recs;
        for (const json &r : m.runs)
            recs.push_back(RunRecord::from_json(r));
        json head = eval_head(eo, s, m.campaign, m.threads, m.timing);
        add_merge_fields(head, m);
        if (!o.quiet)
            std::printf("pft merge: %s, %u runs from %zu shards\n", s.name.c_str(), m.campaign.runs, m.shards.size());
        return finish(eo, s, use, head, recs, false);
    }

private:
    /** The summary from the runs (head: its settings part; bench: the whole bench.json), the
     *  table, and with --out the JSON, the plots and the overlay snapshots. Shared by eval and
     *  merge, so both give the same summary from the same runs. */
    int finish(const Options &o, const Scenario &s, const std::vector<std::string> &use, json sum,
               const std::vector<RunRecord> &recs, bool bench)
    {
        EvalResult r = aggregate(use, recs, 8);
        if (!bench)
            sum["trackers"] = trackers_json(s, r);
        const uint64_t seed = sum["seed_first"].get<uint64_t>();
        if (!o.quiet)
            print_table(s, sum);
        if (!o.out.empty()) {
            ensure_dir(o.out);
            write_json_atomic(join_path(o.out, bench ? "bench.json" : "summary.json"), sum);
            write_plots(s, r, o.out);
            // overlay snapshots of the first run of TSA (frames 1/4, 1/2, 3/4, last)
            {
                std::vector<cv::Mat> frames;
                std::vector<TruthRow> truth;
                render_sequence(s.scene, seed, frames, truth, o.frames ? (int)o.frames + 1 : -1);
                PftParams p = s.tracker;
                p.seed = seed;
                auto t = make_tracker(s.eval_trackers.empty() ? "tsa" : s.eval_trackers[0], p, s.scene.width,
                                      s.scene.height);
                t->init(frames[0], box_poly(truth[0].box));
                const std::size_t n = frames.size();
                for (std::size_t k = 1; k < n; ++k) {
                    TrackOut out;
                    t->update(frames[k], out);
                    if (k == n / 4 || k == n / 2 || k == 3 * n / 4 || k == n - 1) {
                        cv::Mat ov = frames[k].clone();
                        draw_overlay(ov, out, &truth[k].box, (int)k + 1, t->name());
                        char name[64];
                        std::snprintf(name, sizeof name, "overlay_%04zu.jpg", k + 1);
                        AtomicPath pth(join_path(o.out, name));
                        cv::imwrite(pth.tmp(), ov, {cv::IMWRITE_JPEG_QUALITY, 85});
                        pth.commit();
                    }
                }
            }
        }
        return 0;
    }
};

PFT_REGISTER_KIND("tsa", TsaHandler);
// scenario files written with the earlier kind name
PFT_REGISTER_KIND_ALIAS("vis", "tsa", tsa_vis);

}  // namespace

int run_track(const TrackCli &t)
{
    TrackRun tr;
    int given = !t.box.empty() + !t.polygon.empty() + !t.init.empty();
    if (given != 1)
        throw InputError("track: give exactly one of --box, --polygon, --init");
    if (!t.box.empty())
        tr.init = parse_points(t.box, true, "--box");
    else if (!t.polygon.empty())
        tr.init = parse_points(t.polygon, false, "--polygon");
    else {
        json j = load_json_file(t.init);
        Field f(j, t.init);
        f.only({"box", "polygon"});
        if (f.has("box")) {
            auto v = f.numbers("box", 4);
            tr.init = parse_points(std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]) + "," +
                                       std::to_string(v[3]),
                                   true, t.init + ": box");
        } else if (f.has("polygon")) {
            Field p = f.at("polygon");
            for (std::size_t i = 0; i < p.size(); ++i) {
                Field q = p.at(i);
                if (q.size() != 2)
                    q.fail("expected [x, y]");
                tr.init.emplace_back((int)std::lround(q.at(0).as_number()), (int)std::lround(q.at(1).as_number()));
            }
            if (tr.init.size() < 3)
                p.fail("expected at least 3 points");
        } else {
            f.fail("expected \"box\" or \"polygon\"");
        }
    }
    const cv::Rect2d br = polygon_extent(tr.init);
    // parameters: the scenario's tracker object, then the flags
    if (!t.scenario.empty()) {
        const json sc = load_json_file(t.scenario);
        if (sc.contains("tracker"))
            tr.params = parse_pft_params(sc.at("tracker"), t.scenario, "tracker");
    }
    if (!t.motion.empty())
        tr.params.motion = t.motion;
    if (t.particles > 0)
        tr.params.particles = t.particles;
    for (const auto &a : t.set)
        set_pft_param(tr.params, a, "--set");
    const int side = (int)std::ceil(std::max(br.width, br.height));
    tr.params.max_target = t.max_target > 0 ? t.max_target
                                            : (t.scenario.empty() || side + 1 > tr.params.max_target
                                                   ? std::min(255, std::max(16, 2 * (side + 1)))
                                                   : tr.params.max_target);
    tr.label = tr.params.motion;
    tr.compare = t.compare;
    tr.out = t.out;
    tr.frames = t.frames;
    tr.video = t.video && !t.no_video;
    tr.snapshots = t.snapshots;
    tr.snapshot_at = t.snapshot_at;
    tr.snapshot_format = t.snapshot_format;
    tr.snapshot_scale = t.snapshot_scale;
    tr.quiet = t.quiet;
    ColourInput in(t.sequence);
    return do_track(in, tr, t.sequence);
}

}  // namespace pft::host::tsa
