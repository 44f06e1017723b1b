#include "ir_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/output.hpp"
#include "../common/real.hpp"

namespace pft::host::tbd_ir {

namespace {

// Median and robust sd (1.4826 MAD) of v (reordered).
void robust(std::vector<float> &v, double &med, double &sd)
{
    med = sd = NAN;
    if (v.empty())
        return;
    const std::size_t h = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
    med = v[h];
    for (float &a : v)
        a = std::fabs(a - static_cast<float>(med));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(h), v.end());
    sd = 1.4826 * v[h];
}

std::string num(double v, int prec = 3)
{
    return fixed_text(v, prec, "");
}

// "id:frames;id:frames" of a map truth id -> frames.
std::string joined(const std::map<int, int> &m)
{
    std::string s;
    for (const auto &p : m)
        s += (s.empty() ? "" : ";") + std::to_string(p.first) + ":" + std::to_string(p.second);
    return s;
}

}  // namespace

IrTrace::IrTrace(const IrScenario &s, const IrSequence &q, uint64_t seed) : s_(s), q_(q), seed_(seed)
{
    // the PSF-matched filter of unit noise gain: g / sqrt(sum g^2), g the point-sampled PSF
    const int R = 3;
    kern_.create(2 * R + 1, 2 * R + 1, CV_32F);
    double ss = 0;
    for (int b = -R; b <= R; ++b)
        for (int a = -R; a <= R; ++a) {
            const double g = std::exp(-(a * a + b * b) / (2.0 * s.targets.psf_sigma * s.targets.psf_sigma));
            kern_.at<float>(b + R, a + R) = static_cast<float>(g);
            ss += g * g;
        }
    kern_ /= std::sqrt(ss);
}

void IrTrace::frame(int k, const IrPipeline &pl, const tbd::FrameOut &out)
{
    const pft_tbd_t &m = pl.tracker().manager();
    const pft_tbd_config_t &c = m.cfg;
    const double dx = from_real(c.dx), dy = from_real(c.dy);
    // the search layers (cfg.search_layers = H >= 2: layers 1 .. H - 1 in search_x) and their
    // confirmation counts
    const uint32_t nl = c.search_layers >= 2u ? static_cast<uint32_t>(c.search_layers) : 1u;
    auto slayer = [&m](uint32_t h) -> const pft_tbd_filter_t & { return h == 0u ? m.search : m.search_x[h - 1u]; };
    auto sabove = [&m](uint32_t h) -> uint8_t { return h == 0u ? m.above : m.above_x[h - 1u]; };
    const cv::Mat &res = pl.residual();
    const int W = res.cols, H = res.rows;
    cv::Mat mf, dil;
    cv::filter2D(res, mf, CV_32F, kern_, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
    cv::dilate(mf, dil, cv::Mat::ones(3, 3, CV_8U));
    std::vector<float> peaks;  // the frame's 3 x 3 local maxima of the matched filter, descending
    for (int y = 0; y < H; ++y) {
        const float *p = mf.ptr<float>(y), *d = dil.ptr<float>(y);
        for (int x = 0; x < W; ++x)
            if (p[x] > 0 && p[x] >= d[x])
                peaks.push_back(p[x]);
    }
    std::sort(peaks.begin(), peaks.end(), std::greater<float>());
    // the stage's residual before the clutter map (kept by the pipeline while tracing): its
    // matched filter, for the same z at the target before the map
    cv::Mat mfs;
    const bool stage = !pl.stage_residual().empty();
    if (stage)
        cv::filter2D(pl.stage_residual(), mfs, CV_32F, kern_, cv::Point(-1, -1), 0, cv::BORDER_CONSTANT);
    const std::array<double, 2> sc = pl.scene_shift();
    scene_x_ = sc[0];
    scene_y_ = sc[1];

    // the track records: ends (with the reason read from the slot's layer) and hand-overs
    if (slot_id_.empty())
        slot_id_.assign(c.max_targets, 0u);
    struct Rec { double x, y; uint32_t id; bool tentative; double in; };
    std::vector<Rec> recs;
    for (uint32_t k2 = 0; k2 < c.max_targets; ++k2) {
        const pft_tbd_track_t &r = m.records[k2];
        if (r.id != 0u)
            recs.push_back({from_real(r.x) - dx, from_real(r.y) - dy, r.id, r.first_frame == 0u,
                            from_real(r.intensity)});
    }
    for (uint32_t k2 = 0; k2 < c.max_targets; ++k2) {
        const uint32_t id = m.records[k2].id, prev = slot_id_[k2];
        if (prev != 0u && id != prev) {
            TrackLife &L = life_[prev];
            L.end = k;
            if (id != 0u) {
                L.reason = "slot_reused";  // a hand-over into the freed slot at the same frame
            } else {
                const pft_tbd_filter_t &tf = m.tracks[k2];
                uint32_t alive = 0;
                for (uint32_t p = 0; p < tf.n; ++p)
                    alive += tf.cur.e[p] != 0u ? 1u : 0u;
                if (tf.gone)
                    L.reason = "disappearance_test";
                else if (from_real(tf.est.p_exist) < from_real(c.theta_end))
                    L.reason = "existence";
                else if (alive == 0u)
                    L.reason = "no_particle";
                else if (c.end_lr_frames > 0u)
                    L.reason = "lr_window";
                else if (from_real(c.sprt_accept) > 0)
                    L.reason = "sequential_test";
                else
                    L.reason = "other";
            }
            for (const Rec &r : recs)
                if (r.id != prev && std::hypot(r.x - L.lx, r.y - L.ly) <= 3.0)
                    L.merged = true;
            L.scene_dx = scene_x_ - L.sx0;
            L.scene_dy = scene_y_ - L.sy0;
        }
        if (id != 0u && id != prev) {
            TrackLife &L = life_[id];
            L.id = id;
            L.handover = k;
            // the search layer that handed it over, from its record (-1: made by a split)
            L.hlayer = m.records[k2].search_layer == PFT_TBD_LAYER_NONE ? -1 : static_cast<int>(m.records[k2].search_layer);
            L.hx = from_real(m.records[k2].x) - dx;
            L.hy = from_real(m.records[k2].y) - dy;
            L.hp = from_real(m.records[k2].p_exist);
            L.hi = from_real(m.records[k2].intensity);
            L.sx0 = scene_x_;
            L.sy0 = scene_y_;
        }
        slot_id_[k2] = id;
    }
    std::vector<const TruthRow *> truth;
    for (const TruthRow &r : q_.truth)
        if (r.frame == k)
            truth.push_back(&r);
    for (const Rec &r : recs) {
        TrackLife &L = life_[r.id];
        ++L.alive;
        L.lx = r.x;
        L.ly = r.y;
        L.li = r.in;
        L.scene = L.scene || pl.scene_flagged(r.id);
        L.scene_dx = scene_x_ - L.sx0;
        L.scene_dy = scene_y_ - L.sy0;
        for (const TruthRow *t : truth)
            if (std::hypot(r.x - t->x, r.y - t->y) <= 3.0)
                ++L.near[t->id];
    }
    // per live track layer: age, state, existence and the nearest truth point
    for (uint32_t k2 = 0; k2 < c.max_targets; ++k2) {
        const pft_tbd_track_t &r = m.records[k2];
        if (r.id == 0u)
            continue;
        const double x = from_real(r.x) - dx, y = from_real(r.y) - dy;
        double td = 1e9;
        int tid = 0;
        bool lab = false;
        for (const TruthRow *t : truth) {
            const double d = std::hypot(x - t->x, y - t->y);
            if (d < td) {
                td = d;
                tid = t->id;
                lab = t->labelled;
            }
        }
        bool rep = false;
        for (const tbd::TrackOut &t : out.tracks)
            rep = rep || t.id == r.id;
        // cfg.resid_split: the layer's largest matched residual beside it and the truth point
        // nearest to that peak (0 when not tested)
        const pft_tbd_filter_t &lf = m.tracks[k2];
        const double rm = from_real(lf.resid_m);
        const double qx = from_real(lf.resid_x) - dx, qy = from_real(lf.resid_y) - dy;
        double qd = 1e9;
        int qtid = 0;
        for (const TruthRow *t : truth) {
            const double d = std::hypot(qx - t->x, qy - t->y);
            if (d < qd) {
                qd = d;
                qtid = t->id;
            }
        }
        const bool tested = rm != 0.0;
        layer_rows_.push_back(std::to_string(seed_) + "," + std::to_string(k) + "," + std::to_string(r.id) + "," +
                              std::to_string(k - life_[r.id].handover) + "," + num(x, 2) + "," + num(y, 2) + "," +
                              num(from_real(r.p_exist), 4) + "," + num(from_real(r.intensity), 2) + "," +
                              num(from_real(r.log_mean_lr), 3) + "," + (r.first_frame == 0u ? "1" : "0") + "," +
                              (rep ? "1" : "0") + "," + std::to_string(tid) + "," + (lab ? "1" : "0") + "," +
                              (tid ? num(td, 2) : std::string()) + "," + num(scene_x_, 4) + "," +
                              num(scene_y_, 4) + "," + std::to_string(pl.scene_decision(r.id)) + "," +
                              num(from_real(r.pos_cov[0]), 4) + "," + num(from_real(r.pos_cov[2]), 4) + "," +
                              num(x + dx, 5) + "," + num(y + dy, 5) + "," + num(rm, 3) + "," +
                              (tested ? num(qx, 1) + "," + num(qy, 1) : std::string(",")) + "," +
                              std::to_string(static_cast<int>(lf.resid_n)) + "," +
                              (tested && qtid ? std::to_string(qtid) + "," + num(qd, 2) : std::string(",")) + "," +
                              std::to_string(life_[r.id].hlayer));
    }
    for (const tbd::TrackOut &t : out.tracks) {
        auto it = life_.find(t.id);
        if (it == life_.end())
            continue;
        TrackLife &L = it->second;
        if (L.reported == 0)
            L.first_reported = k;
        ++L.reported;
        L.last_reported = k;
        for (const TruthRow *r : truth)
            if (std::hypot(t.x - r->x, t.y - r->y) <= 3.0)
                ++L.near_rep[r->id];
    }

    // per truth point: the residual, the search layer, births, track layers, reports
    std::vector<pft_tbd_estimate_t> sest(nl);
    for (uint32_t h = 0; h < nl; ++h)
        pft_tbd_search_layer_estimate(&m, h, &sest[h]);
    for (const TruthRow *t : truth) {
        // the search layer whose estimate is nearest to the point (layer 0 when no layer has
        // one; with one layer, that layer), and the largest P over the layers whose estimate
        // lies within 3 px of it
        uint32_t sl = 0;
        double sd = NAN, spmax = NAN;
        for (uint32_t h = 0; h < nl; ++h) {
            if (!sest[h].valid)
                continue;
            const double d = std::hypot(from_real(sest[h].x) - t->x, from_real(sest[h].y) - t->y);
            if (std::isnan(sd) || d < sd) {
                sd = d;
                sl = h;
            }
            if (d <= 3.0 && !(from_real(sest[h].p_exist) <= spmax))
                spmax = from_real(sest[h].p_exist);
        }
        const pft_tbd_filter_t &sf = slayer(sl);
        const double sp = from_real(sest[sl].p_exist);
        const long xi = std::lround(t->x), yi = std::lround(t->y);
        if (xi < 0 || yi < 0 || xi >= W || yi >= H)
            continue;
        float mf_at = mf.at<float>(static_cast<int>(yi), static_cast<int>(xi)), mf3 = -1e9f;
        for (long b = -1; b <= 1; ++b)
            for (long a = -1; a <= 1; ++a) {
                const long x = xi + a, y = yi + b;
                if (x >= 0 && y >= 0 && x < W && y < H)
                    mf3 = std::max(mf3, mf.at<float>(static_cast<int>(y), static_cast<int>(x)));
            }
        // the matched filter and the residual around it: 31 x 31 less the 7 x 7 core
        std::vector<float> lm, lr, ls, lrs;
        for (long b = -15; b <= 15; ++b)
            for (long a = -15; a <= 15; ++a) {
                const long x = xi + a, y = yi + b;
                if ((std::labs(a) <= 3 && std::labs(b) <= 3) || x < 0 || y < 0 || x >= W || y >= H)
                    continue;
                lm.push_back(mf.at<float>(static_cast<int>(y), static_cast<int>(x)));
                lr.push_back(res.at<float>(static_cast<int>(y), static_cast<int>(x)));
                if (stage) {
                    ls.push_back(mfs.at<float>(static_cast<int>(y), static_cast<int>(x)));
                    lrs.push_back(pl.stage_residual().at<float>(static_cast<int>(y), static_cast<int>(x)));
                }
            }
        double lmed, lsd, rmed, rsd, smed = NAN, ssd = NAN, srmed = NAN, srsd = NAN;
        robust(lm, lmed, lsd);
        robust(lr, rmed, rsd);
        const double mf_stage = stage ? mfs.at<float>(static_cast<int>(yi), static_cast<int>(xi)) : NAN;
        if (stage) {
            robust(ls, smed, ssd);
            robust(lrs, srmed, srsd);
        }
        // the matched filter centred on the true sub-pixel position (what a likelihood at the
        // true position weighs): sum r(p) g(p - x) / sqrt(sum g(p - x)^2) over the 7 x 7 pixels
        // around the nearest one, on the map's residual and on the stage's
        double sub_map = 0, sub_stage = stage ? 0.0 : NAN, gg = 0;
        {
            const double ps = s_.targets.psf_sigma;
            for (long b = -3; b <= 3; ++b)
                for (long a = -3; a <= 3; ++a) {
                    const long x = xi + a, y = yi + b;
                    if (x < 0 || y < 0 || x >= W || y >= H)
                        continue;
                    const double ex = static_cast<double>(x) - t->x, ey = static_cast<double>(y) - t->y;
                    const double g = std::exp(-(ex * ex + ey * ey) / (2.0 * ps * ps));
                    gg += g * g;
                    sub_map += g * res.at<float>(static_cast<int>(y), static_cast<int>(x));
                    if (stage)
                        sub_stage += g * pl.stage_residual().at<float>(static_cast<int>(y), static_cast<int>(x));
                }
            sub_map /= std::sqrt(gg);
            sub_stage /= std::sqrt(gg);
        }
        const long rank = std::upper_bound(peaks.begin(), peaks.end(), mf3, std::greater<float>()) - peaks.begin();
        uint32_t alive = 0, near = 0;
        for (uint32_t p = 0; p < sf.n; ++p) {
            if (sf.cur.e[p] == 0u)
                continue;
            ++alive;
            if (std::hypot(from_real(sf.cur.x[p]) - dx - t->x, from_real(sf.cur.y[p]) - dy - t->y) <= 3.0)
                ++near;
        }
        int b1 = 0, b3 = 0;
        for (uint32_t p : out.births) {
            const long bc = static_cast<long>(p % static_cast<uint32_t>(W)), br = static_cast<long>(p / static_cast<uint32_t>(W));
            const long dd = std::max(std::labs(bc - xi), std::labs(br - yi));
            b1 += dd <= 1;
            b3 += dd <= 3;
        }
        double td = 1e9, rd = 1e9;
        uint32_t tid = 0, rid = 0;
        bool tent = false;
        double tin = NAN;
        for (const Rec &r : recs) {
            const double d = std::hypot(r.x - t->x, r.y - t->y);
            if (d < td) {
                td = d;
                tid = r.id;
                tent = r.tentative;
                tin = r.in;
            }
        }
        for (const tbd::TrackOut &r : out.tracks) {
            const double d = std::hypot(r.x - t->x, r.y - t->y);
            if (d < rd) {
                rd = d;
                rid = r.id;
            }
        }
        std::string row = std::to_string(seed_) + "," + std::to_string(k) + "," + std::to_string(t->id) + "," +
                          (t->labelled ? "1" : "0") + "," + num(t->x, 2) + "," + num(t->y, 2) + "," + num(mf_at) +
                          "," + num(mf3) + "," + num(lmed) + "," + num(lsd) + "," + num(rsd) + "," +
                          std::to_string(rank) + "," + std::to_string(peaks.size()) + "," + num(sp, 4) +
                          "," + num(sd, 2) + "," + std::to_string(sf.n) + "," + std::to_string(alive) + "," +
                          std::to_string(near) + "," + std::to_string(b1) + "," + std::to_string(b3) + "," +
                          std::to_string(out.births.size()) + "," + (tid ? num(td, 2) : std::string()) + "," +
                          std::to_string(tid) + "," + (tent ? "1" : "0") + "," + (rid ? num(rd, 2) : std::string()) +
                          "," + std::to_string(rid) + "," + std::to_string(m.n_tracks) + "," +
                          std::to_string(sabove(sl)) + "," + num(from_real(sf.est.intensity), 2) + "," + num(tin, 2) + "," +
                          num(mf_stage) + "," + num(smed) + "," + num(ssd) + "," + num(srsd) + "," + num(sub_map) + "," +
                          num(sub_stage) + "," + std::to_string(sl) + "," + num(spmax, 4);
        rows_.push_back(row);
    }
}

void IrTrace::write(const std::string &dir, const IrRunEval &ev) const
{
    const std::string base = dir + "/s" + std::to_string(seed_);
    write_text_atomic(base + "_targets.csv", [&](std::ostream &f) {
        f << "seed,frame,tid,labelled,x,y,mf_at,mf3,loc_med,loc_sd,res_sd,rank,n_peaks,search_p,search_d,"
             "search_n,alive,alive_near,births1,births3,n_births,trk_d,trk_id,trk_tentative,rep_d,rep_id,"
             "n_tracks,above,search_int,trk_int,mf_stage,loc_med_stage,loc_sd_stage,res_sd_stage,mfsub_at,mfsub_stage,search_layer,search_p_max\n";
        for (const std::string &r : rows_)
            f << r << "\n";
    });
    write_text_atomic(base + "_tracks.csv", [&](std::ostream &f) { write_tracks_(f, ev); });
    write_text_atomic(base + "_layers.csv", [&](std::ostream &f) {
        f << "seed,frame,id,age,x,y,p_exist,intensity,log_mean_lr,tentative,reported,near_tid,near_labelled,near_d,scene_x,scene_y,scene_dec,cov_xx,cov_yy,rx,ry,resid_m,resid_x,resid_y,resid_n,resid_tid,resid_d,handover_layer\n";
        for (const std::string &r : layer_rows_)
            f << r << "\n";
    });
}

void IrTrace::write_tracks_(std::ostream &f, const IrRunEval &ev) const
{
    f << "seed,id,handover,hx,hy,hp,hi,li,end,reason,merged,alive,scene_flag,reported,first_reported,last_reported,"
         "lx,ly,scene_dx,scene_dy,near_tid,near_frames,near_rep_tid,near_rep_frames,near_all,near_rep_all,is_false,false_x,false_y,"
         "false_scene_x,false_scene_y,handover_layer\n";
    for (const auto &kv : life_) {
        const TrackLife &L = kv.second;
        int nt = 0, nf = 0, rt = 0, rf = 0;
        for (const auto &p : L.near)
            if (p.second > nf) {
                nt = p.first;
                nf = p.second;
            }
        for (const auto &p : L.near_rep)
            if (p.second > rf) {
                rt = p.first;
                rf = p.second;
            }
        bool fals = false;
        const TrackSpan *ft = nullptr;
        for (const TrackSpan &x : ev.false_list)
            if (x.id == L.id) {
                fals = true;
                ft = &x;
            }
        f << seed_ << "," << L.id << "," << L.handover << "," << num(L.hx, 2) << "," << num(L.hy, 2) << ","
          << num(L.hp, 3) << "," << num(L.hi, 2) << "," << num(L.li, 2) << "," << L.end << "," << L.reason << "," << (L.merged ? 1 : 0) << "," << L.alive << ","
          << (L.scene ? 1 : 0) << "," << L.reported << "," << L.first_reported << "," << L.last_reported << ","
          << num(L.lx, 2) << "," << num(L.ly, 2) << "," << num(L.scene_dx, 2) << "," << num(L.scene_dy, 2) << ","
          << nt << "," << nf << "," << rt << "," << rf << "," << joined(L.near) << "," << joined(L.near_rep) << ","
          << (fals ? 1 : 0) << ","
          << (ft ? num(ft->x, 2) : std::string()) << "," << (ft ? num(ft->y, 2) : std::string()) << ","
          << (ft ? num(ft->scene_x, 2) : std::string()) << "," << (ft ? num(ft->scene_y, 2) : std::string())
          << "," << L.hlayer << "\n";
    }
}

}  // namespace pft::host::tbd_ir
