// Trackers behind one interface for the "tsa" kind: pftrack's TSA-AK and its NCV / TS
// baselines (lib/include/pft/pft_tsa.h), and OpenCV's KCF, CSRT, MOSSE and MIL.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

namespace pft::host::tsa {

struct TrackOut {
    cv::Rect2d box;                     ///< reported box
    cv::Point2d center;                 ///< reported centre
    bool ok = true;                     ///< the tracker reports success
    // pftrack only
    double beta = NAN, rho = NAN, rho_pioneer = NAN;
    int state = -1, alive = -1;
    bool template_updated = false;
    cv::Point2d pioneer{NAN, NAN};
    std::vector<cv::Point> contour;
    std::vector<cv::Point2f> particles;
};

/** Parameters of a pftrack tracker (the JSON "tracker" object of a scenario). */
struct PftParams {
    std::string motion = "tsa";  ///< tsa | ts | ncv
    int particles = 100;
    double beta0 = 2.0, q = 4.07, pos_sd = 2.0, rho_min = 0.75, theta_u = 0.9, update_rho_min = 0.85;
    double lik_lambda = 300.0;  ///< 0: w = rho (paper eq. 22); > 0: w = exp(lik_lambda (rho - rho_best))
    int fit_k = 10;
    double fit_sigma = 5.0;
    double fit_a_max = 0.5, fit_v_max = 12.0;  ///< bounds on the conservative fit (0: off, the paper)
    int snake_points = 40, init_passes = 50, max_target = 96;
    uint64_t seed = 1;
};
PftParams parse_pft_params(const nlohmann::json &j, const std::string &file, const std::string &path);
nlohmann::json pft_params_json(const PftParams &p);

class Tracker {
public:
    virtual ~Tracker() = default;
    virtual std::string name() const = 0;
    /** Initialise on frame 1 from a polygon (a box is its 4 corners). */
    virtual void init(const cv::Mat &bgr, const std::vector<cv::Point> &poly) = 0;
    virtual void update(const cv::Mat &bgr, TrackOut &out) = 0;
    virtual std::size_t memory_bytes() const { return 0; }
};

/** "tsa", "ts", "ncv", "ncv200" (NCV with 200 particles), or pftrack params explicitly. */
std::unique_ptr<Tracker> make_pft_tracker(const std::string &label, const PftParams &p, int width, int height);
/** "kcf", "csrt", "mosse", "mil"; nullptr when the contrib tracking module was not built in. */
std::unique_ptr<Tracker> make_cv_tracker(const std::string &name);
bool have_cv_tracking();
/** A named tracker of the bench list: tsa, ts, ncv, ncv200, kcf, csrt, mosse, mil. */
std::unique_ptr<Tracker> make_tracker(const std::string &name, const PftParams &base, int width, int height);

}  // namespace pft::host::tsa
