#include "metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "../common/campaign.hpp"

namespace pft::host::tbd {

namespace {
const double kNaN = std::numeric_limits<double>::quiet_NaN();

double dist(double x, double y, const TruthState &t) { return std::hypot(x - t.x, y - t.y); }
}  // namespace

double gospa_cutoff(const Scenario &s) { return s.eval.gospa_c > 0 ? s.eval.gospa_c : s.eval.d_assoc; }

std::vector<TrackHist> collect_tracks(const std::vector<FrameOut> &out)
{
    std::map<uint32_t, TrackHist> m;
    for (const FrameOut &f : out) {
        for (const TrackOut &t : f.tracks) {
            TrackHist &h = m[t.id];
            if (!h.id) {
                h.id = t.id;
                h.first = static_cast<int>(f.frame);
            }
            h.last = static_cast<int>(f.frame);
            h.frames.push_back(static_cast<int>(f.frame));
            h.xs.push_back(t.x);
            h.ys.push_back(t.y);
            h.ps.push_back(t.p_exist);
        }
        for (const EventOut &e : f.events)
            if (e.kind == PFT_TBD_EV_ENDED && m.count(e.id))
                m[e.id].end_frame = static_cast<int>(e.frame);
    }
    std::vector<TrackHist> v;
    for (auto &kv : m)
        v.push_back(std::move(kv.second));
    return v;
}

PcrlbResult target_floor(const Scenario &s, const Target &t)
{
    PcrlbInput in;
    in.peak = s.peak(t.x0[4]);
    in.sigma = s.noise_sigma;
    in.psf_sigma = s.psf_sigma;
    in.intensity = t.x0[4];
    in.dx = s.dx;
    in.dy = s.dy;
    in.T = s.T;
    in.q1 = s.q1;
    in.q2 = s.q2;
    in.stochastic = t.motion == Motion::StochasticCV;
    // birth prior of the filter's configuration (defaults: P0 = 1/3 -> 3; U[10, 30] -> 0.03)
    pft_tbd_config_t c = make_config(s, 0);
    in.vel_info = 2.0 / (from_real(c.vel_var[0]) + from_real(c.vel_var[1]));
    double w = from_real(c.i_max) - from_real(c.i_min);
    in.int_info = 12.0 / (w * w);
    in.frames = t.death - t.birth + 1;
    return pcrlb(in);
}

namespace {

/** The true state of target ti at a frame (1-based), or nullptr when absent. */
struct TruthAt {
    const std::vector<std::vector<TruthState>> &truth;
    const TruthState *operator()(int frame, std::size_t ti) const
    {
        if (frame < 1 || frame > static_cast<int>(truth.size()))
            return nullptr;
        const TruthState &t = truth[frame - 1][ti];
        return t.present ? &t : nullptr;
    }
};

/** assoc[ti][frame] = (track, point) associated with target ti at that frame, track -1: none. */
using AssocPoints = std::vector<std::vector<std::pair<long, std::size_t>>>;

/** Per-frame association: greedy on distance within d_assoc, one track per target and one
 *  target per track (a track may follow different targets in different frames). Fills each
 *  track's per-point assoc. */
AssocPoints associate(RunEval &r, const TruthAt &truth_at, int nf, std::size_t nt, double d_as)
{
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> at_frame(nf + 1);  // (track, point)
    for (std::size_t h = 0; h < r.tracks.size(); ++h) {
        r.tracks[h].assoc.assign(r.tracks[h].frames.size(), -1);
        for (std::size_t k = 0; k < r.tracks[h].frames.size(); ++k) {
            int f = r.tracks[h].frames[k];
            if (f >= 1 && f <= nf)
                at_frame[f].push_back({h, k});
        }
    }
    struct Cand {
        double d;
        std::size_t ti, h, k;
    };
    AssocPoints assoc_pt(nt, std::vector<std::pair<long, std::size_t>>(nf + 1, {-1L, 0}));
    for (int f = 1; f <= nf; ++f) {
        std::vector<Cand> c;
        for (auto [h, k] : at_frame[f])
            for (std::size_t ti = 0; ti < nt; ++ti)
                if (const TruthState *t = truth_at(f, ti)) {
                    double d = dist(r.tracks[h].xs[k], r.tracks[h].ys[k], *t);
                    if (d <= d_as)
                        c.push_back({d, ti, h, k});
                }
        std::sort(c.begin(), c.end(), [](const Cand &a, const Cand &b) { return a.d < b.d; });
        std::vector<bool> used_t(nt, false), used_h(r.tracks.size(), false);
        for (const Cand &x : c) {
            if (used_t[x.ti] || used_h[x.h])
                continue;
            used_t[x.ti] = used_h[x.h] = true;
            r.tracks[x.h].assoc[x.k] = static_cast<int>(x.ti);
            assoc_pt[x.ti][f] = {static_cast<long>(x.h), x.k};
        }
    }
    return assoc_pt;
}

/** Each track's target: the one it was associated with most often; never: a false track. */
void assign_tracks(RunEval &r, std::size_t nt)
{
    for (TrackHist &h : r.tracks) {
        std::vector<int> cnt(nt, 0);
        for (int a : h.assoc)
            if (a >= 0)
                ++cnt[a];
        h.assigned = -1;
        for (std::size_t ti = 0; ti < nt; ++ti)
            if (cnt[ti] > 0 && (h.assigned < 0 || cnt[ti] > cnt[h.assigned]))
                h.assigned = static_cast<int>(ti);
        if (h.assigned < 0)
            ++r.unassigned;
    }
}

/** Disappearance of target ti, whose last associated frame was last_f: the track that
 *  followed it last is declared gone when it ends or is associated with another target; after
 *  last_f the target's existence curve follows that track until then (multi only). */
void disappearance(const Target &tg, std::size_t ti, const TrackHist &h, int last_f, int nf,
                   bool single, TargetRun &tr)
{
    int declared = 0;
    for (std::size_t k = 0; k < h.frames.size(); ++k)
        if (h.frames[k] > last_f && h.assoc[k] >= 0 && h.assoc[k] != static_cast<int>(ti)) {
            declared = h.frames[k];
            break;
        }
    if (!declared)
        declared = h.end_frame;
    if (!single)
        for (std::size_t k = 0; k < h.frames.size(); ++k) {
            int f = h.frames[k];
            if (f > last_f && (!declared || f < declared) && f >= 1 && f <= nf && tr.p_exist[f - 1] == 0.0)
                tr.p_exist[f - 1] = h.ps[k];
        }
    if (declared) {
        tr.disappear_delay = declared - tg.death;
    } else {
        tr.censored = true;
        tr.disappear_delay = nf + 1 - tg.death;
    }
}

/** The measures of target ti in one run (appearance, correct points, errors, confirmation,
 *  disappearance). */
void score_target(const Scenario &s, std::size_t ti, const TruthAt &truth_at, const AssocPoints &assoc_pt,
                  const std::vector<FrameOut> &out, bool single, RunEval &r)
{
    const double d_c = s.eval.d_c;
    const int nf = static_cast<int>(out.size());
    const Target &tg = s.targets[ti];
    TargetRun &tr = r.targets[ti];
    tr.err2.assign(nf, kNaN);
    tr.p_exist.assign(nf, 0.0);
    std::vector<long> ids;
    int last_f = 0;
    for (int f = 1; f <= nf; ++f) {
        const TruthState *t = truth_at(f, ti);
        auto [h, k] = assoc_pt[ti][f];
        tr.p_exist[f - 1] = single ? out[f - 1].search_p : (h >= 0 ? r.tracks[h].ps[k] : 0.0);
        if (!t)
            continue;
        ++tr.true_frames;
        if (h < 0)
            continue;
        if (std::find(ids.begin(), ids.end(), h) == ids.end())
            ids.push_back(h);
        double d = dist(r.tracks[h].xs[k], r.tracks[h].ys[k], *t);
        if (!tr.detected) {
            tr.detected = true;
            tr.appear_frame = f;
            tr.appear_delay = f - tg.birth;
        }
        tr.sq_all += d * d;
        ++tr.n_all;
        if (d <= d_c) {
            ++tr.correct;
            tr.sq_correct += d * d;
            tr.err2[f - 1] = d * d;
        }
        last_f = f;
    }
    tr.tracks = static_cast<int>(ids.size());
    for (const TrackHist &h : r.tracks)
        if (h.first >= tg.birth && h.first <= tg.death && !h.assoc.empty() &&
            h.assoc[0] == static_cast<int>(ti) && (!tr.confirmed || h.first - tg.birth < tr.confirm_delay)) {
            tr.confirmed = true;
            tr.confirm_delay = h.first - tg.birth;
        }
    if (tr.detected)
        disappearance(tg, ti, r.tracks[assoc_pt[ti][last_f].first], last_f, nf, single, tr);
}

}  // namespace

RunEval evaluate_run(const Scenario &s, const std::vector<std::vector<TruthState>> &truth,
                     const std::vector<FrameOut> &out, bool single)
{
    const int nf = static_cast<int>(out.size());
    const std::size_t nt = s.targets.size();
    const TruthAt truth_at{truth};
    RunEval r;
    r.tracks = collect_tracks(out);
    r.targets.resize(nt);
    for (const FrameOut &f : out)
        r.search_p.push_back(f.search_p);
    AssocPoints assoc_pt = associate(r, truth_at, nf, nt, s.eval.d_assoc);
    assign_tracks(r, nt);
    for (std::size_t ti = 0; ti < nt; ++ti)
        score_target(s, ti, truth_at, assoc_pt, out, single, r);
    // set measures per frame: present targets against every reported track point
    const double gc = gospa_cutoff(s), gp = s.eval.gospa_p;
    r.set.resize(nf);
    for (int f = 1; f <= nf; ++f) {
        std::vector<metrics::Point> X, Y;
        for (std::size_t ti = 0; ti < nt; ++ti)
            if (const TruthState *t = truth_at(f, ti))
                X.push_back({t->x, t->y});
        for (const TrackOut &t : out[f - 1].tracks)
            Y.push_back({t.x, t.y});
        metrics::FrameMetrics fm = metrics::frame_metrics(X, Y, gc, gp);
        r.set[f - 1] = {fm.localisation, fm.missed_count, fm.false_count, std::pow(fm.ospa, gp)};
    }
    // declared points against the truth (Deng's false-track probability)
    for (const TrackHist &h : r.tracks) {
        for (std::size_t k = 0; k < h.frames.size(); ++k) {
            ++r.declared_points;
            const TruthState *t = h.assoc[k] >= 0 ? truth_at(h.frames[k], h.assoc[k]) : nullptr;
            if (!t || dist(h.xs[k], h.ys[k], *t) > s.eval.d_c)
                ++r.incorrect_points;
        }
    }
    return r;
}

namespace {

/** Sums of one target's measures over the runs. */
struct TargetSums {
    double app = 0, dis = 0, cor = 0, sqc = 0, sqa = 0, extra = 0, conf = 0;
    int nconf = 0;
    long nc = 0, na = 0;
    int det = 0, ndis = 0, cens = 0;
    std::vector<double> p, e2;
    std::vector<int> ne2;
};

TargetSums sum_target(const std::vector<RunEval> &runs, std::size_t ti, int nf)
{
    TargetSums S;
    S.p.assign(nf, 0.0);
    S.e2.assign(nf, 0.0);
    S.ne2.assign(nf, 0);
    for (const RunEval &r : runs) {
        const TargetRun &t = r.targets[ti];
        if (t.detected) {
            ++S.det;
            S.app += t.appear_delay;
            // a track alive at the end counts with its lower bound frames + 1 - death
            S.cens += t.censored ? 1 : 0;
            S.dis += t.disappear_delay;
            ++S.ndis;
        }
        if (t.confirmed) {
            S.conf += t.confirm_delay;
            ++S.nconf;
        }
        S.cor += t.correct;
        S.sqc += t.sq_correct;
        S.nc += t.correct;
        S.sqa += t.sq_all;
        S.na += t.n_all;
        S.extra += t.tracks > 1 ? t.tracks - 1 : 0;
        for (int k = 0; k < nf && k < static_cast<int>(t.p_exist.size()); ++k) {
            S.p[k] += t.p_exist[k];
            if (std::isfinite(t.err2[k])) {
                S.e2[k] += t.err2[k];
                ++S.ne2[k];
            }
        }
    }
    return S;
}

/** Standard error sd/sqrt(n) over the runs of a per-run measure get(t), for the runs with use(t). */
template <class Get, class Use>
double se_over_runs(const std::vector<RunEval> &runs, std::size_t ti, Get get, Use use)
{
    double m = 0, m2 = 0;
    int n = 0;
    for (const RunEval &r : runs) {
        const TargetRun &t = r.targets[ti];
        if (!use(t))
            continue;
        double v = get(t);
        m += v;
        m2 += v * v;
        ++n;
    }
    if (n < 2)
        return kNaN;
    double var = (m2 - m * m / n) / (n - 1);
    return std::sqrt(std::max(0.0, var) / n);
}

/** Jackknife standard error of the pooled RMSE over correct points. */
double rmse_jackknife_se(const std::vector<RunEval> &runs, std::size_t ti, const TargetSums &S)
{
    if (runs.size() < 2 || S.nc <= 0)
        return kNaN;
    std::vector<double> jk;
    for (const RunEval &r : runs) {
        const TargetRun &t = r.targets[ti];
        long n = S.nc - t.correct;
        if (n > 0)
            jk.push_back(std::sqrt((S.sqc - t.sq_correct) / n));
    }
    if (jk.size() < 2)
        return kNaN;
    double m = 0, ss = 0;
    for (double v : jk)
        m += v;
    m /= jk.size();
    for (double v : jk)
        ss += (v - m) * (v - m);
    return std::sqrt(ss * (jk.size() - 1.0) / jk.size());
}

/** Running sums of the per-target means for the "averaged" block. */
struct Averages {
    double app = 0, dis = 0, cor = 0, true_frames = 0, rmse = 0, floor = 0, fm = 0, ra = 0, false_t = 0;
    double det_rate = 0, app_all = 0;
    int n_app = 0, n_dis = 0, n_rmse = 0;
    std::vector<double> mean_p;
};

/** Per-frame series of one target: mean existence, RMSE, correct fraction, floor; and the
 *  floor matched to the correct points. Adds the existence to the averages. */
struct FrameSeries {
    nlohmann::json p, rmse, correct, floor;
    double matched_num = 0;
};

FrameSeries frame_series(TargetSums &S, const Target &tg, const PcrlbResult &fl, int nf, double Rd,
                         std::size_t nt, Averages &A)
{
    using nlohmann::json;
    FrameSeries f;
    f.p = json::array();
    f.rmse = json::array();
    f.correct = json::array();
    f.floor = json::array();
    for (int k = 0; k < nf; ++k) {
        S.p[k] /= Rd;
        A.mean_p[k] += S.p[k] / static_cast<double>(nt ? nt : 1);
        f.p.push_back(S.p[k]);
        f.rmse.push_back(num_or_null(S.ne2[k] ? std::sqrt(S.e2[k] / S.ne2[k]) : kNaN));
        f.correct.push_back(S.ne2[k] / Rd);
        int life = k + 1 - tg.birth;
        double fk = (life >= 0 && life < static_cast<int>(fl.radial.size())) ? fl.radial[life] : kNaN;
        f.floor.push_back(num_or_null(fk));
        if (std::isfinite(fk))
            f.matched_num += S.ne2[k] * fk * fk;
    }
    return f;
}

/** The summary of target ti (contract names), adding to the averages. */
nlohmann::json target_summary(const Scenario &s, const std::vector<RunEval> &runs, std::size_t ti, int nf,
                              Averages &A)
{
    using nlohmann::json;
    const std::size_t nt = s.targets.size();
    const std::size_t R = runs.size();
    const Target &tg = s.targets[ti];
    PcrlbResult fl = target_floor(s, tg);
    TargetSums S = sum_target(runs, ti, nf);
    double Rd = R ? static_cast<double>(R) : 1.0;
    FrameSeries fs = frame_series(S, tg, fl, nf, Rd, nt, A);
    const json &pf = fs.p, &rf = fs.rmse, &cf = fs.correct, &ff = fs.floor;
    const double matched_num = fs.matched_num;
    double rmse = S.nc ? std::sqrt(S.sqc / S.nc) : kNaN;
    auto detected = [](const TargetRun &t) { return t.detected; };
    auto always = [](const TargetRun &) { return true; };
    double app_se = se_over_runs(runs, ti, [](const TargetRun &t) { return t.appear_delay; }, detected);
    double dis_se = se_over_runs(runs, ti, [](const TargetRun &t) { return t.disappear_delay; }, detected);
    double cor_se = se_over_runs(runs, ti, [](const TargetRun &t) { return static_cast<double>(t.correct); }, always);
    double rmse_se = rmse_jackknife_se(runs, ti, S);
    double rmse_all = S.na ? std::sqrt(S.sqa / S.na) : kNaN;
    double matched = S.nc ? std::sqrt(matched_num / S.nc) : kNaN;
    double app_m = S.det ? S.app / S.det : kNaN, dis_m = S.ndis ? S.dis / S.ndis : kNaN;
    const int life = tg.death - tg.birth + 1;
    // a miss as a miss: over all runs, a run that never detected the target counts its whole life
    double det_rate = R ? S.det / Rd : kNaN;
    double app_all = R ? (S.app + static_cast<double>(R - S.det) * life) / Rd : kNaN;
    json tj = {
        {"id", tg.id},
        {"birth_frame", tg.birth},
        {"death_frame", tg.death},
        {"motion", tg.motion == Motion::Line ? "line" : "cv"},
        {"appearance_delay", num_or_null(app_m)},
        {"disappearance_delay", num_or_null(dis_m)},
        {"correct_frames", S.cor / Rd},
        {"true_frames", tg.death - tg.birth + 1},
        {"rmse", num_or_null(rmse)},
        {"pcrlb", fl.track_rmse},
        {"false_tracks", S.extra / Rd},
        {"detected_runs", S.det},
        {"detection_rate", num_or_null(det_rate)},
        {"appearance_delay_all_runs", num_or_null(app_all)},
        {"confirmation_delay", num_or_null(S.nconf ? S.conf / S.nconf : kNaN)},
        {"confirmed_runs", S.nconf},
        {"appearance_delay_se", num_or_null(app_se)},
        {"disappearance_delay_se", num_or_null(dis_se)},
        {"correct_frames_se", num_or_null(cor_se)},
        {"rmse_se", num_or_null(rmse_se)},
        {"censored_disappearances", S.cens},
        {"rmse_all_assigned", num_or_null(rmse_all)},
        {"pcrlb_matched", num_or_null(matched)},
        {"rmse_over_pcrlb", num_or_null(rmse / fl.track_rmse)},
        {"existence_probability", pf},
        {"rmse_per_frame", rf},
        {"correct_fraction_per_frame", cf},
        {"pcrlb_per_frame", ff},
    };
    if (std::isfinite(app_m)) {
        A.app += app_m;
        ++A.n_app;
    }
    if (std::isfinite(dis_m)) {
        A.dis += dis_m;
        ++A.n_dis;
    }
    A.cor += S.cor / Rd;
    A.true_frames += tg.death - tg.birth + 1;
    if (std::isfinite(rmse)) {
        A.rmse += rmse;
        A.fm += matched;
        A.ra += rmse_all;
        ++A.n_rmse;
    }
    A.floor += fl.track_rmse;
    A.false_t += S.extra / Rd;
    A.det_rate += det_rate;
    A.app_all += app_all;
    return tj;
}

/** The per-run block: seed, unassigned tracks and each target's detection and counts. */
nlohmann::json per_run_summary(const std::vector<RunEval> &runs, double c, double p)
{
    using nlohmann::json;
    json per_run = json::array();
    for (const RunEval &r : runs) {
        metrics::SetMetricSums one(r.set.size(), c, p);
        for (std::size_t k = 0; k < r.set.size(); ++k)
            one.add_terms(k, r.set[k].localisation, r.set[k].missed, r.set[k].false_, r.set[k].ospa_pow);
        json pr = {{"seed", r.seed}, {"unassigned_tracks", r.unassigned}, {"gospa", num_or_null(one.gospa())},
                   {"ospa", num_or_null(one.ospa())}};
        json tt = json::array();
        for (const TargetRun &t : r.targets)
            tt.push_back({{"detected", t.detected},
                          {"appearance_delay", t.detected ? json(t.appear_delay) : json(nullptr)},
                          {"disappearance_delay", t.detected ? json(t.disappear_delay) : json(nullptr)},
                          {"censored", t.censored},
                          {"correct_frames", t.correct},
                          {"tracks", t.tracks}});
        pr["targets"] = tt;
        per_run.push_back(pr);
    }
    return per_run;
}

}  // namespace

nlohmann::json summarize(const Scenario &s, const std::vector<RunEval> &runs, bool single)
{
    using nlohmann::json;
    const std::size_t nt = s.targets.size();
    const std::size_t R = runs.size();
    const int nf = R ? static_cast<int>(runs[0].search_p.size()) : s.frames;
    json targets = json::array();
    Averages A;
    A.mean_p.assign(nf, 0.0);
    for (std::size_t ti = 0; ti < nt; ++ti)
        targets.push_back(target_summary(s, runs, ti, nf, A));
    double unassigned = 0, decl = 0, incorrect = 0;
    std::vector<double> sp(nf, 0.0);
    for (const RunEval &r : runs) {
        unassigned += r.unassigned;
        decl += r.declared_points;
        incorrect += r.incorrect_points;
        for (int k = 0; k < nf && k < static_cast<int>(r.search_p.size()); ++k)
            sp[k] += r.search_p[k] / static_cast<double>(R ? R : 1);
    }
    double Rd = R ? static_cast<double>(R) : 1.0;
    // no target (noise only): the per-target means do not exist (null), they are not 0
    const double ntd = nt ? static_cast<double>(nt) : kNaN;
    const double gc = gospa_cutoff(s), gp = s.eval.gospa_p;
    metrics::SetMetricSums sm(static_cast<std::size_t>(nf), gc, gp);
    for (const RunEval &r : runs)
        for (std::size_t k = 0; k < r.set.size() && k < static_cast<std::size_t>(nf); ++k)
            sm.add_terms(k, r.set[k].localisation, r.set[k].missed, r.set[k].false_, r.set[k].ospa_pow);
    std::vector<double> gpf(nf), opf(nf);
    for (int k = 0; k < nf; ++k) {
        gpf[k] = sm.gospa_at(k);
        opf[k] = sm.ospa_at(k);
    }
    json avg = {
        {"appearance_delay", num_or_null(A.n_app ? A.app / A.n_app : kNaN)},
        {"appearance_delay_all_runs", num_or_null(A.app_all / ntd)},
        {"detection_rate", num_or_null(A.det_rate / ntd)},
        {"disappearance_delay", num_or_null(A.n_dis ? A.dis / A.n_dis : kNaN)},
        {"correct_frames", num_or_null(A.cor / ntd)},
        {"true_frames", num_or_null(A.true_frames / ntd)},
        {"rmse", num_or_null(A.n_rmse ? A.rmse / A.n_rmse : kNaN)},
        {"pcrlb", num_or_null(A.floor / ntd)},
        {"gospa_per_frame", nums_or_null(gpf)},
        {"ospa_per_frame", nums_or_null(opf)},
        {"false_tracks", (unassigned + 0.0) / Rd + A.false_t},
        {"unassigned_tracks", unassigned / Rd},
        {"false_point_fraction", num_or_null(decl > 0 ? incorrect / decl : kNaN)},
        {"rmse_all_assigned", num_or_null(A.n_rmse ? A.ra / A.n_rmse : kNaN)},
        {"pcrlb_matched", num_or_null(A.n_rmse ? A.fm / A.n_rmse : kNaN)},
        {"existence_probability", nt ? json(A.mean_p) : nums_or_null(std::vector<double>(nf, kNaN))},
    };
    avg.update(metrics::set_metric_fields(sm));
    json j;
    j["targets"] = targets;
    j["averaged"] = avg;
    j[single ? "filter_existence_probability" : "search_existence_probability"] = sp;
    j["per_run"] = per_run_summary(runs, gc, gp);
    j["gospa_c"] = gc;
    j["gospa_p"] = gp;
    j["gospa_alpha"] = 2;
    return j;
}

nlohmann::json run_to_json(const RunEval &r)
{
    using nlohmann::json;
    json tt = json::array();
    for (const TargetRun &t : r.targets)
        tt.push_back({{"detected", t.detected}, {"appear_frame", t.appear_frame}, {"appear_delay", t.appear_delay},
                      {"confirmed", t.confirmed}, {"confirm_delay", t.confirm_delay}, {"censored", t.censored},
                      {"disappear_delay", t.disappear_delay}, {"correct", t.correct},
                      {"true_frames", t.true_frames}, {"sq_correct", t.sq_correct}, {"sq_all", t.sq_all},
                      {"n_all", t.n_all}, {"tracks", t.tracks}, {"err2", nums_or_null(t.err2)},
                      {"p_exist", t.p_exist}});
    json set = json::array();
    for (const SetFrame &f : r.set)
        set.push_back({f.localisation, f.missed, f.false_, f.ospa_pow});
    return {{"seed", r.seed}, {"targets", tt}, {"unassigned", r.unassigned},
            {"declared_points", r.declared_points}, {"incorrect_points", r.incorrect_points},
            {"search_p", r.search_p}, {"set", set}};
}

RunEval run_from_json(const nlohmann::json &j)
{
    RunEval r;
    r.seed = j.at("seed").get<uint64_t>();
    for (const auto &x : j.at("targets")) {
        TargetRun t;
        t.detected = x.at("detected").get<bool>();
        t.appear_frame = x.at("appear_frame").get<int>();
        t.appear_delay = x.at("appear_delay").get<double>();
        t.confirmed = x.at("confirmed").get<bool>();
        t.confirm_delay = x.at("confirm_delay").get<double>();
        t.censored = x.at("censored").get<bool>();
        t.disappear_delay = x.at("disappear_delay").get<double>();
        t.correct = x.at("correct").get<int>();
        t.true_frames = x.at("true_frames").get<int>();
        t.sq_correct = x.at("sq_correct").get<double>();
        t.sq_all = x.at("sq_all").get<double>();
        t.n_all = x.at("n_all").get<int>();
        t.tracks = x.at("tracks").get<int>();
        t.err2 = nulls_to_nan(x.at("err2"));
        t.p_exist = x.at("p_exist").get<std::vector<double>>();
        r.targets.push_back(std::move(t));
    }
    r.unassigned = j.at("unassigned").get<int>();
    r.declared_points = j.at("declared_points").get<int>();
    r.incorrect_points = j.at("incorrect_points").get<int>();
    r.search_p = j.at("search_p").get<std::vector<double>>();
    for (const auto &f : j.at("set"))
        r.set.push_back({f.at(0).get<double>(), f.at(1).get<int>(), f.at(2).get<int>(), f.at(3).get<double>()});
    return r;
}

}  // namespace pft::host::tbd
