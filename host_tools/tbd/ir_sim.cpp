#include "ir_sim.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/progress.hpp"
#include "ir_scene.hpp"

namespace pft::host::tbd_ir {

namespace {

const double kPi = 3.14159265358979323846;
const int kInterpMargin = 3;  // bicubic support plus one

bool inside(double x, double y, int w, int h)
{
    return x >= -0.5 && x <= w - 0.5 && y >= -0.5 && y <= h - 0.5;
}

/** Positions from birth on, heading th (rad), speed v, turn om (rad/frame), until the target
 *  leaves the frame, the end, or `last` (0: none). */
TargetPath walk(int id, int birth, int last, double x, double y, double th, double v, double om,
                int frames, int w, int h)
{
    TargetPath p;
    p.id = id;
    p.birth = birth;
    int end = last ? std::min(last, frames) : frames;
    for (int k = birth; k <= end; ++k) {
        if (!inside(x, y, w, h))
            break;
        p.x.push_back(x);
        p.y.push_back(y);
        x += v * std::cos(th);
        y += v * std::sin(th);
        th += om;
    }
    p.death = birth + static_cast<int>(p.x.size()) - 1;
    return p;
}

struct Draw {
    std::mt19937_64 g;
    Draw(uint64_t seed, uint64_t stream)
    {
        std::seed_seq sq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                         static_cast<uint32_t>(stream)};
        g.seed(sq);
    }
    double u(double a, double b) { return a + (b - a) * std::uniform_real_distribution<double>(0.0, 1.0)(g); }
    int i(int a, int b) { return b <= a ? a : std::uniform_int_distribution<int>(a, b)(g); }
    double n() { return std::normal_distribution<double>(0.0, 1.0)(g); }
};

TargetPath random_target(const IrScenario &s, Draw &d, int id, int w, int h)
{
    const Targets &T = s.targets;
    const int F = s.frames;
    TargetPath best;
    for (int tries = 0; tries < 200; ++tries) {
        double v = d.u(T.speed_px[0], T.speed_px[1]);
        double om = d.u(-T.turn_deg, T.turn_deg) * kPi / 180.0;
        double snr = d.u(T.snr_db[0], T.snr_db[1]);
        int birth = d.i(1, std::max(1, F - T.min_life + 1));
        double x, y, th;
        if (d.u(0, 1) < T.enter_fraction) {
            // on a border, heading inwards within 60 degrees of the normal
            double per = 2.0 * (w + h), a = d.u(0, per), jit = d.u(-kPi / 3, kPi / 3);
            if (a < w) {
                x = a - 0.5; y = -0.5; th = kPi / 2;
            } else if (a < 2.0 * w) {
                x = a - w - 0.5; y = h - 0.5; th = -kPi / 2;
            } else if (a < 2.0 * w + h) {
                x = -0.5; y = a - 2.0 * w - 0.5; th = 0;
            } else {
                x = w - 0.5; y = a - 2.0 * w - h - 0.5; th = kPi;
            }
            th += jit;
        } else {
            x = d.u(8, w - 9);
            y = d.u(8, h - 9);
            th = d.u(0, 2 * kPi);
        }
        TargetPath p = walk(id, birth, 0, x, y, th, v, om, F, w, h);
        p.snr_db = snr;
        if (p.death - p.birth + 1 >= std::min(T.min_life, F - birth + 1) && !p.x.empty())
            return p;
        if (p.x.size() > best.x.size())
            best = p;
    }
    return best;
}

/** Two targets through one point at one frame, at 45..135 degrees to each other. */
std::array<TargetPath, 2> crossing_pair(const IrScenario &s, Draw &d, int id, int w, int h)
{
    const Targets &T = s.targets;
    const int F = s.frames;
    std::array<TargetPath, 2> best{};
    for (int tries = 0; tries < 200; ++tries) {
        int kc = d.i(std::max(1, F / 4), std::max(1, 3 * F / 4));
        double px = d.u(w / 4.0, 3.0 * w / 4.0), py = d.u(h / 4.0, 3.0 * h / 4.0);
        double th0 = d.u(0, 2 * kPi), dth = d.u(kPi / 4, 3 * kPi / 4) * (d.u(0, 1) < 0.5 ? -1 : 1);
        int half = d.i(std::max(1, T.min_life / 2 + 1), std::max(T.min_life / 2 + 1, F / 3));
        std::array<TargetPath, 2> pr{};
        bool ok = true;
        for (int j = 0; j < 2; ++j) {
            double th = th0 + j * dth, v = std::max(0.2, d.u(T.speed_px[0], T.speed_px[1]));
            // back from the crossing point to where the life starts (in the frame)
            int b = std::max(1, kc - half);
            while (b < kc && !inside(px + v * (b - kc) * std::cos(th), py + v * (b - kc) * std::sin(th), w, h))
                ++b;
            pr[j] = walk(id + j, b, kc + half, px + v * (b - kc) * std::cos(th),
                         py + v * (b - kc) * std::sin(th), th, v, 0.0, F, w, h);
            pr[j].snr_db = d.u(T.snr_db[0], T.snr_db[1]);
            ok = ok && pr[j].death >= kc && pr[j].death - pr[j].birth + 1 >= std::min(T.min_life, F);
        }
        if (ok)
            return pr;
        best = pr;
    }
    return best;
}

/** Cubic B-spline coefficients of img (CV_32F), computed in double: the causal and anticausal
 *  recursions of the pole sqrt(3) - 2 along rows, then columns, mirror-symmetric ends. */
cv::Mat bspline_coefficients(const cv::Mat &img)
{
    const double z = std::sqrt(3.0) - 2.0;
    cv::Mat c;
    img.convertTo(c, CV_64F);
    std::vector<double> v;
    auto filt = [&]() {
        const int n = static_cast<int>(v.size());
        if (n < 2)
            return;
        double sum = 0.0, zk = 1.0;  // causal start for mirror-symmetric ends: sum of z^k v[k], |z|^40 < 1e-22
        for (int k = 0; k < std::min(n, 40); ++k) {
            sum += zk * v[static_cast<std::size_t>(k)];
            zk *= z;
        }
        v[0] = sum;
        for (int k = 1; k < n; ++k)
            v[static_cast<std::size_t>(k)] += z * v[static_cast<std::size_t>(k - 1)];
        v[static_cast<std::size_t>(n - 1)] =
            z / (z * z - 1.0) * (v[static_cast<std::size_t>(n - 1)] + z * v[static_cast<std::size_t>(n - 2)]);
        for (int k = n - 2; k >= 0; --k)
            v[static_cast<std::size_t>(k)] = z * (v[static_cast<std::size_t>(k + 1)] - v[static_cast<std::size_t>(k)]);
        for (double &x : v)
            x *= 6.0;
    };
    for (int r = 0; r < c.rows; ++r) {
        v.assign(c.ptr<double>(r), c.ptr<double>(r) + c.cols);
        filt();
        std::copy(v.begin(), v.end(), c.ptr<double>(r));
    }
    v.resize(static_cast<std::size_t>(c.rows));
    for (int col = 0; col < c.cols; ++col) {
        for (int r = 0; r < c.rows; ++r)
            v[static_cast<std::size_t>(r)] = c.at<double>(r, col);
        filt();
        for (int r = 0; r < c.rows; ++r)
            c.at<double>(r, col) = v[static_cast<std::size_t>(r)];
    }
    return c;
}

/** The four weights of taps -1, 0, 1, 2 at fraction t in [0, 1). */
void cubic_weights(double t, bool bspline, double w[4])
{
    if (bspline) {
        const double u = 1.0 - t;
        w[0] = u * u * u / 6.0;
        w[1] = (4.0 - 6.0 * t * t + 3.0 * t * t * t) / 6.0;
        w[2] = (1.0 + 3.0 * t + 3.0 * t * t - 3.0 * t * t * t) / 6.0;
        w[3] = t * t * t / 6.0;
        return;
    }
    // Catmull-Rom (Keys a = -0.5)
    w[0] = ((-0.5 * t + 1.0) * t - 0.5) * t;
    w[1] = (1.5 * t - 2.5) * t * t + 1.0;
    w[2] = ((-1.5 * t + 2.0) * t + 0.5) * t;
    w[3] = (0.5 * t - 0.5) * t * t;
}

/** dst(r, c) = the scene at (c + px, r + py), exact position; src: the scene (CV_32F) or its
 *  B-spline coefficients (CV_64F) when bspline. Separable: rows first, then columns. */
void translate_exact(const cv::Mat &src, bool bspline, double px, double py, int W, int H, cv::Mat &dst)
{
    const int ix = static_cast<int>(std::floor(px)), iy = static_cast<int>(std::floor(py));
    double wx[4], wy[4];
    cubic_weights(px - ix, bspline, wx);
    cubic_weights(py - iy, bspline, wy);
    std::vector<int> cols(static_cast<std::size_t>(W) + 3);
    for (int c = 0; c < W + 3; ++c)
        cols[static_cast<std::size_t>(c)] = cv::borderInterpolate(ix - 1 + c, src.cols, cv::BORDER_REFLECT_101);
    cv::Mat tmp(H + 3, W, CV_64F);
    for (int r = 0; r < H + 3; ++r) {
        const int sr = cv::borderInterpolate(iy - 1 + r, src.rows, cv::BORDER_REFLECT_101);
        double *tp = tmp.ptr<double>(r);
        for (int c = 0; c < W; ++c) {
            double v = 0.0;
            for (int j = 0; j < 4; ++j) {
                const int sc = cols[static_cast<std::size_t>(c + j)];
                v += wx[j] * (bspline ? src.at<double>(sr, sc) : static_cast<double>(src.at<float>(sr, sc)));
            }
            tp[c] = v;
        }
    }
    dst.create(H, W, CV_32F);
    for (int r = 0; r < H; ++r) {
        float *dp = dst.ptr<float>(r);
        for (int c = 0; c < W; ++c) {
            double v = 0.0;
            for (int i = 0; i < 4; ++i)
                v += wy[i] * tmp.at<double>(r + i, c);
            dp[c] = static_cast<float>(v);
        }
    }
}

}  // namespace

void add_point(cv::Mat &img, double x, double y, double amplitude, double psf_sigma)
{
    int rad = static_cast<int>(std::ceil(4.0 * psf_sigma));
    int c0 = static_cast<int>(std::lround(x)), r0 = static_cast<int>(std::lround(y));
    double k = -1.0 / (2.0 * psf_sigma * psf_sigma);
    for (int r = std::max(0, r0 - rad); r <= std::min(img.rows - 1, r0 + rad); ++r) {
        float *p = img.ptr<float>(r);
        for (int c = std::max(0, c0 - rad); c <= std::min(img.cols - 1, c0 + rad); ++c) {
            double dx = c - x, dy = r - y;
            p[c] += static_cast<float>(amplitude * std::exp(k * (dx * dx + dy * dy)));
        }
    }
}

std::vector<TargetPath> make_targets(const IrScenario &s, int w, int h, uint64_t seed)
{
    Draw d(seed, 1);
    std::vector<TargetPath> v;
    int id = 1;  // random targets after the largest listed id
    for (const TargetSpec &t : s.targets.list)
        id = std::max(id, t.id + 1);
    const int count = d.i(s.targets.count[0], s.targets.count[1]);
    for (int i = 0; i < count; ++i)
        v.push_back(random_target(s, d, id++, w, h));
    for (int i = 0; i < s.targets.crossings; ++i) {
        auto pr = crossing_pair(s, d, id, w, h);
        id += 2;
        v.push_back(pr[0]);
        v.push_back(pr[1]);
    }
    for (const TargetSpec &t : s.targets.list) {
        double v0 = std::hypot(t.vx, t.vy), th = std::atan2(t.vy, t.vx);
        TargetPath p = walk(t.id, t.birth, t.death, t.x, t.y, th, v0, t.turn_deg * kPi / 180.0,
                            s.frames, w, h);
        p.snr_db = t.snr_db;
        v.push_back(p);
    }
    v.erase(std::remove_if(v.begin(), v.end(), [](const TargetPath &p) { return p.x.empty(); }), v.end());
    for (TargetPath &p : v)
        p.amplitude = s.amplitude(p.snr_db);
    return v;
}


IrSequence simulate_ir(const IrScenario &s, uint64_t seed, Progress *bar)
{
    IrSequence q;
    q.frames = s.frames;
    q.bit_depth = s.sensor.bit_depth;
    Draw plat(seed, 2);
    const double dxp = s.platform.drift_px[0], dyp = s.platform.drift_px[1], jit = s.platform.jitter_px;
    const double ex = std::fabs(dxp) * (s.frames - 1) + 8.0 * jit, ey = std::fabs(dyp) * (s.frames - 1) + 8.0 * jit;
    const int need_x = static_cast<int>(std::ceil(ex)) + 2 * kInterpMargin + 1;
    const int need_y = static_cast<int>(std::ceil(ey)) + 2 * kInterpMargin + 1;

    // the scene and the sensor frame in it
    Scene sc;
    if (s.background.source == "procedural") {
        q.width = s.width;
        q.height = s.height;
        int W = q.width + need_x, H = q.height + need_y;
        double y0 = (H - q.height - 1) / 2.0 - (s.frames - 1) * dyp / 2.0;
        sc = procedural_scene(s, W, H, y0, q.height, seed);
    } else {
        std::vector<std::string> files = background_files(s.background);
        std::size_t idx = s.background.index ? static_cast<std::size_t>(*s.background.index)
                                             : static_cast<std::size_t>((seed > 0 ? seed - 1 : 0) % files.size());
        if (idx >= files.size())
            throw InputError(s.file + ": background.index: " + std::to_string(idx) + " but the folder has " +
                             std::to_string(files.size()) + " images");
        sc = image_scene(s, files[idx]);
        q.width = s.size_given ? s.width : (sc.counts.cols - need_x) / 2 * 2;
        q.height = s.size_given ? s.height : (sc.counts.rows - need_y) / 2 * 2;
        if (q.width < 16 || q.height < 16)
            throw InputError(files[idx] + ": the background is too small for " + std::to_string(s.frames) +
                             " frames of this drift (give image.width/height to mirror its borders)");
        int pad = std::max({0, q.width + need_x - sc.counts.cols, q.height + need_y - sc.counts.rows});
        if (pad > 0) {
            pad = (pad + 1) / 2 + 1;
            cv::copyMakeBorder(sc.counts, sc.counts, pad, pad, pad, pad, cv::BORDER_REFLECT_101);
            for (SceneObject &o : sc.objects) {
                o.x += pad;
                o.y += pad;
            }
            sc.mirrored_px = pad;
            std::fprintf(stderr, "pft: warning: %s: background mirrored by %d px at its borders to "
                         "cover the platform's path\n", files[idx].c_str(), pad);
        }
    }
    q.background = sc.source;
    q.mirrored_px = sc.mirrored_px;
    q.labelled_objects = static_cast<int>(sc.objects.size());
    const int W = q.width, H = q.height;

    // platform path, centred in the scene's slack; jitter truncated at 4 sigma
    double p0x = (sc.counts.cols - W - 1) / 2.0 - (s.frames - 1) * dxp / 2.0;
    double p0y = (sc.counts.rows - H - 1) / 2.0 - (s.frames - 1) * dyp / 2.0;
    q.platform.resize(static_cast<std::size_t>(s.frames));
    for (int k = 0; k < s.frames; ++k) {
        double jx = jit > 0 ? std::max(-4.0, std::min(4.0, plat.n())) * jit : 0.0;
        double jy = jit > 0 ? std::max(-4.0, std::min(4.0, plat.n())) * jit : 0.0;
        q.platform[static_cast<std::size_t>(k)] = {p0x + dxp * k + jx, p0y + dyp * k + jy};
    }

    q.targets = make_targets(s, W, H, seed);

    // sensor-fixed patterns: vignetting, column offsets, dead and saturated pixels
    cv::RNG fixed(seed * 0xD1B54A32D192ED03ull + 3);
    cv::RNG noise(seed * 0xA24BAED4963EE407ull + 4);
    cv::Mat vig(H, W, CV_32F);
    double cx = (W - 1) / 2.0, cy = (H - 1) / 2.0, r2max = cx * cx + cy * cy;
    for (int r = 0; r < H; ++r)
        for (int c = 0; c < W; ++c)
            vig.at<float>(r, c) = static_cast<float>(1.0 - s.sensor.vignetting * ((c - cx) * (c - cx) + (r - cy) * (r - cy)) / r2max);
    cv::Mat col(1, W, CV_32F), fpn;
    fixed.fill(col, cv::RNG::NORMAL, 0.0, s.sensor.column_fpn_sigma);
    cv::repeat(col, H, 1, fpn);
    const std::size_t npx = static_cast<std::size_t>(W) * H;
    std::vector<int> dead, sat;
    for (std::size_t i = 0; i < npx; ++i) {
        double u = fixed.uniform(0.0, 1.0);
        if (u < s.sensor.dead_fraction)
            dead.push_back(static_cast<int>(i));
        else if (u < s.sensor.dead_fraction + s.sensor.saturated_fraction)
            sat.push_back(static_cast<int>(i));
    }
    const double fs = s.sensor.full_scale();

    // platform.warp: "opencv" (cv::warpAffine below, every sequence so far) or an exact translation
    const bool exact_warp = s.platform.warp != "opencv", bspline = s.platform.warp == "bspline";
    const cv::Mat coef = bspline ? bspline_coefficients(sc.counts) : cv::Mat();

    cv::Mat bg, nz(H, W, CV_32F);
    q.images.reserve(static_cast<std::size_t>(s.frames));
    for (int k = 1; k <= s.frames; ++k) {
        const auto &p = q.platform[static_cast<std::size_t>(k - 1)];
        cv::Matx23d M(1, 0, p[0], 0, 1, p[1]);
        if (exact_warp)
            translate_exact(bspline ? coef : sc.counts, bspline, p[0], p[1], W, H, bg);
        else
            cv::warpAffine(sc.counts, bg, M, cv::Size(W, H), cv::INTER_CUBIC | cv::WARP_INVERSE_MAP,
                           cv::BORDER_REFLECT_101);
        cv::multiply(bg, vig, bg);
        for (const TargetPath &t : q.targets)
            if (t.present(k))
                add_point(bg, t.x[static_cast<std::size_t>(k - t.birth)], t.y[static_cast<std::size_t>(k - t.birth)],
                          t.amplitude, s.targets.psf_sigma);
        bg += fpn;
        noise.fill(nz, cv::RNG::NORMAL, 0.0, s.sensor.noise_sigma);
        bg += nz;
        cv::Mat u16;
        bg.convertTo(u16, CV_16U);  // rounds, saturates at 0
        cv::min(u16, fs, u16);
        auto *px = reinterpret_cast<uint16_t *>(u16.data);
        for (int i : dead)
            px[i] = 0;
        for (int i : sat)
            px[i] = static_cast<uint16_t>(fs);
        q.images.push_back(u16);

        // truth of this frame: injected targets, then labelled objects moving with the scene
        for (const TargetPath &t : q.targets)
            if (t.present(k))
                q.truth.push_back({k, t.id, t.x[static_cast<std::size_t>(k - t.birth)],
                                   t.y[static_cast<std::size_t>(k - t.birth)], t.snr_db, false});
        for (std::size_t i = 0; i < sc.objects.size(); ++i) {
            const SceneObject &o = sc.objects[i];
            double x = o.x - p[0], y = o.y - p[1];
            if (inside(x, y, W, H))
                q.truth.push_back({k, 1001 + static_cast<int>(i), x, y, o.snr_db, true});
        }
        if (bar)
            bar->tick();
    }
    // the platform relative to the original background image (mirroring undone)
    for (auto &p : q.platform) {
        p[0] -= sc.mirrored_px;
        p[1] -= sc.mirrored_px;
    }
    return q;
}

}  // namespace pft::host::tbd_ir
