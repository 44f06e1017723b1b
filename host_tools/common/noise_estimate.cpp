#include "noise_estimate.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace pft::host {

namespace {

const double kMadToSigma = 1.482602218505602;  // 1 / Phi^-1(3/4)
const std::size_t kMaxSamples = 4000000;       // enough for a 0.1% estimate; bounds the time

double median_of(std::vector<float> &v)
{
    if (v.empty())
        return 0.0;
    auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

double frames_median(const std::vector<cv::Mat> &frames)
{
    std::vector<float> all;
    for (const cv::Mat &f : frames) {
        std::size_t step = std::max<std::size_t>(1, f.total() * frames.size() / kMaxSamples);
        for (int r = 0; r < f.rows; ++r) {
            const float *p = f.ptr<float>(r);
            for (int c = 0; c < f.cols; ++c)
                if ((static_cast<std::size_t>(r) * f.cols + c) % step == 0)
                    all.push_back(p[c]);
        }
    }
    return median_of(all);
}

cv::Mat usable_3x3(const cv::Mat &mask, cv::Size size)
{
    cv::Mat ok(size, CV_8U, cv::Scalar(255));
    if (!mask.empty())
        cv::erode(mask != 0, ok, cv::Mat::ones(3, 3, CV_8U), cv::Point(-1, -1), 1,
                  cv::BORDER_CONSTANT, cv::Scalar(0));
    // the border row/column has no full ring
    ok.row(0).setTo(0);
    ok.row(size.height - 1).setTo(0);
    ok.col(0).setTo(0);
    ok.col(size.width - 1).setTo(0);
    return ok;
}

}  // namespace

double robust_sigma(std::vector<float> &v, double *median)
{
    if (v.empty()) {
        if (median)
            *median = 0.0;
        return 0.0;
    }
    double med = median_of(v);
    if (median)
        *median = med;
    std::vector<float> dev(v.size());
    double sum_abs = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        dev[i] = static_cast<float>(std::fabs(v[i] - med));
        sum_abs += dev[i];
    }
    double s = kMadToSigma * median_of(dev);
    if (!(s > 0.0))
        s = std::sqrt(M_PI / 2.0) * sum_abs / static_cast<double>(v.size());
    if (!(s > 0.0))
        return 0.0;
    // refine: deviation of the values within 3 s of the median, for the truncation scaled
    // back to a Gaussian sigma (a MAD of integer data moves in steps; this does not)
    const double k = 3.0, trunc = 0.98658;  // sqrt(1 - 2 k phi(k) / (2 Phi(k) - 1))
    for (int it = 0; it < 3; ++it) {
        double sum = 0.0, sum2 = 0.0;
        std::size_t n = 0;
        const double lim = k * s;
        for (float x : v) {
            double d = x - med;
            if (std::fabs(d) <= lim) {
                sum += d;
                sum2 += d * d;
                ++n;
            }
        }
        if (n < 2)
            break;
        double mean = sum / static_cast<double>(n);
        double var = sum2 / static_cast<double>(n) - mean * mean;
        if (!(var > 0.0))
            break;
        s = std::sqrt(var) / trunc;
    }
    return s;
}

NoiseEstimate estimate_noise_spatial(const std::vector<cv::Mat> &frames, const cv::Mat &mask)
{
    NoiseEstimate e;
    e.method = "spatial";
    e.frames = static_cast<int>(frames.size());
    if (frames.empty() || frames[0].rows < 3 || frames[0].cols < 3) {
        e.degenerate = true;
        return e;
    }
    e.background = frames_median(frames);
    cv::Mat ok = usable_3x3(mask, frames[0].size());
    std::size_t per = static_cast<std::size_t>(cv::countNonZero(ok));
    std::size_t step = std::max<std::size_t>(1, per * frames.size() / kMaxSamples);
    std::vector<float> res;
    res.reserve(per * frames.size() / step + 1);
    cv::Mat sum9;
    std::size_t n = 0;
    for (const cv::Mat &f : frames) {
        cv::boxFilter(f, sum9, CV_32F, cv::Size(3, 3), cv::Point(-1, -1), false,
                      cv::BORDER_REPLICATE);
        for (int r = 1; r + 1 < f.rows; ++r) {
            const float *z = f.ptr<float>(r), *s = sum9.ptr<float>(r);
            const uint8_t *m = ok.ptr<uint8_t>(r);
            for (int c = 1; c + 1 < f.cols; ++c)
                if (m[c] && (n++ % step) == 0)
                    res.push_back((9.0f * z[c] - s[c]) / 8.0f);
        }
    }
    e.samples = static_cast<long>(res.size());
    e.sigma = robust_sigma(res) / std::sqrt(9.0 / 8.0);
    e.degenerate = !(e.sigma > 0.0);
    return e;
}

NoiseEstimate estimate_noise_temporal(const std::vector<cv::Mat> &frames, const cv::Mat &mask)
{
    NoiseEstimate e;
    e.method = "temporal";
    e.frames = static_cast<int>(frames.size());
    if (frames.size() < 2) {
        e.degenerate = true;
        return e;
    }
    e.background = frames_median(frames);
    std::vector<float> d;
    for (std::size_t k = 1; k < frames.size(); ++k)
        for (int r = 0; r < frames[k].rows; ++r) {
            const float *a = frames[k].ptr<float>(r), *b = frames[k - 1].ptr<float>(r);
            const uint8_t *m = mask.empty() ? nullptr : mask.ptr<uint8_t>(r);
            for (int c = 0; c < frames[k].cols; ++c)
                if (!m || m[c])
                    d.push_back(a[c] - b[c]);
        }
    e.samples = static_cast<long>(d.size());
    e.sigma = robust_sigma(d) / std::sqrt(2.0);
    e.degenerate = !(e.sigma > 0.0);
    return e;
}

}  // namespace pft::host
