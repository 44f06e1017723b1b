#include "ir_dbt.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>

extern "C" {
#include "pft/pft_types.h"
}

namespace pft::host::tbd_ir {

double dbt_threshold(double pfa)
{
    // Q(t) = erfc(t / sqrt 2) / 2 falls monotonically: bisection to 1e-9 sigma
    double lo = -40.0, hi = 40.0;
    for (int i = 0; i < 200 && hi - lo > 1e-9; ++i) {
        double mid = 0.5 * (lo + hi);
        if (0.5 * std::erfc(mid / std::sqrt(2.0)) > pfa)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

std::vector<Detection> dbt_detect(const int16_t *res, int width, int height, int stride_px,
                                  double threshold, int max_detections)
{
    // a pixel exceeds when its Q8.8 value is at or above the threshold (rounded up to 1/256)
    const int thr = static_cast<int>(std::ceil(threshold * 256.0));
    auto above = [&](int x, int y) {
        int16_t v = res[static_cast<std::ptrdiff_t>(y) * stride_px + x];
        return v != PFT_RES16_MASKED && v >= thr;
    };
    std::vector<uint8_t> seen(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    std::vector<Detection> out;
    std::vector<int> stack;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::size_t i0 = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
            if (seen[i0] || !above(x, y))
                continue;
            // one 8-connected component, flood-filled with an explicit stack
            double sw = 0, sx = 0, sy = 0, peak = 0;
            int n = 0;
            seen[i0] = 1;
            stack.assign(1, y * width + x);
            while (!stack.empty()) {
                int p = stack.back();
                stack.pop_back();
                int px = p % width, py = p / width;
                double v = res[static_cast<std::ptrdiff_t>(py) * stride_px + px] / 256.0;
                sw += v;
                sx += v * px;
                sy += v * py;
                peak = std::max(peak, v);
                ++n;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        int qx = px + dx, qy = py + dy;
                        if (qx < 0 || qy < 0 || qx >= width || qy >= height)
                            continue;
                        std::size_t qi = static_cast<std::size_t>(qy) * static_cast<std::size_t>(width) +
                                         static_cast<std::size_t>(qx);
                        if (!seen[qi] && above(qx, qy)) {
                            seen[qi] = 1;
                            stack.push_back(qy * width + qx);
                        }
                    }
            }
            Detection d;
            d.x = sx / sw;
            d.y = sy / sw;
            d.peak = peak;
            d.pixels = n;
            out.push_back(d);
        }
    if (static_cast<int>(out.size()) > max_detections) {
        std::stable_sort(out.begin(), out.end(), [](const Detection &a, const Detection &b) { return a.peak > b.peak; });
        out.resize(static_cast<std::size_t>(max_detections));
    }
    return out;
}

DbtTracker::DbtTracker(const DbtSettings &s) : S_(s) {}

tbd::FrameOut DbtTracker::step(const std::vector<Detection> &dets, uint32_t frame)
{
    tbd::FrameOut out;
    out.frame = frame;
    const double q2 = S_.accel_sigma * S_.accel_sigma, r2 = S_.meas_sigma_px * S_.meas_sigma_px;
    // predict (constant velocity, white acceleration; the axes are independent)
    for (Track &t : tracks_) {
        for (int a = 0; a < 2; ++a) {
            t.x[a] += t.x[2 + a];
            double *P = t.P[a];
            double pp = P[0] + 2 * P[1] + P[2] + 0.25 * q2, pv = P[1] + P[2] + 0.5 * q2, vv = P[2] + q2;
            P[0] = pp;
            P[1] = pv;
            P[2] = vv;
        }
        t.hits <<= 1;
        ++t.age;
    }
    // association: confirmed tracks first, then tentative ones, each class greedily by NIS
    std::vector<int> taken(dets.size(), 0);
    std::vector<int> assoc(tracks_.size(), -1);
    for (int cls = 0; cls < 2; ++cls) {
        struct Cand { double nis; std::size_t t, d; };
        std::vector<Cand> c;
        for (std::size_t i = 0; i < tracks_.size(); ++i) {
            const Track &t = tracks_[i];
            if (t.confirmed != (cls == 0))
                continue;
            double sx = t.P[0][0] + r2, sy = t.P[1][0] + r2;
            for (std::size_t j = 0; j < dets.size(); ++j) {
                double dx = dets[j].x - t.x[0], dy = dets[j].y - t.x[1];
                if (dx * dx + dy * dy > S_.gate_max_px * S_.gate_max_px)
                    continue;
                double nis = dx * dx / sx + dy * dy / sy;
                if (nis <= S_.gate_chi2)
                    c.push_back({nis, i, j});
            }
        }
        std::sort(c.begin(), c.end(), [](const Cand &a, const Cand &b) {
            return a.nis < b.nis || (a.nis == b.nis && (a.t < b.t || (a.t == b.t && a.d < b.d)));
        });
        for (const Cand &k : c) {
            if (assoc[k.t] >= 0 || taken[k.d])
                continue;
            assoc[k.t] = static_cast<int>(k.d);
            taken[k.d] = 1;
        }
    }
    // update
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
        Track &t = tracks_[i];
        if (assoc[i] < 0) {
            ++t.misses;
            continue;
        }
        const Detection &d = dets[static_cast<std::size_t>(assoc[i])];
        const double z[2] = {d.x, d.y};
        for (int a = 0; a < 2; ++a) {
            double *P = t.P[a];
            double s = P[0] + r2, kp = P[0] / s, kv = P[1] / s, inn = z[a] - t.x[a];
            t.x[a] += kp * inn;
            t.x[2 + a] += kv * inn;
            double pp = (1 - kp) * P[0], pv = (1 - kp) * P[1], vv = P[2] - kv * P[1];
            P[0] = pp;
            P[1] = pv;
            P[2] = vv;
        }
        t.hits |= 1u;
        t.misses = 0;
        t.peak = d.peak;
    }
    // confirmation, ends
    const uint32_t window = S_.n >= 32 ? 0xFFFFFFFFu : ((1u << S_.n) - 1u);
    std::vector<Track> keep;
    keep.reserve(tracks_.size() + dets.size());
    for (Track &t : tracks_) {
        if (!t.confirmed) {
            int hits = static_cast<int>(std::bitset<32>(t.hits & window).count());
            if (hits >= S_.m) {
                t.confirmed = true;
                t.id = next_id_++;
                t.first_frame = frame;
                out.events.push_back({PFT_TBD_EV_CONFIRMED, t.id, frame, t.x[0], t.x[1]});
            } else if (t.age >= S_.n) {
                continue;  // m of its first n frames can no longer be reached
            }
        } else if (t.misses >= S_.max_misses) {
            out.events.push_back({PFT_TBD_EV_ENDED, t.id, frame, t.x[0], t.x[1]});
            continue;
        }
        keep.push_back(t);
    }
    // new tentative tracks from the detections no track took
    for (std::size_t j = 0; j < dets.size(); ++j) {
        if (taken[j])
            continue;
        Track t{};
        t.x[0] = dets[j].x;
        t.x[1] = dets[j].y;
        t.x[2] = t.x[3] = 0;
        for (int a = 0; a < 2; ++a) {
            t.P[a][0] = r2;
            t.P[a][1] = 0;
            t.P[a][2] = S_.vel_sigma0 * S_.vel_sigma0;
        }
        t.hits = 1u;
        t.age = 1;
        t.peak = dets[j].peak;
        if (S_.m <= 1) {
            t.confirmed = true;
            t.id = next_id_++;
            t.first_frame = frame;
            out.events.push_back({PFT_TBD_EV_CONFIRMED, t.id, frame, t.x[0], t.x[1]});
        }
        keep.push_back(t);
    }
    tracks_.swap(keep);
    for (const Track &t : tracks_)
        if (t.confirmed) {
            tbd::TrackOut o;
            o.id = t.id;
            o.x = t.x[0];
            o.y = t.x[1];
            o.vx = t.x[2];
            o.vy = t.x[3];
            o.intensity = t.peak;
            o.p_exist = 1.0;
            o.first_frame = t.first_frame;
            out.tracks.push_back(o);
        }
    return out;
}

}  // namespace pft::host::tbd_ir
