// The per-kind handler registry. A scenario file's top-level "kind" selects the module that
// implements `sim`, `run`, `eval`, `merge`, `bench`, `demo`, `track` and `selftest` for it ("tbd",
// "pf_bearings", "pf_tbd", "tsa", "pte"). A module registers itself with PFT_REGISTER_KIND in
// one of its .cpp files, which are compiled directly into the `pft` executable.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pft::host {

/** `pft track` (kind tsa): the initial region and the tracker and output settings that only
 *  that command takes (its sequence, scenario, out, particles, frames and quiet are in Options). */
struct TrackOptions {
    std::string box;                   ///< --box x,y,w,h
    std::string polygon;               ///< --polygon x1,y1;x2,y2;...
    std::string init;                  ///< --init FILE.json ({"box": ...} or {"polygon": ...})
    std::string motion;                ///< --motion tsa|ncv|ts (empty: the scenario's)
    std::vector<std::string> set;      ///< --set name=value (repeatable)
    std::vector<std::string> compare;  ///< --compare a,b,...: more trackers on the same frames
    int max_target = 0;                ///< --max-target (0: from the initial region)
    bool video = false;                ///< --video: write overlay.avi
    int snapshots = 0;                 ///< --snapshots N
    std::vector<int> snapshot_at;      ///< --snapshot-at k,k,...
    std::string snapshot_format = "png";
    double snapshot_scale = 1.0;
};

/** Command-line options shared by all subcommands; a handler ignores what it does not use
 *  and rejects what makes no sense for it (InputError). */
struct Options {
    std::string command;        ///< sim | run | eval | bench | demo | track | selftest
    std::string scenario_path;  ///< --scenario
    nlohmann::json scenario;    ///< parsed scenario (null for selftest)
    std::string out;            ///< --out: output directory
    std::string sequence;       ///< --sequence: input (run, demo)
    std::string truth;          ///< --truth: ground-truth CSV (run)
    std::string raw;            ///< --raw WxH[:bits][:le|be][:skip=BYTES]: --sequence is a u16 dump
    int bits = 0;               ///< --bits (run, demo; kind tbd_ir): the sensor's significant bits (0: the input's)
    std::string backgrounds;    ///< --backgrounds DIR: background images (kind tbd_ir)
    unsigned runs = 0;          ///< --runs (0: scenario or default)
    unsigned threads = 0;       ///< --threads (0: hardware concurrency)
    std::optional<uint64_t> seed;  ///< --seed (sim: the sequence, eval: base seed)
    std::string filter_kind;    ///< --filter rbpf|pf (empty: scenario)
    std::string preset;         ///< --preset (kind-specific parameter preset; empty: scenario)
    uint32_t particles = 0;     ///< --particles (0: scenario)
    uint32_t frames = 0;        ///< --frames (bench: frames per timed run)
    bool single = false;        ///< --single: single-target filter instead of the manager
    bool progress = false;      ///< --progress: draw the bar even when stderr is no terminal
    bool no_video = false;      ///< --no-video (run)
    std::string residual_out;   ///< --residual-out FILE (run, tbd_ir): the residual the TBD manager sees, every frame
    std::string stage_out;      ///< --stage-out FILE (run, tbd_ir): the stage's pft_pre_stats per frame, CSV
    std::string trace;          ///< --trace DIR (eval, tbd_ir): per-run diagnostic trace of the TBD manager (ir_trace.hpp)
    std::string probe_out;      ///< --probe-out DIR (bench, tbd_ir): frames, configurations and expected outputs for tests/tools/ir_probe (ir_probe_out.hpp)
    bool quiet = false;         ///< --quiet
    std::string format;         ///< --format pgm|raw (sim)
    int scale = 0;              ///< --scale: overlay upscale factor (run)
    std::string tag;            ///< --tag: label stored in eval summaries (plots group by it)
    std::string shard;          ///< --shard K/N (eval): compute shard K of N, write a partial summary
    std::optional<double> gospa_c;  ///< --gospa-c: GOSPA/OSPA cut-off (unset: the kind's default)
    std::optional<double> gospa_p;  ///< --gospa-p: GOSPA/OSPA order (unset: 2)
    TrackOptions track;         ///< `pft track` only
    std::vector<std::string> argv;  ///< the command line (recorded in summaries)
};

struct MergedRuns;  // common/campaign.hpp

class KindHandler {
public:
    virtual ~KindHandler() = default;
    virtual int sim(const Options &o);
    virtual int run(const Options &o);
    virtual int eval(const Options &o);
    virtual int bench(const Options &o);
    virtual int demo(const Options &o);
    /** `pft track`: a tracker over a recorded video or image folder from an initial region
     *  (kind tsa; the kind is the --scenario's, else tsa). */
    virtual int track(const Options &o);
    /** `pft merge`: the summary of the whole campaign from its partial summaries (the kind's
     *  records of every run, read back in run order), written as `eval` writes it. */
    virtual int merge(const Options &o, const MergedRuns &m);
    /** Self-checks of the module's formulas; returns 0 when they all hold. */
    virtual int selftest(const Options &o);
    /** Scenario file used by `pft demo` when none is given (absolute path or empty). */
    virtual std::string default_scenario() const { return {}; }

protected:
    [[noreturn]] void unsupported(const Options &o) const;
    std::string kind_;
    friend std::unique_ptr<KindHandler> make_handler(const std::string &kind);
};

using KindFactory = std::function<std::unique_ptr<KindHandler>()>;

void register_kind(const std::string &kind, KindFactory factory);
/** A scenario written with an earlier kind name (e.g. "vis") selects `kind` (e.g. "tsa"), with
 *  a note on stderr. */
void register_kind_alias(const std::string &old_name, const std::string &kind);
/** InputError naming the known kinds when `kind` is not registered. */
std::unique_ptr<KindHandler> make_handler(const std::string &kind);
std::vector<std::string> registered_kinds();

struct KindRegistrar {
    KindRegistrar(const char *kind, KindFactory f) { register_kind(kind, std::move(f)); }
};

struct KindAliasRegistrar {
    KindAliasRegistrar(const char *old_name, const char *kind) { register_kind_alias(old_name, kind); }
};

/** PFT_REGISTER_KIND_ALIAS("vis", "tsa", tsa_vis): the old name "vis" selects kind "tsa". */
#define PFT_REGISTER_KIND_ALIAS(old_name, kind, tag)                                        \
    static const ::pft::host::KindAliasRegistrar pft_kind_alias_##tag(old_name, kind)

#define PFT_REGISTER_KIND(name, type)                                                       \
    static const ::pft::host::KindRegistrar pft_kind_registrar_##type(                      \
        name, [] { return std::unique_ptr<::pft::host::KindHandler>(new type()); })

}  // namespace pft::host
