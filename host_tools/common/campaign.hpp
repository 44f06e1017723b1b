// The Monte Carlo skeleton shared by every kind's `pft eval`: which runs this process computes
// (a whole campaign or one shard of it), the run loop over worker threads with the progress bar,
// the summary header every summary.json starts with, null-for-undefined numbers, and the
// partial summaries that `pft eval --shard K/N` writes and `pft merge` combines.
//
// A kind's eval is:   Campaign c = make_campaign(runs, base, o.shard);
//                     run_campaign(c, threads, progress, "eval", [&](i, seed) { rec[i - c.first] = ...; });
//                     c.partial() ? write_partial(...) : <summarise rec> + finish
// and its merge:      MergedRuns m = read_partials(files); <records from m.runs> -> the same
//                     summarise + finish. The summary is computed from the same per-run records
//                     in the same order either way, so the measures are bit-identical.
#pragma once
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "registry.hpp"

namespace pft::host {

/** Run i (0-based) of a campaign uses seed base_seed + i. Shard K of N (1-based) computes the
 *  runs [floor((K-1) R / N), floor(K R / N)). */
struct Campaign {
    unsigned runs = 0;        ///< runs of the whole campaign
    uint64_t base_seed = 0;
    unsigned shard = 1, shards = 1;
    std::size_t first = 0, end = 0;  ///< the runs of this process
    bool partial() const { return shards > 1; }
    std::size_t count() const { return end - first; }
    uint64_t seed(std::size_t run) const { return base_seed + run; }
};

/** shard_spec: "" (the whole campaign) or "K/N" with 1 <= K <= N <= runs (InputError else). */
Campaign make_campaign(unsigned runs, uint64_t base_seed, const std::string &shard_spec);

struct CampaignTiming {
    double wall_s = 0;  ///< elapsed
    double cpu_s = 0;   ///< sum of the runs' own elapsed times (about CPU time)
};

/** job(run, seed) for every run of the campaign on `threads` workers (0: hardware), with the
 *  progress bar when `progress`. The job stores its result at index run - c.first; results are
 *  in run order whatever the thread timing. Exceptions of a job are rethrown. */
CampaignTiming run_campaign(const Campaign &c, unsigned threads, bool progress, const std::string &label,
                            const std::function<void(std::size_t run, uint64_t seed)> &job);

/** What a kind tells the header about itself. */
struct SummaryHead {
    std::string kind, scenario, scenario_file, description, tag;
    nlohmann::json scenario_json;  ///< as read; the hash is taken from its compact dump
};

/** The header of every eval summary: tool, tool_version, git_describe (null when unknown),
 *  kind, scenario, scenario_file, scenario_hash, description, tag, numeric, runs, base_seed,
 *  seeds, threads, command_line, timing {wall_s, cpu_s, run_s_mean}. */
nlohmann::json summary_header(const Options &o, const Campaign &c, const SummaryHead &h, unsigned threads,
                              const CampaignTiming &t);

/** "fnv1a64:<16 hex digits>" of the compact JSON dump (keys sorted): the same for the same
 *  scenario whatever its whitespace or key order. */
std::string scenario_hash(const nlohmann::json &scenario);
/** The project version of this build and `git describe --always --dirty` of its source tree
 *  ("" when it was not built from a git checkout). */
const char *tool_version();
const char *git_describe();

/** A number, or JSON null when it is not finite (a measure that does not exist). */
inline nlohmann::json num_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
/** The inverse: null (or a missing value) -> NaN. */
inline double null_to_nan(const nlohmann::json &j)
{
    return j.is_number() ? j.get<double>() : std::nan("");
}
/** A vector of doubles with NaN as null, and back. */
nlohmann::json nums_or_null(const std::vector<double> &v);
std::vector<double> nulls_to_nan(const nlohmann::json &a);

/** The options that decide an eval's numbers, stored in partial summaries so that `pft merge`
 *  rebuilds the same evaluation: scenario (path and content), runs, base seed, filter, preset,
 *  particles, single, tag, gospa_c, gospa_p. */
nlohmann::json eval_options_json(const Options &o, const Campaign &c);
Options eval_options_from_json(const nlohmann::json &j);

/** Writes OUT/partial_K_of_N.json: `head` (a summary_header plus the kind's fixed settings),
 *  the eval options, the shard block and one record per run (in run order). */
std::string write_partial(const std::string &out_dir, const nlohmann::json &head, const Options &o,
                          const Campaign &c, const nlohmann::json &run_records);

/** Partial summaries read back and checked: one kind, one campaign, identical settings, every
 *  shard 1..N exactly once. */
struct MergedRuns {
    std::string kind;
    Options options;                   ///< rebuilt eval options (scenario, runs, ...)
    Campaign campaign;                 ///< the whole campaign
    nlohmann::json runs;               ///< every run's record, in run order
    CampaignTiming timing;             ///< sums over the shards
    unsigned threads = 0;              ///< the largest of the shards'
    nlohmann::json shards;             ///< per shard: shard, command_line, threads, timing

    /** The shards' eval options with this merge's output directory, quiet flag and command
     *  line (what a kind's merge loads its scenario with and writes its summary under). */
    Options eval_options(const Options &merge) const
    {
        Options e = options;
        e.out = merge.out;
        e.quiet = merge.quiet;
        e.argv = merge.argv;
        return e;
    }
};
MergedRuns read_partials(const std::vector<std::string> &files);

/** Adds the merge provenance (shards) to a summary made from merged runs. */
void add_merge_fields(nlohmann::json &summary, const MergedRuns &m);

}  // namespace pft::host
