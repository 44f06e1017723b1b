// pft: the host tool. Subcommands sim, run, eval, bench, demo, track (dispatched to the handler
// of the scenario's "kind"; track without --scenario: kind tsa), merge (partial summaries of `eval --shard K/N`, dispatched by their
// kind), selftest (every registered kind), and plot (merges eval summaries into one figure).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "../common/campaign.hpp"
#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../common/plot.hpp"
#include "../common/registry.hpp"

using namespace pft::host;

namespace {

struct PlotOptions {
    std::vector<std::string> files;
    std::string out = "plot.png", x = "/snr_db", y = "/averaged/rmse", group = "/tag",
                floor = "/averaged/pcrlb", err, title, xlabel, ylabel;
    double ymax = 0.0;
};

json pointer_value(const json &j, const std::string &ptr, const std::string &file)
{
    try {
        return j.at(json::json_pointer(ptr));
    } catch (const std::exception &) {
        throw InputError(file + ": no value at JSON pointer " + ptr);
    }
}

int cmd_plot(const PlotOptions &p)
{
    struct Pt {
        double x, y, e;
    };
    std::map<std::string, std::vector<Pt>> groups;
    std::map<double, double> floor;
    std::vector<PlotSeries> curves;
    for (const auto &f : p.files) {
        json j = load_json_file(f);
        json yv = pointer_value(j, p.y, f);
        json gv = p.group.empty() ? json(f) : pointer_value(j, p.group, f);
        std::string g = gv.is_string() ? gv.get<std::string>() : gv.dump();
        json ev = p.err.empty() ? json(nullptr) : pointer_value(j, p.err, f);
        if (yv.is_array()) {
            // a per-frame curve (e.g. /averaged/existence_probability): one series per file
            PlotSeries s;
            s.label = g;
            for (std::size_t k = 0; k < yv.size(); ++k) {
                s.x.push_back(static_cast<double>(k + 1));
                s.y.push_back(null_to_nan(yv[k]));
                if (ev.is_array())
                    s.err.push_back(k < ev.size() ? null_to_nan(ev[k]) : NAN);
            }
            curves.push_back(s);
            continue;
        }
        json xv = pointer_value(j, p.x, f);
        if (!xv.is_number())
            throw InputError(f + ": " + p.x + " is not a number");
        groups[g].push_back({xv.get<double>(), null_to_nan(yv), null_to_nan(ev)});
        if (!p.floor.empty()) {
            json fv = pointer_value(j, p.floor, f);
            if (fv.is_number())
                floor[xv.get<double>()] = fv.get<double>();
        }
    }
    PlotSpec spec;
    spec.title = p.title;
    spec.xlabel = p.xlabel.empty() ? p.x : p.xlabel;
    spec.ylabel = p.ylabel.empty() ? p.y : p.ylabel;
    spec.ymin = 0.0;
    if (p.ymax > 0)
        spec.ymax = p.ymax;
    if (!curves.empty()) {
        if (!groups.empty())
            throw InputError("plot: --y must be a number in every summary or an array in every one");
        std::stable_sort(curves.begin(), curves.end(),
                         [](const PlotSeries &a, const PlotSeries &b) { return natural_less(a.label, b.label); });
        spec.series = curves;
        if (p.xlabel.empty())
            spec.xlabel = "frame";
        save_plot_png(spec, p.out);
        std::printf("pft plot: %zu curves -> %s\n", curves.size(), p.out.c_str());
        return 0;
    }
    // legend entries in natural order: "N=6000" before "N=36000"
    std::vector<std::string> order;
    for (const auto &kv : groups)
        order.push_back(kv.first);
    std::stable_sort(order.begin(), order.end(), natural_less);
    for (const auto &g : order) {
        auto pts = groups[g];
        std::sort(pts.begin(), pts.end(), [](const Pt &a, const Pt &b) { return a.x < b.x; });
        PlotSeries s;
        s.label = g;
        s.markers = true;
        for (auto &pt : pts) {
            s.x.push_back(pt.x);
            s.y.push_back(pt.y);
            if (!p.err.empty())
                s.err.push_back(pt.e);
        }
        spec.series.push_back(s);
    }
    if (!floor.empty()) {
        PlotSeries s;
        s.label = "PCRLB floor";
        s.dashed = true;
        s.color = cv::Scalar(0, 0, 0);
        for (auto &kv : floor) {
            s.x.push_back(kv.first);
            s.y.push_back(kv.second);
        }
        spec.series.push_back(s);
    }
    save_plot_png(spec, p.out);
    std::printf("pft plot: %zu summaries, %zu series -> %s\n", p.files.size(), order.size(), p.out.c_str());
    return 0;
}

void add_scenario(CLI::App *c, Options &o, bool required)
{
    auto *opt = c->add_option("--scenario", o.scenario_path, "scenario file (JSON; its \"kind\" selects the module)");
    if (required)
        opt->required();
}

}  // namespace

int main(int argc, char **argv)
{
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_WARNING);
    CLI::App app{"pft - host tools of pftrack: simulate, run, evaluate and benchmark trackers"};
    app.require_subcommand(1);
    bool want_version = false;
    app.add_flag("--version", want_version, "print the version (library and git) and exit");
    Options o;
    PlotOptions po;
    std::string kind_filter;
    uint64_t seed = 0;
    std::vector<std::string> partials;
    o.argv.assign(argv, argv + argc);

    auto common = [&](CLI::App *c) {
        c->add_flag("--progress", o.progress, "draw the progress bar even when stderr is not a terminal");
        c->add_flag("-q,--quiet", o.quiet, "print less");
    };
    auto filter_opts = [&](CLI::App *c) {
        c->add_option("--filter", o.filter_kind, "override the filter kind")->check(CLI::IsMember({"rbpf", "pf"}));
        c->add_option("--particles", o.particles, "override the particle count (search layer / single filter)")
            ->check(CLI::Range(1u, 4194304u));
        c->add_option("--preset", o.preset, "override the scenario's parameter preset (tbd: paper | recommended | bounded)")
            ->check(CLI::IsMember({"paper", "recommended", "bounded"}));
        c->add_flag("--single", o.single, "single-target filter (existence decision P > theta1) instead of the manager");
        c->add_option("--seed", seed, "seed (sim/demo/bench: the sequence; eval: base seed, run i uses seed + i)");
    };
    auto set_metric_opts = [&](CLI::App *c) {
        c->add_option_function<double>("--gospa-c", [&](const double &v) { o.gospa_c = v; },
                                       "GOSPA/OSPA cut-off c (default: the kind's, e.g. tbd: d_assoc = 3 px)")
            ->check(CLI::PositiveNumber);
        c->add_option_function<double>("--gospa-p", [&](const double &v) { o.gospa_p = v; },
                                       "GOSPA/OSPA order p >= 1 (default 2)")
            ->check(CLI::Range(1.0, 1e6));
    };

    CLI::App *sim = app.add_subcommand("sim", "simulate a scenario: frames (16-bit PGM or raw float32), truth CSV, sidecar JSON");
    add_scenario(sim, o, true);
    sim->add_option("--out", o.out, "output directory")->required();
    sim->add_option("--format", o.format, "pgm (16-bit, default) or raw (tbd: float32; tbd_ir: u16)")->check(CLI::IsMember({"pgm", "raw"}));
    filter_opts(sim);
    sim->add_option("--backgrounds", o.backgrounds, "tbd_ir: folder of background images (replaces the scenario's background.folder)");
    common(sim);

    CLI::App *run = app.add_subcommand("run", "track a recorded sequence; write tracks CSV/JSON and an overlay video");
    add_scenario(run, o, false);
    run->add_option("--sequence", o.sequence, "pft sim directory, PGM pattern (dir/f%04u.pgm), video file, image folder or (with --raw) u16 dump")->required();
    run->add_option("--raw", o.raw, "--sequence is a headerless u16 dump: WxH[:bits][:le|be][:skip=BYTES]");
    run->add_option("--truth", o.truth, "ground-truth CSV (tbd: frame,target,x,y,vx,vy,I,present; tbd_ir: frame,id,x,y,snr_db,kind)");
    run->add_option("--out", o.out, "output directory (default pft_run_out)");
    run->add_option("--scale", o.scale, "overlay upscale factor (default: about 480 px)")->check(CLI::Range(1, 64));
    run->add_flag("--no-video", o.no_video, "do not write the overlay video");
    run->add_option("--residual-out", o.residual_out, "tbd_ir: write the residual the TBD manager sees, every frame (headerless int16, Q8.8 sigma units, width x height per frame)");
    run->add_option("--stage-out", o.stage_out, "tbd_ir: write the stage's statistics, one CSV row per frame (frame, seq, shift_x_px, shift_y_px, flags, sigma_mean, n_masked)");
    run->add_option("--frames", o.frames, "stop after this many frames")->check(CLI::Range(1u, 100000000u));
    run->add_option("--bits", o.bits, "tbd_ir: the sensor's significant bits (default: the input's declaration - sidecar, --raw bits, PGM maxval - else detected from the first 8 frames)")->check(CLI::Range(8, 16));
    filter_opts(run);
    set_metric_opts(run);
    common(run);

    CLI::App *ev = app.add_subcommand("eval", "Monte Carlo evaluation: JSON summary and PNG plots");
    add_scenario(ev, o, true);
    ev->add_option("--runs", o.runs, "Monte Carlo runs (default: the scenario's, else 100)")->check(CLI::Range(1u, 10000000u));
    ev->add_option("--threads", o.threads, "worker threads (default: hardware concurrency)")->check(CLI::Range(1u, 1024u));
    ev->add_option("--out", o.out, "output directory");
    ev->add_option("--tag", o.tag, "label of this configuration in merged plots");
    ev->add_option("--shard", o.shard, "compute shard K of N (runs [(K-1)R/N, KR/N)) and write OUT/partial_K_of_N.json for pft merge");
    filter_opts(ev);
    set_metric_opts(ev);
    ev->add_option("--backgrounds", o.backgrounds, "tbd_ir: folder of background images (replaces the scenario's background.folder)");
    ev->add_option("--trace", o.trace, "tbd_ir: write a diagnostic trace of the TBD manager per run into this folder (s<seed>_targets.csv, s<seed>_tracks.csv; the summary is unchanged)");
    common(ev);

    CLI::App *be = app.add_subcommand("bench", "per-frame time, particles/s and workspace bytes (not a test)");
    add_scenario(be, o, true);
    be->add_option("--frames", o.frames, "frames per timed run (default: the scenario's)")->check(CLI::Range(1u, 10000000u));
    be->add_option("--runs", o.runs, "timed runs (default 1)")->check(CLI::Range(1u, 100000u));
    be->add_option("--out", o.out, "directory for bench.json");
    filter_opts(be);
    be->add_option("--backgrounds", o.backgrounds, "tbd_ir: folder of background images (replaces the scenario's background.folder)");
    be->add_option("--probe-out", o.probe_out, "tbd_ir: write the simulated frames (frames.u16), the pipeline's library configurations (probe.cfg) and its outputs per frame (expect.txt) for tests/tools/ir_probe -c into this folder");
    common(be);

    CLI::App *de = app.add_subcommand("demo", "simulate the default two-target scenario (or take --sequence), track it, print tracks and summary");
    add_scenario(de, o, false);
    de->add_option("--sequence", o.sequence, "track this sequence instead of simulating");
    de->add_option("--raw", o.raw, "--sequence is a headerless u16 dump: WxH[:bits][:le|be][:skip=BYTES]");
    de->add_option("--out", o.out, "output directory when --sequence is given");
    de->add_option("--bits", o.bits, "tbd_ir with --sequence: the sensor's significant bits (as pft run --bits)")->check(CLI::Range(8, 16));
    filter_opts(de);
    set_metric_opts(de);
    de->add_option("--backgrounds", o.backgrounds, "tbd_ir: folder of background images (replaces the scenario's background.folder)");
    common(de);

    CLI::App *mg = app.add_subcommand("merge", "combine the partial summaries of pft eval --shard K/N into the summary one eval gives");
    mg->add_option("partials", partials, "partial_K_of_N.json files, every shard once")->required()->check(CLI::ExistingFile);
    mg->add_option("--out", o.out, "output directory (summary.json and the kind's plots)")->required();
    common(mg);

    CLI::App *st = app.add_subcommand("selftest", "self-checks of the modules' formulas (e.g. the PCRLB table)");
    st->add_option("--kind", kind_filter, "only this kind");
    common(st);

    CLI::App *pl = app.add_subcommand("plot", "merge eval summaries into one figure (e.g. RMSE vs SNR, paper Fig. 5)");
    pl->add_option("summaries", po.files, "summary.json files")->required()->check(CLI::ExistingFile);
    pl->add_option("--out", po.out, "PNG file");
    pl->add_option("--x", po.x, "JSON pointer of the x value");
    pl->add_option("--y", po.y, "JSON pointer of the y value (an array: one curve per summary, x = frame)");
    pl->add_option("--group", po.group, "JSON pointer of the series label");
    pl->add_option("--floor", po.floor, "JSON pointer of a floor curve ('' for none)");
    pl->add_option("--err", po.err, "JSON pointer of each point's error bar half-width (e.g. a standard error)");
    pl->add_option("--title", po.title);
    pl->add_option("--ymax", po.ymax, "upper y limit");
    pl->add_option("--xlabel", po.xlabel);
    pl->add_option("--ylabel", po.ylabel);

    CLI::App *tr = app.add_subcommand("track", "pftrack TSA-AK (or ncv/ts) on a video or image folder from a box or polygon");
    TrackOptions &t = o.track;
    tr->add_option("--sequence", o.sequence, "video file, image folder, or an opencv-doc name (vtest.avi, Megamind.avi)")
        ->required();
    tr->add_option("--box", t.box, "initial box x,y,w,h (pixels; the box's corners are the polygon, so the target's "
                                   "pixels are x .. x+w-1, y .. y+h-1)");
    tr->add_option("--polygon", t.polygon, "initial polygon x1,y1;x2,y2;...");
    tr->add_option("--init", t.init, "file with {\"box\": [x,y,w,h]} or {\"polygon\": [[x,y],...]} (JSON)");
    tr->add_option("--out", o.out, "output directory (default pft_track_out)");
    tr->add_option("--scenario", o.scenario_path, "take the tracker parameters from this tsa scenario's \"tracker\" object");
    tr->add_option("--motion", t.motion, "tsa (default), ncv or ts (overrides the scenario)")
        ->check(CLI::IsMember({"tsa", "ncv", "ts"}));
    tr->add_option("--particles", o.particles, "normal particles (default 100; overrides the scenario)")
        ->check(CLI::Range(1u, 65535u));
    tr->add_option("--compare", t.compare, "more trackers on the same frames, drawn in one overlay (comma "
                                           "separated: tsa, ts, ncv, ncv200, tsa_paper, kcf, csrt, mosse, mil); "
                                           "tracks_<name>.csv each")
        ->delimiter(',');
    tr->add_option("--set", t.set, "tracker parameter name=value (repeatable; any field of pft_tsa_config_t, e.g. "
                                   "lik_lambda=0, loss_search=false; see docs/host_tools.md)");
    tr->add_option("--frames", o.frames, "stop after this many frames (default: all)")->check(CLI::Range(0u, 10000000u));
    tr->add_option("--max-target", t.max_target, "largest target side in px (default: 2x the initial box, <= 255)")
        ->check(CLI::Range(0, 255));
    tr->add_flag("--video", t.video, "write overlay.avi (MJPEG)");
    tr->add_flag("--no-video", o.no_video, "no overlay.avi (the default; kept for older command lines)");
    tr->add_option("--snapshots", t.snapshots, "overlay snapshots evenly spaced over the run (default 0)")
        ->check(CLI::Range(0, 100));
    tr->add_option("--snapshot-at", t.snapshot_at, "overlay snapshots of these frames (1-based, comma separated)")
        ->delimiter(',');
    tr->add_option("--snapshot-format", t.snapshot_format, "png (default) or jpg (quality 85)")
        ->check(CLI::IsMember({"png", "jpg"}));
    tr->add_option("--snapshot-scale", t.snapshot_scale, "scale of the snapshots (default 1)")->check(CLI::Range(0.05, 4.0));
    tr->add_flag("-q,--quiet", o.quiet, "print less");

    // --version alone: answered before the parser insists on a subcommand
    if (argc == 2 && std::string(argv[1]) == "--version") {
        const std::string git = git_describe();
        std::printf("pft %s (git %s)\n", tool_version(), git.empty() ? "unknown" : git.c_str());
        return 0;
    }
    // an unknown subcommand is named as such (CLI11 would only say that one is required)
    if (argc >= 2 && argv[1][0] != '-') {
        bool known = false;
        std::string names;
        for (const CLI::App *sc : app.get_subcommands([](const CLI::App *) { return true; })) {
            known = known || sc->get_name() == argv[1];
            names += (names.empty() ? "" : ", ") + sc->get_name();
        }
        if (!known) {
            std::fprintf(stderr, "pft: error: unknown subcommand '%s' (one of: %s)\n", argv[1], names.c_str());
            return 2;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success &e) {  // --help
        return app.exit(e);
    } catch (const CLI::ParseError &e) {
        // every usage error: one line naming the option, exit 2 (the same as a bad input file)
        std::string msg = e.what();
        if (msg.empty())
            msg = e.get_name();
        std::fprintf(stderr, "pft: error: %s (pft --help, pft SUBCOMMAND --help)\n", msg.c_str());
        return 2;
    }

    try {
        CLI::App *sub = app.get_subcommands().front();
        o.command = sub->get_name();
        if (const CLI::Option *so = sub->get_option_no_throw("--seed"); so && so->count())
            o.seed = seed;
        if (o.command == "plot")
            return cmd_plot(po);
        if (o.command == "track") {
            // the scenario's kind (its "tracker" object gives the parameters), else tsa
            std::string kind = "tsa";
            if (!o.scenario_path.empty()) {
                o.scenario = load_json_file(o.scenario_path);
                kind = Field(o.scenario, o.scenario_path).string("kind");
            }
            return make_handler(kind)->track(o);
        }
        if (o.command == "merge") {
            MergedRuns m = read_partials(partials);
            return make_handler(m.kind)->merge(o, m);
        }
        if (o.command == "selftest") {
            int fails = 0;
            for (const auto &k : registered_kinds())
                if (kind_filter.empty() || kind_filter == k)
                    fails += make_handler(k)->selftest(o) ? 1 : 0;
            return fails ? 1 : 0;
        }
        // demo without --scenario: the default two-target simulation; with --sequence, the
        // sequence's sidecar or the IR pipeline, as pft run (before, a sequence was always given
        // to the tbd kind's two-target settings, a tbd_ir sim directory's sidecar ignored)
        if (o.scenario_path.empty() && o.command == "demo" && o.sequence.empty())
            o.scenario_path = make_handler("tbd")->default_scenario();
        std::string kind;
        if (!o.scenario_path.empty()) {
            o.scenario = load_json_file(o.scenario_path);
            Field root(o.scenario, o.scenario_path);
            kind = root.string("kind");
        } else {
            // run on a pft sim directory: the sidecar carries the scenario and its kind
            std::string side = o.sequence + "/sequence.json";
            std::FILE *fp = o.raw.empty() ? std::fopen(side.c_str(), "r") : nullptr;
            if (fp) {
                std::fclose(fp);
                json sj = load_json_file(side);
                if (!sj.is_object() || !sj.contains("scenario"))
                    throw InputError("--scenario FILE.json is required (" + side + " names no scenario)");
                Field f(sj, side);
                kind = f.at("scenario").string("kind");
            } else {
                // recorded frames without a sidecar: the IR pipeline with its default settings
                o.scenario_path = make_handler("tbd_ir")->default_scenario();
                o.scenario = load_json_file(o.scenario_path);
                kind = "tbd_ir";
                if (!o.quiet)
                    std::fprintf(stderr, "pft: note: no --scenario and no sequence.json sidecar: "
                                 "the IR pipeline (kind tbd_ir) with the settings of %s\n",
                                 o.scenario_path.c_str());
            }
        }
        if (o.bits && kind != "tbd_ir")
            throw InputError("--bits " + std::to_string(o.bits) + ": only kind tbd_ir takes a bit depth (this is kind " +
                             kind + ", which reads its pixel scaling from the sidecar or the frames)");
        auto h = make_handler(kind);
        if (o.command == "sim")
            return h->sim(o);
        if (o.command == "run")
            return h->run(o);
        if (o.command == "eval")
            return h->eval(o);
        if (o.command == "bench")
            return h->bench(o);
        if (o.command == "demo")
            return h->demo(o);
        throw InputError("unknown command " + o.command);
    } catch (const InputError &e) {
        std::fprintf(stderr, "pft: error: %s\n", e.what());
        return 2;
    } catch (const cv::Exception &e) {
        std::fprintf(stderr, "pft: OpenCV error: %s\n", e.what());
        return 3;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "pft: error: %s\n", e.what());
        return 3;
    }
}
