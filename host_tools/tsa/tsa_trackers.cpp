#include "tsa_trackers.hpp"

#include <cmath>
#include <cstdlib>
#include <functional>

#include <opencv2/imgproc.hpp>
#ifdef PFT_HAVE_CV_TRACKING
#include <opencv2/tracking.hpp>
#include <opencv2/tracking/tracking_legacy.hpp>
#include <opencv2/video/tracking.hpp>
#endif

extern "C" {
#include "pft/pft_tsa.h"
}

#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "../common/real.hpp"

namespace pft::host::tsa {


namespace {

// One field of pft_tsa_config_t the host can set by name.
struct ParamDef {
    const char *name;
    char type;  // 'r' real, 'i' integer, 'b' bool
    double lo, hi;
    std::function<void(pft_tsa_config_t &, double)> set;
    std::function<double(const pft_tsa_config_t &)> get;
};

#define PFT_REAL_PARAM(f, lo, hi)                                                                  \
    ParamDef{#f, 'r', lo, hi, [](pft_tsa_config_t &c, double v) { c.f = to_real(v); },             \
             [](const pft_tsa_config_t &c) { return from_real(c.f); }}
#define PFT_INT_PARAM(f, T, lo, hi)                                                                \
    ParamDef{#f, 'i', lo, hi, [](pft_tsa_config_t &c, double v) { c.f = (T)v; },                   \
             [](const pft_tsa_config_t &c) { return (double)c.f; }}
#define PFT_BOOL_PARAM(f)                                                                          \
    ParamDef{#f, 'b', 0, 1, [](pft_tsa_config_t &c, double v) { c.f = v != 0; },                   \
             [](const pft_tsa_config_t &c) { return c.f ? 1.0 : 0.0; }}

const std::vector<ParamDef> &param_defs()
{
    static const std::vector<ParamDef> defs = {
        PFT_REAL_PARAM(beta0, 0, 64),
        PFT_REAL_PARAM(beta_max, 0.001, 64),
        PFT_REAL_PARAM(q, 0, 10000),
        PFT_REAL_PARAM(pos_sd, 0, 1000),
        PFT_REAL_PARAM(spread_gain, 0, 100),
        PFT_REAL_PARAM(spread_max, 0, 1000),
        PFT_INT_PARAM(fit_k, uint8_t, 1, PFT_TSA_MOTION_MAX_K),
        PFT_REAL_PARAM(fit_sigma, 0.01, 100),
        PFT_BOOL_PARAM(fit_rho_weights),
        PFT_REAL_PARAM(fit_a_max, 0, 1000),
        PFT_REAL_PARAM(fit_v_max, 0, 1000),
        PFT_REAL_PARAM(rho_min, 0, 1),
        PFT_REAL_PARAM(lik_lambda, 0, 1000),
        PFT_REAL_PARAM(theta_u, 0, 1),
        PFT_REAL_PARAM(update_rho_min, 0, 1),
        PFT_REAL_PARAM(anchor_rho_min, 0, 1),
        PFT_REAL_PARAM(k_s, 0.01, 100),
        PFT_INT_PARAM(update_max_passes, uint8_t, 0, 255),
        PFT_INT_PARAM(init_passes, uint8_t, 0, 255),
        PFT_INT_PARAM(snake_points, uint8_t, PFT_TSA_MIN_POINTS, PFT_TSA_MAX_POINTS),
        PFT_REAL_PARAM(kernel_c, 0, 1000),
        PFT_REAL_PARAM(max_area_change, 1, 1000),
        PFT_INT_PARAM(lost_frames, uint16_t, 0, 65535),
        PFT_BOOL_PARAM(loss_search),
        PFT_BOOL_PARAM(gain_select),
        PFT_REAL_PARAM(rho_acquire, 0, 1),
        PFT_REAL_PARAM(bg_ring, 0, 8),
        PFT_REAL_PARAM(bg_alpha, 0.0001, 1),
        PFT_INT_PARAM(acquire_on, uint8_t, 0, 2),
        PFT_REAL_PARAM(search_growth, 0, 4096),
        PFT_REAL_PARAM(reacq_radius, 0, 4096),
        PFT_INT_PARAM(map_margin, uint16_t, 0, 4096),
    };
    return defs;
}

const ParamDef *find_param(const std::string &name)
{
    for (const auto &d : param_defs())
        if (name == d.name)
            return &d;
    return nullptr;
}

std::string known_params()
{
    std::string k = "motion, particles, max_target, seed";
    for (const auto &d : param_defs())
        k += std::string(", ") + d.name;
    return k;
}

}  // namespace

std::vector<std::string> tracker_param_names()
{
    std::vector<std::string> v = {"motion", "particles", "max_target", "seed"};
    for (const auto &d : param_defs())
        v.push_back(d.name);
    return v;
}

PftParams parse_pft_params(const nlohmann::json &j, const std::string &file, const std::string &path)
{
    PftParams p;
    Field f(j, file, path);
    if (!f.is_object())
        f.fail("expected an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string &k = it.key();
        if (k == "motion" || k == "particles" || k == "max_target" || k == "seed")
            continue;
        const ParamDef *d = find_param(k);
        if (!d)
            f.at(k).fail("unknown tracker parameter (known: " + known_params() + ")");
        if (d->type == 'b')
            p.set[k] = f.at(k).as_bool() ? 1.0 : 0.0;
        else if (d->type == 'i')
            p.set[k] = (double)f.integer_in(k, 0, (int64_t)d->lo, (int64_t)d->hi);
        else
            p.set[k] = f.number_in(k, 0, d->lo, d->hi);
    }
    p.motion = f.choice_or("motion", p.motion, {"tsa", "ts", "ncv"});
    p.particles = (int)f.integer_in("particles", p.particles, 1, 65535);
    p.max_target = (int)f.integer_in("max_target", p.max_target, 8, PFT_TSA_MAX_SIDE);
    p.seed = (uint64_t)f.integer_in("seed", (int64_t)p.seed, 0, INT64_MAX);
    return p;
}

void set_pft_param(PftParams &p, const std::string &assignment, const std::string &what)
{
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(what + ": expected name=value, got \"" + assignment + "\"");
    const std::string k = assignment.substr(0, eq), v = assignment.substr(eq + 1);
    auto number = [&](double lo, double hi) {
        char *end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0' || !std::isfinite(x) || x < lo || x > hi)
            throw InputError(what + ": " + k + " must be a number in [" + std::to_string(lo) + ", " +
                             std::to_string(hi) + "], got \"" + v + "\"");
        return x;
    };
    if (k == "motion") {
        if (v != "tsa" && v != "ts" && v != "ncv")
            throw InputError(what + ": motion must be tsa, ts or ncv, got \"" + v + "\"");
        p.motion = v;
    } else if (k == "particles") {
        p.particles = (int)number(1, 65535);
    } else if (k == "max_target") {
        p.max_target = (int)number(8, PFT_TSA_MAX_SIDE);
    } else if (k == "seed") {
        p.seed = (uint64_t)number(0, 9.0e15);
    } else if (const ParamDef *d = find_param(k)) {
        if (d->type == 'b') {
            if (v == "true" || v == "1")
                p.set[k] = 1;
            else if (v == "false" || v == "0")
                p.set[k] = 0;
            else
                throw InputError(what + ": " + k + " must be true or false, got \"" + v + "\"");
        } else {
            const double x = number(d->lo, d->hi);
            if (d->type == 'i' && x != std::floor(x))
                throw InputError(what + ": " + k + " must be an integer, got \"" + v + "\"");
            p.set[k] = x;
        }
    } else {
        throw InputError(what + ": unknown tracker parameter \"" + k + "\" (known: " + known_params() + ")");
    }
}

cv::Rect2d polygon_extent(const std::vector<cv::Point> &poly)
{
    // cv::boundingRect counts pixels inclusively (x1 - x0 + 1); a polygon through pixel centres
    // x0 .. x1 covers the extent [x0, x1] and, rasterised half-open, the pixels x0 .. x1 - 1
    const cv::Rect br = cv::boundingRect(poly);
    return cv::Rect2d(br.x, br.y, br.width - 1, br.height - 1);
}

namespace {

pft_tsa_config_t make_config(const PftParams &p, int w, int h)
{
    pft_tsa_config_t c;
    pft_tsa_config_default(&c);
    c.width = (uint16_t)w;
    c.height = (uint16_t)h;
    c.max_target_w = (uint16_t)p.max_target;
    c.max_target_h = (uint16_t)p.max_target;
    pft_tsa_snake_params_default(&c.snake, c.max_target_w, c.max_target_h);
    c.n_particles = (uint32_t)p.particles;
    c.motion = p.motion == "tsa" ? PFT_TSA_MOTION_TSA : (p.motion == "ts" ? PFT_TSA_MOTION_TS : PFT_TSA_MOTION_NCV);
    c.seed = p.seed;
    for (const auto &kv : p.set)
        find_param(kv.first)->set(c, kv.second);
    return c;
}

}  // namespace

nlohmann::json pft_params_json(const PftParams &p)
{
    const pft_tsa_config_t c = make_config(p, 640, 480);
    nlohmann::json j = {{"motion", p.motion}, {"particles", p.particles}, {"max_target", p.max_target},
                        {"seed", p.seed}};
    for (const auto &d : param_defs()) {
        const double v = d.get(c);
        if (d.type == 'b')
            j[d.name] = v != 0;
        else if (d.type == 'i')
            j[d.name] = (int64_t)v;
        else
            j[d.name] = std::round(v * 1e6) / 1e6;
    }
    return j;
}

namespace {

class PftTracker : public Tracker {
public:
    PftTracker(std::string label, const PftParams &p, int w, int h) : label_(std::move(label)), p_(p)
    {
        cfg_ = make_config(p, w, h);
        const char *field = nullptr;
        if (pft_tsa_config_check(&cfg_, &field) != PFT_OK)
            throw InputError("tracker " + label_ + ": invalid pftrack configuration (" +
                             (field ? field : "?") + ")");
        work_.resize(pft_tsa_workspace_size(&cfg_));
        pft_status_t st = pft_tsa_init(&t_, &cfg_, work_.data(), work_.size());
        if (st != PFT_OK)
            throw InputError("tracker " + label_ + ": pft_tsa_init: " + pft_status_str(st));
    }
    std::string name() const override { return label_; }
    std::size_t memory_bytes() const override { return work_.size() + sizeof t_; }

    static pft_frame_t wrap(const cv::Mat &bgr)
    {
        pft_frame_t f{};
        f.data = bgr.data;
        f.width = (uint16_t)bgr.cols;
        f.height = (uint16_t)bgr.rows;
        f.stride_bytes = (uint32_t)bgr.step;
        f.format = bgr.channels() == 3 ? PFT_PIX_BGR888 : PFT_PIX_U8;
        return f;
    }

    void init(const cv::Mat &bgr, const std::vector<cv::Point> &poly) override
    {
        std::vector<pft_tsa_pt_t> pp;
        const cv::Rect2d br = polygon_extent(poly);
        for (auto &q : poly)
            pp.push_back({(int16_t)q.x, (int16_t)q.y});
        pft_frame_t f = wrap(bgr);
        pft_status_t st = pft_tsa_start(&t_, &f, pp.data(), (uint32_t)pp.size());
        if (st != PFT_OK)
            throw InputError("tracker " + label_ + ": pft_tsa_start: " + pft_status_str(st));
        pft_tsa_estimate_t e;
        pft_tsa_estimate(&t_, &e);
        // the kernel origin is the contour's area centroid: report centres relative to the
        // initial box centre so they compare with box-centre ground truth
        off_ = cv::Point2d(from_real(e.x) - (br.x + br.width / 2.0), from_real(e.y) - (br.y + br.height / 2.0));
    }

    void update(const cv::Mat &bgr, TrackOut &out) override
    {
        pft_frame_t f = wrap(bgr);
        pft_status_t st = pft_tsa_update(&t_, &f);
        if (st != PFT_OK)
            throw InputError("tracker " + label_ + ": pft_tsa_update: " + pft_status_str(st));
        fill(out);
    }

    void fill(TrackOut &out) const
    {
        pft_tsa_estimate_t e;
        pft_tsa_estimate(&t_, &e);
        out.center = cv::Point2d(from_real(e.x), from_real(e.y)) - off_;
        // the contour's extent (a box given as x, y, w, h comes back as w x h)
        out.box = cv::Rect2d(e.box_x0, e.box_y0, e.box_x1 - e.box_x0, e.box_y1 - e.box_y0);
        out.ok = e.state == PFT_TSA_TRACKING || e.state == PFT_TSA_PIONEER_ONLY;
        out.beta = from_real(e.beta);
        out.rho = from_real(e.rho);
        out.rho_pioneer = from_real(e.rho_pioneer);
        out.state = (int)e.state;
        out.alive = (int)e.n_alive;
        out.template_updated = e.template_updated;
        out.pioneer = cv::Point2d(from_real(e.pioneer_x), from_real(e.pioneer_y));
        pft_tsa_pt_t c[PFT_TSA_MAX_POINTS];
        const std::size_t n = pft_tsa_contour(&t_, c, PFT_TSA_MAX_POINTS);
        out.contour.clear();
        for (std::size_t i = 0; i < n; ++i)
            out.contour.emplace_back(c[i].x, c[i].y);
        std::vector<pft_tsa_particle_t> parts(pft_tsa_particles(&t_, nullptr, 0));
        const std::size_t m = pft_tsa_particles(&t_, parts.data(), parts.size());
        out.particles.clear();
        for (std::size_t i = 0; i < m && i < parts.size(); ++i)
            out.particles.emplace_back((float)from_real(parts[i].x), (float)from_real(parts[i].y));
    }

private:
    std::string label_;
    PftParams p_;
    pft_tsa_config_t cfg_{};
    pft_tsa_t t_{};
    std::vector<uint8_t> work_;
    cv::Point2d off_;
};

#ifdef PFT_HAVE_CV_TRACKING
class CvTracker : public Tracker {
public:
    explicit CvTracker(std::string n) : name_(std::move(n)) {}
    std::string name() const override { return name_; }
    void init(const cv::Mat &bgr, const std::vector<cv::Point> &poly) override
    {
        const cv::Rect2d ext = polygon_extent(poly);
        const cv::Rect r((int)ext.x, (int)ext.y, (int)ext.width, (int)ext.height);
        if (name_ == "mosse") {
            legacy_ = cv::legacy::TrackerMOSSE::create();
            legacy_->init(bgr, cv::Rect2d(r));
        } else {
            if (name_ == "kcf")
                t_ = cv::TrackerKCF::create();
            else if (name_ == "csrt")
                t_ = cv::TrackerCSRT::create();
            else
                t_ = cv::TrackerMIL::create();
            t_->init(bgr, r);
        }
        last_ = cv::Rect2d(r);
    }
    void update(const cv::Mat &bgr, TrackOut &out) override
    {
        bool ok;
        if (legacy_) {
            cv::Rect2d r = last_;
            ok = legacy_->update(bgr, r);
            if (ok)
                last_ = r;
        } else {
            cv::Rect r;
            ok = t_->update(bgr, r);
            if (ok)
                last_ = cv::Rect2d(r);
        }
        out.ok = ok;
        out.box = last_;
        out.center = cv::Point2d(last_.x + last_.width / 2.0, last_.y + last_.height / 2.0);
    }

private:
    std::string name_;
    cv::Ptr<cv::Tracker> t_;
    cv::Ptr<cv::legacy::Tracker> legacy_;
    cv::Rect2d last_;
};
#endif

}  // namespace

bool have_cv_tracking()
{
#ifdef PFT_HAVE_CV_TRACKING
    return true;
#else
    return false;
#endif
}

std::unique_ptr<Tracker> make_pft_tracker(const std::string &label, const PftParams &p, int width, int height)
{
    return std::make_unique<PftTracker>(label, p, width, height);
}

std::unique_ptr<Tracker> make_cv_tracker(const std::string &name)
{
#ifdef PFT_HAVE_CV_TRACKING
    if (name == "kcf" || name == "csrt" || name == "mosse" || name == "mil")
        return std::make_unique<CvTracker>(name);
#else
    (void)name;
#endif
    return nullptr;
}

std::unique_ptr<Tracker> make_tracker(const std::string &label, const PftParams &base, int width, int height)
{
    PftParams p = base;
    // "NAME+field=value+...": the pftrack tracker NAME with those fields of pft_tsa_config_t set
    // on top of its own (a variant evaluated on the same frames as NAME)
    const std::string name = label.substr(0, label.find('+'));
    std::map<std::string, double> over;
    for (std::size_t at = label.find('+'); at != std::string::npos;) {
        const std::size_t next = label.find('+', at + 1);
        const std::string kv = label.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
        const std::size_t eq = kv.find('=');
        const ParamDef *d = eq == std::string::npos ? nullptr : find_param(kv.substr(0, eq));
        if (!d)
            throw InputError("tracker \"" + label + "\": expected NAME+field=value (fields: " + known_params() + ")");
        char *end = nullptr;
        const std::string vs = kv.substr(eq + 1);
        const double v = std::strtod(vs.c_str(), &end);
        if (vs.empty() || *end != '\0' || !(v >= d->lo && v <= d->hi))
            throw InputError("tracker \"" + label + "\": " + d->name + " out of range or not a number");
        at = next;
        over[d->name] = v;
    }
    if (name == "tsa") {
        p.motion = "tsa";
    } else if (name == "ts") {
        p.motion = "ts";
        p.set["beta0"] = 2.0;
    } else if (name == "ncv" || name == "ncv100") {
        p.motion = "ncv";
        p.particles = 100;
    } else if (name == "ncv200") {
        p.motion = "ncv";
        p.particles = 200;
    } else if (name == "tsa_paper") {
        p.motion = "tsa";
        p.set["lik_lambda"] = 0;
        p.set["fit_a_max"] = 0;
        p.set["fit_v_max"] = 0;
        p.set["fit_k"] = 10;
        p.set["fit_sigma"] = 5;
        p.set["pos_sd"] = 2;
        p.set["spread_gain"] = 0;
        p.set["theta_u"] = 0.9;
        p.set["loss_search"] = 0;
        p.set["gain_select"] = 0;
        p.set["init_passes"] = 50;
        p.set["bg_ring"] = 0;
    } else {
        auto t = name == label ? make_cv_tracker(name) : nullptr;
        if (!t)
            throw InputError("tracker \"" + name + "\": unknown, or OpenCV's contrib tracking module is not available "
                             "(known: tsa, ts, ncv, ncv200, tsa_paper, kcf, csrt, mosse, mil)");
        return t;
    }
    for (const auto &kv : over)  // on top of the named tracker's own settings
        p.set[kv.first] = kv.second;
    return make_pft_tracker(label, p, width, height);
}

}  // namespace pft::host::tsa
