// Trackers behind one interface for the "tsa" kind: pftrack's TSA-AK and its NCV / TS
// baselines (lib/include/pft/pft_tsa.h), and OpenCV's KCF, CSRT, MOSSE and MIL.
#pragma once
#include <map>
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

/** Parameters of a pftrack tracker (the JSON "tracker" object of a scenario, or `pft track`'s
 *  flags): the dynamics, the particle count, the largest target side, the seed, and any field
 *  of pft_tsa_config_t by its name (see tracker_param_names()); a field not given keeps the
 *  library's default (pft_tsa_config_default). */
struct PftParams {
    std::string motion = "tsa";  ///< tsa | ts | ncv
    int particles = 100;
    int max_target = 96;         ///< max_target_w = max_target_h
    uint64_t seed = 1;
    std::map<std::string, double> set;  ///< library fields given explicitly (bools as 0/1)
};
/** Reads the "tracker" object (every member checked: unknown names and out-of-range values are
 *  refused with the file and field). */
PftParams parse_pft_params(const nlohmann::json &j, const std::string &file, const std::string &path);
/** Sets one field by name from text ("lik_lambda=0", "loss_search=false"); InputError naming
 *  `what` on an unknown name or a bad value. */
void set_pft_param(PftParams &p, const std::string &assignment, const std::string &what);
/** Every parameter with its effective value (the library's default where not given). */
nlohmann::json pft_params_json(const PftParams &p);
/** The names set_pft_param accepts. */
std::vector<std::string> tracker_param_names();

class Tracker {
public:
    virtual ~Tracker() = default;
    virtual std::string name() const = 0;
    /** Initialise on frame 1 from a polygon (a box is its 4 corners). */
    virtual void init(const cv::Mat &bgr, const std::vector<cv::Point> &poly) = 0;
    virtual void update(const cv::Mat &bgr, TrackOut &out) = 0;
    virtual std::size_t memory_bytes() const { return 0; }
};

/** The extent of a polygon through pixel centres, [x0, x1] x [y0, y1], as x0, y0, x1 - x0,
 *  y1 - y0: a box x, y, w, h given as its four corners comes back as itself. */
cv::Rect2d polygon_extent(const std::vector<cv::Point> &poly);
/** A pftrack tracker with the given parameters (label: its name in tables). */
std::unique_ptr<Tracker> make_pft_tracker(const std::string &label, const PftParams &p, int width, int height);
/** "kcf", "csrt", "mosse", "mil"; nullptr when the contrib tracking module was not built in. */
std::unique_ptr<Tracker> make_cv_tracker(const std::string &name);
bool have_cv_tracking();
/** A named tracker of the eval / bench lists: tsa, ts, ncv, ncv200 (NCV with 200 particles),
 *  tsa_paper (the paper's variant: w = rho, unbounded fit over K = 10, position diffusion 2 px,
 *  template updates, no loss search, no gain selection, 50 initial snake passes, no background
 *  weighting), kcf, csrt,
 *  mosse, mil; and a variant of a pftrack one, "NAME+field=value+..." (e.g. "tsa+bg_ring=3"):
 *  NAME with those fields of pft_tsa_config_t set on top of its own (label: the whole name). */
std::unique_ptr<Tracker> make_tracker(const std::string &name, const PftParams &base, int width, int height);

}  // namespace pft::host::tsa
