#include "tsa_trackers.hpp"

#include <cmath>

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


PftParams parse_pft_params(const nlohmann::json &j, const std::string &file, const std::string &path)
{
    PftParams p;
    Field f(j, file, path);
    f.only({"motion", "particles", "beta0", "q", "pos_sd", "rho_min", "lik_lambda", "theta_u", "update_rho_min", "fit_k",
            "fit_sigma", "fit_a_max", "fit_v_max", "snake_points", "init_passes", "max_target", "seed"});
    p.motion = f.choice_or("motion", p.motion, {"tsa", "ts", "ncv"});
    p.particles = (int)f.integer_in("particles", p.particles, 1, 65535);
    p.beta0 = f.number_in("beta0", p.beta0, 0, 64);
    p.q = f.number_in("q", p.q, 0, 10000);
    p.pos_sd = f.number_in("pos_sd", p.pos_sd, 0, 1000);
    p.rho_min = f.number_in("rho_min", p.rho_min, 0, 1);
    p.lik_lambda = f.number_in("lik_lambda", p.lik_lambda, 0, 1000);
    p.theta_u = f.number_in("theta_u", p.theta_u, 0, 1);
    p.update_rho_min = f.number_in("update_rho_min", p.update_rho_min, 0, 1);
    p.fit_k = (int)f.integer_in("fit_k", p.fit_k, 1, PFT_TSA_MOTION_MAX_K);
    p.fit_sigma = f.number_in("fit_sigma", p.fit_sigma, 0.1, 100);
    p.fit_a_max = f.number_in("fit_a_max", p.fit_a_max, 0, 1000);
    p.fit_v_max = f.number_in("fit_v_max", p.fit_v_max, 0, 1000);
    p.snake_points = (int)f.integer_in("snake_points", p.snake_points, PFT_TSA_MIN_POINTS, PFT_TSA_MAX_POINTS);
    p.init_passes = (int)f.integer_in("init_passes", p.init_passes, 0, 255);
    p.max_target = (int)f.integer_in("max_target", p.max_target, 8, PFT_TSA_MAX_SIDE);
    p.seed = (uint64_t)f.integer_in("seed", (int64_t)p.seed, 0, INT64_MAX);
    return p;
}

nlohmann::json pft_params_json(const PftParams &p)
{
    return {{"motion", p.motion}, {"particles", p.particles}, {"beta0", p.beta0}, {"q", p.q}, {"pos_sd", p.pos_sd},
            {"rho_min", p.rho_min}, {"lik_lambda", p.lik_lambda}, {"theta_u", p.theta_u}, {"update_rho_min", p.update_rho_min},
            {"fit_k", p.fit_k}, {"fit_sigma", p.fit_sigma}, {"fit_a_max", p.fit_a_max}, {"fit_v_max", p.fit_v_max}, {"snake_points", p.snake_points},
            {"init_passes", p.init_passes}, {"max_target", p.max_target}, {"seed", p.seed}};
}

namespace {

class PftTracker : public Tracker {
public:
    PftTracker(std::string label, const PftParams &p, int w, int h) : label_(std::move(label)), p_(p)
    {
        pft_tsa_config_default(&cfg_);
        cfg_.width = (uint16_t)w;
        cfg_.height = (uint16_t)h;
        cfg_.max_target_w = (uint16_t)p.max_target;
        cfg_.max_target_h = (uint16_t)p.max_target;
        pft_tsa_snake_params_default(&cfg_.snake, cfg_.max_target_w, cfg_.max_target_h);
        cfg_.n_particles = (uint32_t)p.particles;
        cfg_.motion = p.motion == "tsa" ? PFT_TSA_MOTION_TSA : (p.motion == "ts" ? PFT_TSA_MOTION_TS : PFT_TSA_MOTION_NCV);
        cfg_.beta0 = to_real(p.beta0);
        cfg_.q = to_real(p.q);
        cfg_.pos_sd = to_real(p.pos_sd);
        cfg_.rho_min = to_real(p.rho_min);
        cfg_.lik_lambda = to_real(p.lik_lambda);
        cfg_.theta_u = to_real(p.theta_u);
        cfg_.update_rho_min = to_real(p.update_rho_min);
        cfg_.fit_k = (uint8_t)p.fit_k;
        cfg_.fit_sigma = to_real(p.fit_sigma);
        cfg_.fit_a_max = to_real(p.fit_a_max);
        cfg_.fit_v_max = to_real(p.fit_v_max);
        cfg_.snake_points = (uint8_t)p.snake_points;
        cfg_.init_passes = (uint8_t)p.init_passes;
        cfg_.seed = p.seed;
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
        cv::Rect br = cv::boundingRect(poly);
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
        off_ = cv::Point2d(from_real(e.x) - (br.x + (br.width - 1) / 2.0), from_real(e.y) - (br.y + (br.height - 1) / 2.0));
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
        out.box = cv::Rect2d(e.box_x0, e.box_y0, e.box_x1 - e.box_x0 + 1, e.box_y1 - e.box_y0 + 1);
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
        cv::Rect r = cv::boundingRect(poly);
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
        out.center = cv::Point2d(last_.x + (last_.width - 1) / 2.0, last_.y + (last_.height - 1) / 2.0);
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

std::unique_ptr<Tracker> make_tracker(const std::string &name, const PftParams &base, int width, int height)
{
    PftParams p = base;
    if (name == "tsa") {
        p.motion = "tsa";
    } else if (name == "ts") {
        p.motion = "ts";
        p.beta0 = 2.0;
    } else if (name == "ncv" || name == "ncv100") {
        p.motion = "ncv";
        p.particles = 100;
    } else if (name == "ncv200") {
        p.motion = "ncv";
        p.particles = 200;
    } else {
        auto t = make_cv_tracker(name);
        if (!t)
            throw InputError("tracker \"" + name + "\": unknown, or OpenCV's contrib tracking module is not available "
                             "(known: tsa, ts, ncv, ncv200, kcf, csrt, mosse, mil)");
        return t;
    }
    return make_pft_tracker(name, p, width, height);
}

}  // namespace pft::host::tsa
