#include "ir_eval.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "../common/errors.hpp"
#include "../common/output.hpp"

namespace pft::host::tbd_ir {

std::vector<TruthRow> read_ir_truth(const std::string &path)
{
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open truth file");
    std::vector<TruthRow> rows;
    std::string line;
    int ln = 0;
    while (std::getline(in, line)) {
        ++ln;
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        if (line.empty())
            continue;
        if (ln == 1) {
            if (line.rfind("frame,id,x,y", 0) != 0)
                throw InputError(path + ":1: expected the header frame,id,x,y,snr_db,kind (a tbd_ir "
                                        "truth file)");
            continue;
        }
        std::vector<std::string> f;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ','))
            f.push_back(cell);
        try {
            if (f.size() < 4)
                throw std::invalid_argument("columns");
            TruthRow r;
            r.frame = std::stoi(f[0]);
            r.id = std::stoi(f[1]);
            r.x = std::stod(f[2]);
            r.y = std::stod(f[3]);
            r.snr_db = f.size() > 4 && !f[4].empty() ? std::stod(f[4]) : NAN;
            r.labelled = f.size() > 5 && f[5] == "labelled";
            if (r.frame < 1)
                throw std::out_of_range("frame");
            rows.push_back(r);
        } catch (const std::exception &) {
            throw InputError(path + ":" + std::to_string(ln) + ": expected frame,id,x,y,snr_db,kind");
        }
    }
    return rows;
}

void write_ir_truth(const std::string &path, const std::vector<TruthRow> &rows)
{
    write_text_atomic(path, [&](std::ostream &os) {
        CsvWriter w(os);
        w.field("frame").field("id").field("x").field("y").field("snr_db").field("kind");
        w.end_row();
        for (const TruthRow &r : rows) {
            w.field(r.frame).field(r.id).field(r.x).field(r.y);
            if (std::isfinite(r.snr_db))
                w.field(r.snr_db);
            else
                w.field("");
            w.field(r.labelled ? "labelled" : "injected");
            w.end_row();
        }
    });
}

IrRunEval evaluate_ir(const std::vector<TruthRow> &truth, const std::vector<tbd::FrameOut> &out,
                      double d_c, double d_assoc)
{
    IrRunEval ev;
    ev.frames = static_cast<int>(out.size());
    std::map<int, std::vector<const TruthRow *>> by_frame;
    std::map<int, std::size_t> index;  // target id -> ev.targets
    int last_frame = 0;
    for (const tbd::FrameOut &f : out)
        last_frame = std::max(last_frame, static_cast<int>(f.frame));
    for (const TruthRow &r : truth) {
        if (r.frame > last_frame)
            continue;
        by_frame[r.frame].push_back(&r);
        auto it = index.find(r.id);
        if (it == index.end()) {
            it = index.emplace(r.id, ev.targets.size()).first;
            TargetResult t;
            t.id = r.id;
            t.labelled = r.labelled;
            t.snr_db = r.snr_db;
            t.first = r.frame;
            ev.targets.push_back(t);
        }
        TargetResult &t = ev.targets[it->second];
        if (r.frame <= t.first || !std::isfinite(t.first_x)) {
            t.first_x = r.x;
            t.first_y = r.y;
        }
        t.first = std::min(t.first, r.frame);
        t.last = std::max(t.last, r.frame);
        ++t.present;
    }
    // the border each target entered by (its first truth point within 2 px of it), in the
    // frame's coordinates: the lost side of the scene's drift is where new scene comes in
    int fw = 0, fh = 0;
    for (const tbd::FrameOut &f : out)
        if (f.width > 0 && f.height > 0) {
            fw = f.width;
            fh = f.height;
            break;
        }
    for (TargetResult &t : ev.targets) {
        if (fw <= 0)
            continue;
        t.entry = t.first_x < 2.0        ? "left"
                  : t.first_x > fw - 3.0 ? "right"
                  : t.first_y < 2.0      ? "top"
                  : t.first_y > fh - 3.0 ? "bottom"
                                         : "inside";
    }
    std::map<uint32_t, bool> track_assoc;                 // track id -> ever associated
    std::map<uint32_t, TrackSpan> track_span;            // track id -> first/last report
    std::map<std::size_t, std::set<uint32_t>> tgt_tracks; // target -> tracks
    for (const tbd::FrameOut &f : out) {
        for (const tbd::TrackOut &tr : f.tracks) {
            track_assoc.emplace(tr.id, false);
            auto sp = track_span.find(tr.id);
            if (sp == track_span.end()) {
                TrackSpan ft;
                ft.id = tr.id;
                ft.first = static_cast<int>(f.frame);
                ft.x = tr.x;
                ft.y = tr.y;
                sp = track_span.emplace(tr.id, ft).first;
            }
            sp->second.last = static_cast<int>(f.frame);
            ++sp->second.frames;
        }
        auto bf = by_frame.find(static_cast<int>(f.frame));
        if (bf == by_frame.end())
            continue;
        for (const TruthRow *r : bf->second) {
            if (r->labelled || f.frame <= 1 || f.width <= 0)
                continue;
            const long xi = std::lround(r->x), yi = std::lround(r->y);
            if (xi < 0 || yi < 0 || xi >= f.width || yi >= f.height)
                continue;
            ++ev.birth_frames;
            for (uint32_t k : f.births) {
                const long c = static_cast<long>(k % static_cast<uint32_t>(f.width));
                const long rr = static_cast<long>(k / static_cast<uint32_t>(f.width));
                if (std::labs(c - xi) <= 1 && std::labs(rr - yi) <= 1) {
                    ++ev.birth_hits;
                    break;
                }
            }
        }
        struct Cand { double d; std::size_t tr, tg; };
        std::vector<Cand> c;
        for (std::size_t i = 0; i < f.tracks.size(); ++i)
            for (std::size_t j = 0; j < bf->second.size(); ++j) {
                double d = std::hypot(f.tracks[i].x - bf->second[j]->x, f.tracks[i].y - bf->second[j]->y);
                if (d <= d_assoc)
                    c.push_back({d, i, j});
            }
        std::sort(c.begin(), c.end(), [](const Cand &a, const Cand &b) { return a.d < b.d; });
        std::vector<bool> tr_used(f.tracks.size()), tg_used(bf->second.size());
        for (const Cand &k : c) {
            if (tr_used[k.tr] || tg_used[k.tg])
                continue;
            tr_used[k.tr] = tg_used[k.tg] = true;
            std::size_t ti = index[bf->second[k.tg]->id];
            TargetResult &t = ev.targets[ti];
            if (!t.detected) {
                t.detected = true;
                t.appear_delay = static_cast<int>(f.frame) - t.first;
            }
            if (k.d <= d_c) {
                ++t.correct;
                t.sq_correct += k.d * k.d;
            }
            track_assoc[f.tracks[k.tr].id] = true;
            tgt_tracks[ti].insert(f.tracks[k.tr].id);
        }
    }
    for (auto &kv : tgt_tracks)
        ev.targets[kv.first].tracks = static_cast<int>(kv.second.size());
    ev.tracks = static_cast<int>(track_assoc.size());
    for (auto &kv : track_assoc)
        if (!kv.second) {
            ++ev.false_tracks;
            ev.false_ids.push_back(kv.first);
            ev.false_list.push_back(track_span[kv.first]);
        } else {
            ev.target_list.push_back(track_span[kv.first]);
        }
    return ev;
}

namespace {

nlohmann::json group_summary(const std::vector<IrRunEval> &runs, int kind /* -1 all, 0 injected, 1 labelled */)
{
    long n = 0, det = 0, correct = 0, present = 0;
    double delay = 0, sq = 0;
    for (const IrRunEval &r : runs)
        for (const TargetResult &t : r.targets) {
            if (kind >= 0 && t.labelled != (kind == 1))
                continue;
            ++n;
            present += t.present;
            correct += t.correct;
            sq += t.sq_correct;
            if (t.detected) {
                ++det;
                delay += t.appear_delay;
            }
        }
    auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    return {{"targets", n},
            {"detected", det},
            {"detection_probability", num(n ? static_cast<double>(det) / n : NAN)},
            {"appearance_delay", num(det ? delay / det : NAN)},
            {"correct_fraction", num(present ? static_cast<double>(correct) / present : NAN)},
            {"rmse", num(correct ? std::sqrt(sq / correct) : NAN)}};
}

// the injected targets by the border they entered by (TargetResult::entry)
nlohmann::json entry_summary(const std::vector<IrRunEval> &runs)
{
    nlohmann::json e = nlohmann::json::object();
    for (const char *k : {"left", "right", "top", "bottom", "inside"}) {
        long n = 0, det = 0;
        for (const IrRunEval &r : runs)
            for (const TargetResult &t : r.targets)
                if (!t.labelled && t.entry == k) {
                    ++n;
                    det += t.detected ? 1 : 0;
                }
        e[k] = {{"targets", n},
                {"detected", det},
                {"detection_probability", n ? nlohmann::json(static_cast<double>(det) / n) : nlohmann::json(nullptr)}};
    }
    return e;
}

std::string f2(const nlohmann::json &v, int prec = 2)
{
    if (!v.is_number())
        return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", prec, v.get<double>());
    return b;
}

}  // namespace

nlohmann::json summarize_ir(const std::vector<IrRunEval> &runs)
{
    long frames = 0, fals = 0, tracks = 0, bfr = 0, bhit = 0;
    for (const IrRunEval &r : runs) {
        bfr += r.birth_frames;
        bhit += r.birth_hits;
        frames += r.frames;
        fals += r.false_tracks;
        tracks += r.tracks;
    }
    nlohmann::json a = group_summary(runs, -1);
    a["tracks_per_run"] = runs.empty() ? 0.0 : static_cast<double>(tracks) / runs.size();
    a["false_tracks_per_run"] = runs.empty() ? 0.0 : static_cast<double>(fals) / runs.size();
    a["false_tracks_per_1000_frames"] = frames ? 1000.0 * fals / frames : 0.0;
    // the search layer's birth candidates near the injected targets (TBD only; 0 for DBT)
    a["birth_hit_share"] = bfr ? static_cast<double>(bhit) / bfr : 0.0;
    a["birth_target_frames"] = bfr;
    nlohmann::json per = nlohmann::json::array();
    for (const IrRunEval &r : runs) {
        nlohmann::json ts = nlohmann::json::array();
        for (const TargetResult &t : r.targets)
            ts.push_back({{"id", t.id}, {"kind", t.labelled ? "labelled" : "injected"},
                          {"snr_db", std::isfinite(t.snr_db) ? nlohmann::json(t.snr_db) : nlohmann::json(nullptr)},
                          {"first_frame", t.first}, {"last_frame", t.last}, {"present_frames", t.present},
                          {"detected", t.detected},
                          {"appearance_delay", t.detected ? nlohmann::json(t.appear_delay) : nlohmann::json(nullptr)},
                          {"correct_frames", t.correct}, {"correct_sq_error_px2", t.sq_correct},
                          {"tracks", t.tracks}, {"entry", t.entry}});
        nlohmann::json fl = nlohmann::json::array();
        auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
        for (const TrackSpan &f : r.false_list)
            fl.push_back({{"id", f.id}, {"first_frame", f.first}, {"last_frame", f.last},
                          {"reported_frames", f.frames}, {"x", f.x}, {"y", f.y},
                          {"scene_x", num(f.scene_x)}, {"scene_y", num(f.scene_y)}});
        nlohmann::json tl = nlohmann::json::array();
        for (const TrackSpan &f : r.target_list)
            tl.push_back({{"id", f.id}, {"first_frame", f.first}, {"last_frame", f.last},
                          {"reported_frames", f.frames}});
        per.push_back({{"seed", r.seed}, {"frames", r.frames}, {"tracks", r.tracks},
                       {"false_tracks", r.false_tracks}, {"targets", ts}, {"false_track_list", fl},
                       {"target_track_list", tl}});
    }
    return {{"runs", runs.size()},
            {"frames_total", frames},
            {"averaged", a},
            {"by_kind", {{"injected", group_summary(runs, 0)}, {"labelled", group_summary(runs, 1)}}},
            {"by_entry", entry_summary(runs)},
            {"per_run", per}};
}

void print_ir_summary(const nlohmann::json &sum)
{
    const bool pair = sum.contains("dbt");
    std::printf("  %s%-9s %8s %9s %9s %9s %8s %9s\n", pair ? "tracker " : "", "targets", "count", "detected",
                "appear", "correct", "RMSE", "false/1k");
    auto block = [&](const char *who, const nlohmann::json &s) {
        const nlohmann::json &a = s["averaged"];
        auto row = [&](const char *name, const nlohmann::json &g, bool with_false) {
            if (g["targets"].get<long>() == 0)
                return;
            std::printf("  %s%-9s %8ld %8s%% %9s %8s%% %8s %9s\n", who, name, g["targets"].get<long>(),
                        f2(g["detection_probability"].is_number()
                               ? nlohmann::json(100.0 * g["detection_probability"].get<double>())
                               : nlohmann::json(nullptr), 1).c_str(),
                        f2(g["appearance_delay"]).c_str(),
                        f2(g["correct_fraction"].is_number()
                               ? nlohmann::json(100.0 * g["correct_fraction"].get<double>())
                               : nlohmann::json(nullptr), 1).c_str(),
                        f2(g["rmse"], 3).c_str(),
                        with_false ? f2(a["false_tracks_per_1000_frames"]).c_str() : "");
        };
        row("injected", s["by_kind"]["injected"], false);
        row("labelled", s["by_kind"]["labelled"], false);
        row("all", a, true);
    };
    block(pair ? "TBD     " : "", sum);
    if (pair)
        block("DBT     ", sum["dbt"]);
    auto line = [](const char *who, const nlohmann::json &a) {
        std::printf("  %stracks per run %.2f, false tracks per run %.2f (%.2f per 1000 frames)\n", who,
                    a["tracks_per_run"].get<double>(), a["false_tracks_per_run"].get<double>(),
                    a["false_tracks_per_1000_frames"].get<double>());
    };
    line(pair ? "TBD: " : "", sum["averaged"]);
    if (pair)
        line("DBT: ", sum["dbt"]["averaged"]);
}

}  // namespace pft::host::tbd_ir
