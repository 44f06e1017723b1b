#include "metrics.hpp"

#include <algorithm>
#include <cmath>


namespace pft::host::pte {

void Counts::add(const Counts &o)
{
    true_frames += o.true_frames;
    correct += o.correct;
    declared += o.declared;
    false_points += o.false_points;
    rel_num += o.rel_num;
    rel_den += o.rel_den;
    frames += o.frames;
    sq += o.sq;
    time_s += o.time_s;
    if (set.added() == 0) {
        gospa_c = o.gospa_c;
        gospa_p = o.gospa_p;
    }
    set.merge(o.set);
    if (per_frame.frames() == 0)
        per_frame = o.per_frame;
    else
        per_frame.merge(o.per_frame);
}

namespace {
/** Adds one frame's GOSPA / OSPA terms: truth and declared positions in cells (1-D). */
void add_set_metrics(Counts &c, std::size_t k, const std::vector<double> &truth, const std::vector<double> &est)
{
    std::vector<metrics::Point> t, e;
    for (double r : truth)
        t.push_back({r, 0.0});
    for (double r : est)
        e.push_back({r, 0.0});
    const metrics::FrameMetrics f = metrics::frame_metrics(t, e, c.gospa_c, c.gospa_p);
    c.set.add(0, f);
    c.per_frame.add(k, f);
}
}  // namespace

double Counts::detection_prob() const { return true_frames ? double(correct) / true_frames : NAN; }
double Counts::reliable3_prob() const { return rel_den ? double(rel_num) / rel_den : NAN; }
double Counts::false_track_prob() const { return declared ? double(false_points) / declared : 0.0; }
double Counts::rmse() const { return correct ? std::sqrt(sq / correct) : NAN; }
double Counts::us_per_frame() const { return frames ? time_s * 1e6 / frames : NAN; }

nlohmann::json Counts::to_json() const
{
    auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    nlohmann::json j = {{"detection_prob", num(detection_prob())}, {"reliable3_prob", num(reliable3_prob())},
            {"false_track_prob", num(false_track_prob())}, {"rmse_cells", num(rmse())},
            {"us_per_frame", num(us_per_frame())}, {"true_frames", true_frames}, {"correct_points", correct},
            {"declared_points", declared}, {"false_points", false_points}, {"reliable_frames", rel_num},
            {"reliable_den", rel_den}, {"frames", frames}};
    j.update(metrics::set_metric_fields(set));
    if (per_frame.frames()) {
        nlohmann::json g = nlohmann::json::array(), o = nlohmann::json::array();
        for (std::size_t k = 0; k < per_frame.frames(); ++k) {
            g.push_back(num(per_frame.gospa_at(k)));
            o.push_back(num(per_frame.ospa_at(k)));
        }
        j["gospa_per_frame"] = g;
        j["ospa_per_frame"] = o;
    }
    j["gospa_c"] = gospa_c;
    j["gospa_p"] = gospa_p;
    j["gospa_alpha"] = 2;
    return j;
}

nlohmann::json Counts::raw() const
{
    return {{"true_frames", true_frames}, {"correct", correct}, {"declared", declared},
            {"false_points", false_points}, {"rel_num", rel_num}, {"rel_den", rel_den}, {"frames", frames},
            {"sq", sq}, {"time_s", time_s}, {"gospa_c", gospa_c}, {"gospa_p", gospa_p}, {"set", set.raw()},
            {"per_frame", per_frame.raw()}};
}

Counts Counts::from_raw(const nlohmann::json &j)
{
    Counts c;
    c.true_frames = j.at("true_frames").get<long long>();
    c.correct = j.at("correct").get<long long>();
    c.declared = j.at("declared").get<long long>();
    c.false_points = j.at("false_points").get<long long>();
    c.rel_num = j.at("rel_num").get<long long>();
    c.rel_den = j.at("rel_den").get<long long>();
    c.frames = j.at("frames").get<long long>();
    c.sq = j.at("sq").get<double>();
    c.time_s = j.at("time_s").get<double>();
    c.gospa_c = j.at("gospa_c").get<double>();
    c.gospa_p = j.at("gospa_p").get<double>();
    c.set = metrics::SetMetricSums::from_raw(j.at("set"));
    c.per_frame = metrics::SetMetricSums::from_raw(j.at("per_frame"));
    return c;
}

Counts score_run(const std::vector<Truth> &truth, const std::vector<std::vector<Report>> &out,
                 int cells, double d_c, std::vector<char> *correct, bool with_coasting, double gospa_c,
                 double gospa_p)
{
    Counts c;
    c.gospa_c = gospa_c > 0.0 ? gospa_c : d_c;
    c.gospa_p = gospa_p;
    c.set = metrics::SetMetricSums(1, c.gospa_c, c.gospa_p);
    std::size_t n = std::min(truth.size(), out.size());
    c.per_frame = metrics::SetMetricSums(n, c.gospa_c, c.gospa_p);
    std::vector<char> ok(n, 0), present(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
        present[k] = truth[k].r >= 0.0 && truth[k].r <= cells - 1.0;
        long long nd = 0;
        double best = INFINITY;
        std::vector<double> est;
        for (const Report &r : out[k])
            if (r.detected || with_coasting) {
                ++nd;
                best = std::min(best, std::fabs(r.pos - truth[k].r));
                est.push_back(r.pos);
            }
        c.declared += nd;
        add_set_metrics(c, k, present[k] ? std::vector<double>{truth[k].r} : std::vector<double>{}, est);
        if (!present[k]) {
            c.false_points += nd;
            continue;
        }
        c.true_frames++;
        if (best <= d_c) {
            ok[k] = 1;
            c.correct++;
            c.sq += best * best;
            c.false_points += nd - 1;
        } else {
            c.false_points += nd;
        }
    }
    for (std::size_t k = 2; k < n; ++k)
        if (present[k] && present[k - 1] && present[k - 2]) {
            c.rel_den++;
            c.rel_num += ok[k] && ok[k - 1] && ok[k - 2];
        }
    if (correct)
        *correct = ok;
    return c;
}

Counts score_runs(const std::vector<std::vector<Truth>> &truths, const std::vector<std::vector<Report>> &out,
                  int cells, double d_c, bool with_coasting, double gospa_c, double gospa_p)
{
    if (truths.size() == 1)
        return score_run(truths[0], out, cells, d_c, nullptr, with_coasting, gospa_c, gospa_p);
    Counts c;
    c.gospa_c = gospa_c > 0.0 ? gospa_c : d_c;
    c.gospa_p = gospa_p;
    c.set = metrics::SetMetricSums(1, c.gospa_c, c.gospa_p);
    const std::size_t nt = truths.size();
    std::size_t n = out.size();
    for (const auto &tr : truths)
        n = std::min(n, tr.size());
    c.per_frame = metrics::SetMetricSums(n, c.gospa_c, c.gospa_p);
    std::vector<std::vector<char>> ok(nt, std::vector<char>(n, 0)), present(nt, std::vector<char>(n, 0));
    for (std::size_t k = 0; k < n; ++k) {
        std::vector<double> pos;
        for (const Report &r : out[k])
            if (r.detected || with_coasting)
                pos.push_back(r.pos);
        c.declared += static_cast<long long>(pos.size());
        struct Pair { double d; std::size_t t, r; };
        std::vector<Pair> pairs;
        for (std::size_t t = 0; t < nt; ++t) {
            const Truth &tr = truths[t][k];
            present[t][k] = tr.active && tr.r >= 0.0 && tr.r <= cells - 1.0;
            if (!present[t][k])
                continue;
            c.true_frames++;
            for (std::size_t r = 0; r < pos.size(); ++r) {
                double d = std::fabs(pos[r] - tr.r);
                if (d <= d_c)
                    pairs.push_back({d, t, r});
            }
        }
        std::vector<double> present_r;
        for (std::size_t t = 0; t < nt; ++t)
            if (present[t][k])
                present_r.push_back(truths[t][k].r);
        add_set_metrics(c, k, present_r, pos);
        std::sort(pairs.begin(), pairs.end(), [](const Pair &a, const Pair &b) {
            return a.d < b.d || (a.d == b.d && (a.t < b.t || (a.t == b.t && a.r < b.r)));
        });
        std::vector<char> used(pos.size(), 0);
        long long matched = 0;
        for (const Pair &p : pairs) {
            if (ok[p.t][k] || used[p.r])
                continue;
            ok[p.t][k] = 1;
            used[p.r] = 1;
            ++matched;
            c.correct++;
            c.sq += p.d * p.d;
        }
        c.false_points += static_cast<long long>(pos.size()) - matched;
    }
    for (std::size_t t = 0; t < nt; ++t)
        for (std::size_t k = 2; k < n; ++k)
            if (present[t][k] && present[t][k - 1] && present[t][k - 2]) {
                c.rel_den++;
                c.rel_num += ok[t][k] && ok[t][k - 1] && ok[t][k - 2];
            }
    return c;
}

}  // namespace pft::host::pte
