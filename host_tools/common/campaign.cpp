#include "campaign.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>

#include "errors.hpp"
#include "json_field.hpp"
#include "output.hpp"
#include "parallel.hpp"
#include "progress.hpp"
#include "real.hpp"

extern const char *const pft_host_git_describe_str;  // generated at build time (git_describe.cmake)

namespace pft::host {

using nlohmann::json;

namespace {
const char *const kPartialFormat = "pft_partial_summary";
/** Fields of a partial that differ between the shards of one campaign. */
const char *const kShardFields[] = {"command_line", "timing", "threads", "shard", "run_records"};
}  // namespace

const char *tool_version() { return PFT_HOST_VERSION; }
const char *git_describe() { return pft_host_git_describe_str; }

Campaign make_campaign(unsigned runs, uint64_t base_seed, const std::string &shard_spec)
{
    Campaign c;
    c.runs = runs;
    c.base_seed = base_seed;
    if (!shard_spec.empty()) {
        unsigned k = 0, n = 0;
        char tail = 0;
        if (std::sscanf(shard_spec.c_str(), "%u/%u%c", &k, &n, &tail) != 2 || k < 1 || n < 1 || k > n)
            throw InputError("--shard " + shard_spec + ": expected K/N with 1 <= K <= N (e.g. 3/8)");
        if (n > runs)
            throw InputError("--shard " + shard_spec + ": more shards than runs (" + std::to_string(runs) + ")");
        c.shard = k;
        c.shards = n;
    }
    c.first = static_cast<std::size_t>(static_cast<unsigned long long>(c.shard - 1) * runs / c.shards);
    c.end = static_cast<std::size_t>(static_cast<unsigned long long>(c.shard) * runs / c.shards);
    return c;
}

CampaignTiming run_campaign(const Campaign &c, unsigned threads, bool progress, const std::string &label,
                            const std::function<void(std::size_t, uint64_t)> &job)
{
    Progress bar(c.count(), label, progress);
    auto t0 = std::chrono::steady_clock::now();
    std::atomic<double> cpu{0.0};
    parallel_for(c.count(), threads, [&](std::size_t i) {
        auto c0 = std::chrono::steady_clock::now();
        std::size_t run = c.first + i;
        job(run, c.seed(run));
        double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
        double cur = cpu.load();
        while (!cpu.compare_exchange_weak(cur, cur + dt)) {
        }
        bar.tick();
    });
    bar.finish();
    CampaignTiming t;
    t.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t.cpu_s = cpu.load();
    return t;
}

std::string scenario_hash(const json &scenario)
{
    uint64_t h = 14695981039346656037ull;
    for (unsigned char ch : scenario.dump()) {
        h ^= ch;
        h *= 1099511628211ull;
    }
    char b[40];
    std::snprintf(b, sizeof b, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
    return b;
}

json summary_header(const Options &o, const Campaign &c, const SummaryHead &h, unsigned threads,
                    const CampaignTiming &t)
{
    json seeds = json::array();
    for (unsigned i = 0; i < c.runs; ++i)
        seeds.push_back(c.seed(i));
    json cmd = json::array();
    for (const auto &a : o.argv)
        cmd.push_back(a);
    const std::string git = git_describe();
    return {
        {"tool", "pft eval"},
        {"tool_version", tool_version()},
        {"git_describe", git.empty() ? json(nullptr) : json(git)},
        {"kind", h.kind},
        {"scenario", h.scenario},
        {"scenario_file", h.scenario_file},
        {"scenario_hash", scenario_hash(h.scenario_json)},
        {"description", h.description},
        {"tag", h.tag},
        {"numeric", numeric_name()},
        {"runs", c.runs},
        {"base_seed", c.base_seed},
        {"seeds", seeds},
        {"threads", threads},
        {"command_line", cmd},
        {"timing", {{"wall_s", t.wall_s}, {"cpu_s", t.cpu_s},
                    {"run_s_mean", c.count() ? t.cpu_s / static_cast<double>(c.count()) : 0.0}}},
    };
}

json nums_or_null(const std::vector<double> &v)
{
    json a = json::array();
    for (double x : v)
        a.push_back(num_or_null(x));
    return a;
}

std::vector<double> nulls_to_nan(const json &a)
{
    std::vector<double> v;
    for (const json &x : a)
        v.push_back(null_to_nan(x));
    return v;
}

json eval_options_json(const Options &o, const Campaign &c)
{
    return {{"scenario_file", o.scenario_path},
            {"scenario", o.scenario},
            {"runs", c.runs},
            {"base_seed", c.base_seed},
            {"filter", o.filter_kind},
            {"preset", o.preset},
            {"particles", o.particles},
            {"single", o.single},
            {"tag", o.tag},
            {"gospa_c", o.gospa_c ? json(*o.gospa_c) : json(nullptr)},
            {"gospa_p", o.gospa_p ? json(*o.gospa_p) : json(nullptr)}};
}

Options eval_options_from_json(const json &j)
{
    Options o;
    o.command = "eval";
    o.scenario_path = j.at("scenario_file").get<std::string>();
    o.scenario = j.at("scenario");
    o.runs = j.at("runs").get<unsigned>();
    o.seed = j.at("base_seed").get<uint64_t>();
    o.filter_kind = j.at("filter").get<std::string>();
    o.preset = j.at("preset").get<std::string>();
    o.particles = j.at("particles").get<uint32_t>();
    o.single = j.at("single").get<bool>();
    o.tag = j.at("tag").get<std::string>();
    if (j.at("gospa_c").is_number())
        o.gospa_c = j["gospa_c"].get<double>();
    if (j.at("gospa_p").is_number())
        o.gospa_p = j["gospa_p"].get<double>();
    return o;
}

std::string write_partial(const std::string &out_dir, const json &head, const Options &o, const Campaign &c,
                          const json &run_records)
{
    json j = head;
    j[kPartialFormat] = 1;
    j["eval_options"] = eval_options_json(o, c);
    j["shard"] = {{"shard", c.shard}, {"shards", c.shards}, {"first_run", c.first}, {"end_run", c.end}};
    j["run_records"] = run_records;
    std::string path = join_path(out_dir, "partial_" + std::to_string(c.shard) + "_of_" +
                                              std::to_string(c.shards) + ".json");
    write_json_atomic(path, j);
    return path;
}

namespace {

/** The first key at which two JSON values differ ("" when equal). */
std::string first_difference(const json &a, const json &b, const std::string &path)
{
    if (a == b)
        return "";
    if (a.is_object() && b.is_object()) {
        for (auto it = a.begin(); it != a.end(); ++it) {
            if (!b.contains(it.key()))
                return path + "/" + it.key();
            std::string d = first_difference(it.value(), b[it.key()], path + "/" + it.key());
            if (!d.empty())
                return d;
        }
        for (auto it = b.begin(); it != b.end(); ++it)
            if (!a.contains(it.key()))
                return path + "/" + it.key();
    }
    return path.empty() ? "/" : path;
}

json without_shard_fields(json j)
{
    for (const char *k : kShardFields)
        j.erase(k);
    return j;
}

}  // namespace

MergedRuns read_partials(const std::vector<std::string> &files)
{
    if (files.empty())
        throw InputError("merge: no partial summaries given");
    std::map<unsigned, std::pair<std::string, json>> by_shard;
    json ref;
    std::string ref_file;
    unsigned shards = 0;
    for (const auto &f : files) {
        json j = load_json_file(f);
        if (!j.is_object() || !j.contains(kPartialFormat))
            throw InputError(f + ": not a partial summary (write one with pft eval --shard K/N)");
        if (j[kPartialFormat] != 1)
            throw InputError(f + ": partial summary format " + j[kPartialFormat].dump() + " (this pft reads 1)");
        unsigned k = j.at("shard").at("shard").get<unsigned>(), n = j.at("shard").at("shards").get<unsigned>();
        json fixed = without_shard_fields(j);
        if (ref_file.empty()) {
            ref = fixed;
            ref_file = f;
            shards = n;
        } else {
            std::string d = first_difference(ref, fixed, "");
            if (!d.empty())
                throw InputError(f + ": not from the same campaign as " + ref_file + " (they differ at " + d + ")");
            if (n != shards)
                throw InputError(f + ": shard of " + std::to_string(n) + ", " + ref_file + " of " +
                                 std::to_string(shards));
        }
        if (by_shard.count(k))
            throw InputError(f + ": shard " + std::to_string(k) + "/" + std::to_string(n) + " given twice (also " +
                             by_shard[k].first + ")");
        by_shard[k] = {f, std::move(j)};
    }
    for (unsigned k = 1; k <= shards; ++k)
        if (!by_shard.count(k))
            throw InputError("merge: shard " + std::to_string(k) + "/" + std::to_string(shards) + " is missing");
    MergedRuns m;
    m.kind = ref.at("kind").get<std::string>();
    m.options = eval_options_from_json(ref.at("eval_options"));
    m.campaign = make_campaign(m.options.runs, *m.options.seed, "");
    m.runs = json::array();
    m.shards = json::array();
    for (auto &[k, fj] : by_shard) {
        const json &j = fj.second;
        const json &sh = j.at("shard");
        Campaign expect = make_campaign(m.options.runs, *m.options.seed,
                                        std::to_string(k) + "/" + std::to_string(shards));
        const json &recs = j.at("run_records");
        if (sh.at("first_run").get<std::size_t>() != expect.first || sh.at("end_run").get<std::size_t>() != expect.end ||
            recs.size() != expect.count())
            throw InputError(fj.first + ": shard " + std::to_string(k) + " should hold runs " +
                             std::to_string(expect.first) + ".." + std::to_string(expect.end) + " (" +
                             std::to_string(recs.size()) + " records)");
        for (const json &r : recs)
            m.runs.push_back(r);
        const json &t = j.at("timing");
        m.timing.wall_s += t.value("wall_s", 0.0);
        m.timing.cpu_s += t.value("cpu_s", 0.0);
        m.threads = std::max(m.threads, j.value("threads", 0u));
        m.shards.push_back({{"file", fj.first}, {"shard", k}, {"shards", shards}, {"first_run", expect.first},
                            {"end_run", expect.end}, {"command_line", j.value("command_line", json(nullptr))},
                            {"threads", j.value("threads", json(nullptr))}, {"timing", t}});
    }
    return m;
}

void add_merge_fields(json &summary, const MergedRuns &m)
{
    summary["shards"] = m.shards;
    summary["timing"]["note"] = "sums over the shards (pft merge)";
}

}  // namespace pft::host
