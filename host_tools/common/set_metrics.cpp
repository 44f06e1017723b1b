#include "set_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pft::host::metrics {

namespace {

const double kInf = std::numeric_limits<double>::infinity();

/** rows <= cols: each row gets a distinct column. Rows are added one at a time; for each, a
 *  Dijkstra search on reduced costs c(i, j) - u(i) - v(j) >= 0 finds the cheapest augmenting
 *  path to a free column; the potentials are then updated so reduced costs stay >= 0 and are 0
 *  on the matched pairs (which proves optimality), and the path is flipped. */
std::vector<int> assign_wide(const std::vector<double> &cost, std::size_t rows, std::size_t cols)
{
    std::vector<double> u(rows, 0.0), v(cols, 0.0), shortest(cols);
    std::vector<int> col_of_row(rows, -1), row_of_col(cols, -1), pred(cols);
    std::vector<char> row_seen(rows), col_done(cols);
    for (std::size_t start = 0; start < rows; ++start) {
        std::fill(shortest.begin(), shortest.end(), kInf);
        std::fill(pred.begin(), pred.end(), -1);
        std::fill(row_seen.begin(), row_seen.end(), 0);
        std::fill(col_done.begin(), col_done.end(), 0);
        double reach = 0.0;  // length of the path to the row being expanded
        std::size_t i = start;
        int sink = -1;
        while (sink < 0) {
            row_seen[i] = 1;
            double best = kInf;
            int best_j = -1;
            for (std::size_t j = 0; j < cols; ++j) {
                if (col_done[j])
                    continue;
                double r = reach + cost[i * cols + j] - u[i] - v[j];
                if (r < shortest[j]) {
                    shortest[j] = r;
                    pred[j] = static_cast<int>(i);
                }
                // ties: prefer a free column (ends the search sooner)
                if (shortest[j] < best || (shortest[j] == best && row_of_col[j] < 0)) {
                    best = shortest[j];
                    best_j = static_cast<int>(j);
                }
            }
            if (best_j < 0 || !std::isfinite(best))
                throw std::invalid_argument("assign_min_cost: cost matrix with a non-finite entry");
            reach = best;
            col_done[best_j] = 1;
            if (row_of_col[best_j] < 0)
                sink = best_j;
            else
                i = static_cast<std::size_t>(row_of_col[best_j]);
        }
        // potentials: keep reduced costs >= 0 on every edge, 0 on the matched ones
        u[start] += reach;
        for (std::size_t r = 0; r < rows; ++r)
            if (row_seen[r] && r != start)
                u[r] += reach - shortest[col_of_row[r]];
        for (std::size_t j = 0; j < cols; ++j)
            if (col_done[j])
                v[j] -= reach - shortest[j];
        // flip the augmenting path
        int j = sink;
        for (;;) {
            int r = pred[j];
            row_of_col[j] = r;
            std::swap(col_of_row[r], j);
            if (r == static_cast<int>(start))
                break;
        }
    }
    return col_of_row;
}

}  // namespace

std::vector<int> assign_min_cost(const std::vector<double> &cost, std::size_t rows, std::size_t cols,
                                 double *total)
{
    if (cost.size() != rows * cols)
        throw std::invalid_argument("assign_min_cost: cost size is not rows x cols");
    std::vector<int> row_to_col(rows, -1);
    if (rows && cols) {
        if (rows <= cols) {
            row_to_col = assign_wide(cost, rows, cols);
        } else {
            std::vector<double> t(cols * rows);
            for (std::size_t i = 0; i < rows; ++i)
                for (std::size_t j = 0; j < cols; ++j)
                    t[j * rows + i] = cost[i * cols + j];
            std::vector<int> col_to_row = assign_wide(t, cols, rows);
            for (std::size_t j = 0; j < cols; ++j)
                row_to_col[col_to_row[j]] = static_cast<int>(j);
        }
    }
    if (total) {
        double s = 0.0;
        for (std::size_t i = 0; i < rows; ++i)
            if (row_to_col[i] >= 0)
                s += cost[i * cols + row_to_col[i]];
        *total = s;
    }
    return row_to_col;
}

FrameMetrics frame_metrics(const std::vector<double> &dist, std::size_t m, std::size_t n, double c, double p)
{
    if (!(c > 0) || !(p >= 1) || !std::isfinite(c) || !std::isfinite(p))
        throw std::invalid_argument("GOSPA/OSPA need c > 0 and 1 <= p < infinity");
    if (dist.size() != m * n)
        throw std::invalid_argument("frame_metrics: distance matrix is not m x n");
    const double cp = std::pow(c, p);
    FrameMetrics f;
    f.truth_to_est.assign(m, -1);
    double opt = 0.0;  // sum over the matching of min(d, c)^p
    if (m && n) {
        std::vector<double> cost(m * n);
        for (std::size_t k = 0; k < cost.size(); ++k)
            cost[k] = dist[k] < c ? std::pow(dist[k], p) : cp;
        std::vector<int> a = assign_min_cost(cost, m, n);
        for (std::size_t i = 0; i < m; ++i) {
            if (a[i] < 0)
                continue;
            double d = dist[i * n + a[i]];
            if (d < c) {
                double dp = cost[i * n + a[i]];
                f.localisation += dp;
                opt += dp;
                f.truth_to_est[i] = a[i];
                ++f.assigned;
            } else {
                opt += cp;
            }
        }
    }
    f.missed_count = static_cast<int>(m) - f.assigned;
    f.false_count = static_cast<int>(n) - f.assigned;
    f.missed = cp / 2.0 * f.missed_count;
    f.false_ = cp / 2.0 * f.false_count;
    f.gospa = std::pow(f.localisation + f.missed + f.false_, 1.0 / p);
    const std::size_t big = std::max(m, n), small = std::min(m, n);
    f.ospa = big ? std::pow((opt + cp * static_cast<double>(big - small)) / static_cast<double>(big), 1.0 / p) : 0.0;
    return f;
}

FrameMetrics frame_metrics(const std::vector<Point> &truth, const std::vector<Point> &est, double c, double p)
{
    std::vector<double> d(truth.size() * est.size());
    for (std::size_t i = 0; i < truth.size(); ++i)
        for (std::size_t j = 0; j < est.size(); ++j)
            d[i * est.size() + j] = std::hypot(truth[i].x - est[j].x, truth[i].y - est[j].y);
    return frame_metrics(d, truth.size(), est.size(), c, p);
}

SetMetricSums::SetMetricSums(std::size_t frames, double c, double p)
    : c_(c), p_(p), loc_(frames, 0.0), miss_(frames, 0.0), fal_(frames, 0.0), ospa_(frames, 0.0),
      nmiss_(frames, 0.0), nfal_(frames, 0.0), n_(frames, 0)
{
}

void SetMetricSums::add(std::size_t k, const FrameMetrics &f)
{
    add_terms(k, f.localisation, f.missed_count, f.false_count, std::pow(f.ospa, p_));
}

void SetMetricSums::add_terms(std::size_t k, double localisation, int missed_count, int false_count,
                              double ospa_pow)
{
    if (k >= n_.size())
        return;
    const double half = std::pow(c_, p_) / 2.0;
    loc_[k] += localisation;
    miss_[k] += half * missed_count;
    fal_[k] += half * false_count;
    ospa_[k] += ospa_pow;
    nmiss_[k] += missed_count;
    nfal_[k] += false_count;
    ++n_[k];
}

double SetMetricSums::root(double sum, double count) const
{
    return count > 0 ? std::pow(sum / count, 1.0 / p_) : std::numeric_limits<double>::quiet_NaN();
}

double SetMetricSums::total(const std::vector<double> &v) const
{
    double s = 0.0;
    for (double x : v)
        s += x;
    return s;
}

long SetMetricSums::count() const
{
    long s = 0;
    for (long x : n_)
        s += x;
    return s;
}

double SetMetricSums::gospa_at(std::size_t k) const
{
    return root(loc_[k] + miss_[k] + fal_[k], static_cast<double>(n_[k]));
}
double SetMetricSums::ospa_at(std::size_t k) const { return root(ospa_[k], static_cast<double>(n_[k])); }
double SetMetricSums::gospa() const
{
    return root(total(loc_) + total(miss_) + total(fal_), static_cast<double>(count()));
}
double SetMetricSums::localisation() const { return root(total(loc_), static_cast<double>(count())); }
double SetMetricSums::missed() const { return root(total(miss_), static_cast<double>(count())); }
double SetMetricSums::false_() const { return root(total(fal_), static_cast<double>(count())); }
double SetMetricSums::ospa() const { return root(total(ospa_), static_cast<double>(count())); }
double SetMetricSums::missed_count() const
{
    long n = count();
    return n ? total(nmiss_) / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}
double SetMetricSums::false_count() const
{
    long n = count();
    return n ? total(nfal_) / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

void SetMetricSums::merge(const SetMetricSums &o)
{
    if (count() == 0 && n_.size() == o.n_.size()) {
        c_ = o.c_;
        p_ = o.p_;
    }
    const std::size_t n = std::min(n_.size(), o.n_.size());
    for (std::size_t k = 0; k < n; ++k) {
        loc_[k] += o.loc_[k];
        miss_[k] += o.miss_[k];
        fal_[k] += o.fal_[k];
        ospa_[k] += o.ospa_[k];
        nmiss_[k] += o.nmiss_[k];
        nfal_[k] += o.nfal_[k];
        n_[k] += o.n_[k];
    }
}

nlohmann::json SetMetricSums::raw() const
{
    return {{"c", c_}, {"p", p_}, {"loc", loc_}, {"miss", miss_}, {"fal", fal_}, {"ospa", ospa_},
            {"nmiss", nmiss_}, {"nfal", nfal_}, {"n", n_}};
}

SetMetricSums SetMetricSums::from_raw(const nlohmann::json &j)
{
    SetMetricSums s(0, j.at("c").get<double>(), j.at("p").get<double>());
    s.loc_ = j.at("loc").get<std::vector<double>>();
    s.miss_ = j.at("miss").get<std::vector<double>>();
    s.fal_ = j.at("fal").get<std::vector<double>>();
    s.ospa_ = j.at("ospa").get<std::vector<double>>();
    s.nmiss_ = j.at("nmiss").get<std::vector<double>>();
    s.nfal_ = j.at("nfal").get<std::vector<double>>();
    s.n_ = j.at("n").get<std::vector<long>>();
    const std::size_t f = s.n_.size();
    if (s.loc_.size() != f || s.miss_.size() != f || s.fal_.size() != f || s.ospa_.size() != f ||
        s.nmiss_.size() != f || s.nfal_.size() != f)
        throw std::runtime_error("set metric sums: arrays of different lengths");
    return s;
}

nlohmann::json set_metric_fields(const SetMetricSums &s)
{
    auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    return {{"gospa", num(s.gospa())},
            {"gospa_localisation", num(s.localisation())},
            {"gospa_missed", num(s.missed())},
            {"gospa_false", num(s.false_())},
            {"gospa_missed_count", num(s.missed_count())},
            {"gospa_false_count", num(s.false_count())},
            {"ospa", num(s.ospa())}};
}

}  // namespace pft::host::metrics
