// Checks of host_tools/common/set_metrics.cpp (ctest host_set_metrics):
//  1. against an independent implementation: the GOSPA/OSPA values of Stone Soup kept in
//     fixtures/set_metrics_stonesoup.json (how they were made: fixtures/gen_set_metrics_fixture.py);
//  2. against brute force on random small cases: GOSPA straight from its definition (every
//     partial assignment, uncut distances), OSPA over every injection, and the assignment
//     solver over every injection of a random rectangular cost matrix;
//  3. the averages: gospa^p = localisation^p + missed^p + false^p.
// Usage: test_set_metrics FIXTURE.json   (prints "set_metrics: N checks, 0 failed")
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/set_metrics.hpp"

using namespace pft::host::metrics;

namespace {

int g_checks = 0, g_failed = 0;

void check(bool ok, const std::string &what)
{
    ++g_checks;
    if (!ok) {
        ++g_failed;
        std::printf("FAIL: %s\n", what.c_str());
    }
}

bool near(double a, double b, double rel = 1e-12)
{
    return std::fabs(a - b) <= rel * std::max(1.0, std::max(std::fabs(a), std::fabs(b)));
}

std::vector<Point> points(const nlohmann::json &a)
{
    std::vector<Point> v;
    for (const auto &p : a)
        v.push_back({p[0].get<double>(), p[1].get<double>()});
    return v;
}

void fixture_cases(const std::string &path)
{
    std::ifstream in(path);
    check(static_cast<bool>(in), "open " + path);
    if (!in)
        return;
    nlohmann::json j = nlohmann::json::parse(in);
    int n = 0;
    for (const auto &c : j["cases"]) {
        std::string name = c["name"].get<std::string>();
        double cc = c["c"].get<double>(), p = c["p"].get<double>();
        FrameMetrics f = frame_metrics(points(c["truth"]), points(c["estimate"]), cc, p);
        check(near(f.gospa, c["gospa"].get<double>()), name + ": gospa " + std::to_string(f.gospa));
        check(near(f.localisation, c["localisation"].get<double>()), name + ": localisation");
        check(near(f.missed, c["missed"].get<double>()), name + ": missed");
        check(near(f.false_, c["false"].get<double>()), name + ": false");
        if (c.contains("ospa"))
            check(near(f.ospa, c["ospa"].get<double>()), name + ": ospa " + std::to_string(f.ospa));
        ++n;
    }
    check(n >= 20, "fixture has at least 20 cases");
    std::printf("set_metrics: %d fixture cases (Stone Soup %s)\n", n,
                j.value("stonesoup", std::string("?")).c_str());
}

/** GOSPA^p from the definition: minimum over every partial assignment, distances uncut. */
double gospa_pow_brute(const std::vector<double> &d, std::size_t m, std::size_t n, double c, double p)
{
    double best = INFINITY;
    std::vector<char> used(n, 0);
    std::function<void(std::size_t, double, int)> rec = [&](std::size_t i, double acc, int pairs) {
        if (i == m) {
            double v = acc + std::pow(c, p) / 2.0 * static_cast<double>(m + n - 2 * pairs);
            best = std::min(best, v);
            return;
        }
        rec(i + 1, acc, pairs);  // truth i left unassigned
        for (std::size_t j = 0; j < n; ++j)
            if (!used[j]) {
                used[j] = 1;
                rec(i + 1, acc + std::pow(d[i * n + j], p), pairs + 1);
                used[j] = 0;
            }
    };
    rec(0, 0.0, 0);
    return best;
}

/** Minimum over every injection of the smaller side into the larger of sum cost. */
double min_injection(const std::vector<double> &cost, std::size_t rows, std::size_t cols)
{
    bool wide = rows <= cols;
    std::size_t a = wide ? rows : cols, b = wide ? cols : rows;
    auto at = [&](std::size_t i, std::size_t j) { return wide ? cost[i * cols + j] : cost[j * cols + i]; };
    double best = INFINITY;
    std::vector<char> used(b, 0);
    std::function<void(std::size_t, double)> rec = [&](std::size_t i, double acc) {
        if (i == a) {
            best = std::min(best, acc);
            return;
        }
        for (std::size_t j = 0; j < b; ++j)
            if (!used[j]) {
                used[j] = 1;
                rec(i + 1, acc + at(i, j));
                used[j] = 0;
            }
    };
    rec(0, 0.0);
    return best;
}

void brute_force_cases()
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int n_cases = 0;
    for (int t = 0; t < 600; ++t) {
        std::size_t m = rng() % 6, n = rng() % 6;
        double c = 0.5 + 4.0 * u(rng);
        double p = (t % 3 == 0) ? 1.0 : (t % 3 == 1) ? 2.0 : 1.0 + 3.0 * u(rng);
        double span = 2.5 * c;
        std::vector<Point> X(m), Y(n);
        for (auto &q : X)
            q = {span * u(rng), span * u(rng)};
        for (auto &q : Y)
            q = {span * u(rng), span * u(rng)};
        if (t % 7 == 0 && m && n)
            Y[0] = X[0];  // an exact hit
        std::vector<double> d(m * n);
        for (std::size_t i = 0; i < m; ++i)
            for (std::size_t j = 0; j < n; ++j)
                d[i * n + j] = std::hypot(X[i].x - Y[j].x, X[i].y - Y[j].y);
        FrameMetrics f = frame_metrics(X, Y, c, p);
        double gp = gospa_pow_brute(d, m, n, c, p);
        check(near(std::pow(f.gospa, p), gp, 1e-10),
              "brute force GOSPA, case " + std::to_string(t) + ": " + std::to_string(std::pow(f.gospa, p)) +
                  " vs " + std::to_string(gp));
        check(near(f.localisation + f.missed + f.false_, gp, 1e-10), "GOSPA parts add up, case " + std::to_string(t));
        check(f.missed_count == static_cast<int>(m) - f.assigned && f.false_count == static_cast<int>(n) - f.assigned,
              "GOSPA counts, case " + std::to_string(t));
        // OSPA by brute force over injections of min(d, c)^p
        std::size_t big = std::max(m, n), small = std::min(m, n);
        double ospa = 0.0;
        if (big) {
            std::vector<double> cut(m * n);
            for (std::size_t k = 0; k < cut.size(); ++k)
                cut[k] = std::pow(std::min(d[k], c), p);
            double o = small ? min_injection(cut, m, n) : 0.0;
            ospa = std::pow((o + std::pow(c, p) * static_cast<double>(big - small)) / static_cast<double>(big), 1.0 / p);
        }
        check(near(f.ospa, ospa, 1e-10), "brute force OSPA, case " + std::to_string(t));
        ++n_cases;
    }
    // the assignment solver alone, random rectangular costs (with ties from rounding)
    std::uniform_int_distribution<int> small_int(0, 9);
    for (int t = 0; t < 400; ++t) {
        std::size_t r = 1 + rng() % 6, k = 1 + rng() % 7;
        std::vector<double> cost(r * k);
        for (auto &x : cost)
            x = (t % 2) ? static_cast<double>(small_int(rng)) : 100.0 * u(rng) - 30.0;
        double total = 0;
        std::vector<int> a = assign_min_cost(cost, r, k, &total);
        std::vector<char> used(k, 0);
        bool valid = true;
        int n_assigned = 0;
        for (int j : a) {
            if (j < 0)
                continue;
            valid = valid && j < static_cast<int>(k) && !used[j];
            if (j >= 0 && j < static_cast<int>(k))
                used[j] = 1;
            ++n_assigned;
        }
        valid = valid && n_assigned == static_cast<int>(std::min(r, k));
        check(valid, "assignment is a matching of size min(rows, cols), case " + std::to_string(t));
        check(near(total, min_injection(cost, r, k), 1e-10), "assignment is optimal, case " + std::to_string(t));
    }
    std::printf("set_metrics: %d brute-force set cases, 400 assignment cases\n", n_cases);
}

void sums()
{
    SetMetricSums s(3, 2.0, 2.0);
    std::vector<Point> X = {{0, 0}, {5, 5}}, Y = {{0.5, 0}, {9, 9}, {1, 7}};
    FrameMetrics a = frame_metrics(X, Y, 2.0, 2.0), b = frame_metrics(X, {}, 2.0, 2.0);
    s.add(0, a);
    s.add(0, b);
    s.add(1, b);
    s.add(2, frame_metrics({}, {}, 2.0, 2.0));
    double g = s.gospa(), l = s.localisation(), mi = s.missed(), fa = s.false_();
    check(near(g * g, l * l + mi * mi + fa * fa), "averages: gospa^2 = loc^2 + missed^2 + false^2");
    double expect0 = std::sqrt((a.gospa * a.gospa + b.gospa * b.gospa) / 2.0);
    check(near(s.gospa_at(0), expect0), "per frame: power mean over runs");
    check(s.gospa_at(2) == 0.0 && s.ospa_at(2) == 0.0, "empty frame: 0");
    check(near(s.missed_count(), (a.missed_count + 2.0 + 2.0 + 0.0) / 4.0), "mean missed count");
    SetMetricSums e(2, 1.0, 1.0);
    check(std::isnan(e.gospa()) && std::isnan(e.gospa_at(0)), "no run: NaN (null in JSON)");
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::printf("usage: test_set_metrics FIXTURE.json\n");
        return 2;
    }
    fixture_cases(argv[1]);
    brute_force_cases();
    sums();
    std::printf("set_metrics: %d checks, %d failed\n", g_checks, g_failed);
    return g_failed ? 1 : 0;
}
