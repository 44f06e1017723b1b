// Multi-target set metrics between a frame's truth points and its estimated points: GOSPA
// (alpha = 2, cut-off c, order p; Rahmathullah, Garcia-Fernandez & Svensson 2017) with its
// localisation, missed and false parts, and OSPA (Schuhmacher, Vo & Vo 2008), both from one
// optimal assignment (a shortest-augmenting-path linear assignment solver, written here).
// Self-contained: no dependency on a tracker or a scenario; a frame is two lists of points.
//
// For truth X (m points), estimate Y (n points), d(x, y) the Euclidean distance:
//   GOSPA^p = min over partial assignments g of  sum_{(i,j) in g} d(x_i, y_j)^p
//                                               + c^p / 2 * (m + n - 2 |g|)
//   OSPA^p  = ( min over injections pi of sum_i min(d, c)(x_i, y_pi(i))^p + c^p |n - m| )
//             / max(m, n),   OSPA = 0 when both sets are empty.
// Both come from the same minimum-cost matching of size min(m, n) on min(d, c)^p; a matched pair
// with d >= c counts as one missed and one false point in GOSPA (its cost c^p is the same).
#pragma once
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace pft::host::metrics {

struct Point {
    double x = 0, y = 0;
};

/** Minimum-cost assignment of a rows x cols cost matrix (row-major, finite entries): every row
 *  gets a distinct column when rows <= cols, every column a distinct row otherwise.
 *  Returns row_to_col (size rows; -1 for a row left out when rows > cols). Shortest augmenting
 *  paths with dual potentials (Jonker-Volgenant family), O(min^2 max). */
std::vector<int> assign_min_cost(const std::vector<double> &cost, std::size_t rows, std::size_t cols,
                                 double *total = nullptr);

/** One frame's GOSPA (alpha = 2) and OSPA, with the parts of GOSPA as p-th powers:
 *  distance^p = localisation + missed + false (the convention of Stone Soup's GOSPAMetric). */
struct FrameMetrics {
    double gospa = 0;         ///< GOSPA distance
    double localisation = 0;  ///< sum of d^p over the assigned pairs (d < c)
    double missed = 0;        ///< c^p / 2 * missed_count
    double false_ = 0;        ///< c^p / 2 * false_count
    int missed_count = 0;     ///< truth points without an estimate within c
    int false_count = 0;      ///< estimated points without a truth point within c
    int assigned = 0;         ///< pairs with d < c
    double ospa = 0;          ///< OSPA distance (same c and p)
    std::vector<int> truth_to_est;  ///< assigned estimate of each truth point, -1: missed
};

/** GOSPA and OSPA from a distance matrix d[i * n + j] between truth i and estimate j. */
FrameMetrics frame_metrics(const std::vector<double> &dist, std::size_t m, std::size_t n, double c, double p);
/** The same for 2-D points (Euclidean distance). */
FrameMetrics frame_metrics(const std::vector<Point> &truth, const std::vector<Point> &est, double c, double p);

/** Monte Carlo accumulation over runs and frames. Per frame the additive p-th-power terms are
 *  kept; averages are power means, (mean of the p-th powers)^(1/p) (RMS for p = 2), so that
 *  gospa^p = localisation^p + missed^p + false^p holds for the averages too. */
class SetMetricSums {
public:
    SetMetricSums(std::size_t frames, double c, double p);
    /** Adds one run's frame k (0-based). */
    void add(std::size_t k, const FrameMetrics &f);
    /** Adds one run's frame from its stored terms (partial summaries). */
    void add_terms(std::size_t k, double localisation, int missed_count, int false_count, double ospa_pow);
    /** Adds another accumulation of the same frame count, c and p (e.g. another run's); an
     *  empty accumulation takes the other's c and p. */
    void merge(const SetMetricSums &o);
    /** The raw sums, exactly (partial summaries of `pft eval --shard`): {c, p, loc, miss, fal,
     *  ospa, nmiss, nfal, n}; from_raw(raw()) merges bit for bit like the original. */
    nlohmann::json raw() const;
    static SetMetricSums from_raw(const nlohmann::json &j);
    /** Frames (run-frames) added over all frames. */
    long added() const { return count(); }
    std::size_t frames() const { return n_.size(); }
    double c() const { return c_; }
    double p() const { return p_; }
    /** Power mean over the runs at frame k (NaN without a run). */
    double gospa_at(std::size_t k) const;
    double ospa_at(std::size_t k) const;
    /** Over every run and frame. */
    double gospa() const;
    double localisation() const;
    double missed() const;
    double false_() const;
    double ospa() const;
    /** Mean counts per frame over every run and frame. */
    double missed_count() const;
    double false_count() const;

private:
    double c_, p_;
    std::vector<double> loc_, miss_, fal_, ospa_;  ///< per frame: sums of the p-th-power terms
    std::vector<double> nmiss_, nfal_;             ///< per frame: sums of the counts
    std::vector<long> n_;                          ///< per frame: runs added
    double root(double sum, double count) const;
    double total(const std::vector<double> &v) const;
    long count() const;
};

/** The averaged fields of a summary: gospa, gospa_localisation, gospa_missed, gospa_false,
 *  gospa_missed_count, gospa_false_count, ospa (null where nothing was added). */
nlohmann::json set_metric_fields(const SetMetricSums &s);

}  // namespace pft::host::metrics
