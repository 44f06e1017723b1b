#include "plot.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "errors.hpp"
#include "output.hpp"

namespace pft::host {

namespace {

const cv::Scalar kPalette[] = {
    {180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214}, {189, 103, 148},
    {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23}};
const int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string fmt_tick(double v, double step)
{
    char buf[32];
    int dec = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    if (dec > 6)
        dec = 6;
    if (std::fabs(v) < step * 1e-9)
        v = 0.0;
    std::snprintf(buf, sizeof buf, "%.*f", dec, v);
    return buf;
}

void text(cv::Mat &img, const std::string &s, cv::Point org, double scale, int thick,
          int align /* 0 left, 1 centre, 2 right */, int valign /* 0 baseline, 1 centre */)
{
    int base = 0;
    cv::Size sz = cv::getTextSize(s, kFont, scale, thick, &base);
    if (align == 1)
        org.x -= sz.width / 2;
    else if (align == 2)
        org.x -= sz.width;
    if (valign == 1)
        org.y += sz.height / 2;
    cv::putText(img, s, org, kFont, scale, cv::Scalar(0, 0, 0), thick, cv::LINE_AA);
}

}  // namespace

bool natural_less(const std::string &a, const std::string &b)
{
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
        bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
        if (da && db) {
            std::size_t i2 = i, j2 = j;
            while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2])))
                ++i2;
            while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2])))
                ++j2;
            // compare the numbers without leading zeros: longer is larger, else digit by digit
            std::size_t a0 = i, b0 = j;
            while (a0 + 1 < i2 && a[a0] == '0')
                ++a0;
            while (b0 + 1 < j2 && b[b0] == '0')
                ++b0;
            if (i2 - a0 != j2 - b0)
                return i2 - a0 < j2 - b0;
            int c = a.compare(a0, i2 - a0, b, b0, j2 - b0);
            if (c != 0)
                return c < 0;
            i = i2;
            j = j2;
            continue;
        }
        if (a[i] != b[j])
            return a[i] < b[j];
        ++i;
        ++j;
    }
    return a.size() - i < b.size() - j;
}

std::vector<double> nice_ticks(double lo, double hi, int target)
{
    std::vector<double> t;
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi))
        return t;
    double raw = (hi - lo) / std::max(1, target);
    double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
        step = m * mag;
        if (step >= raw)
            break;
    }
    double first = std::ceil(lo / step - 1e-9) * step;
    for (double v = first; v <= hi + step * 1e-9 && t.size() < 100; v += step)
        t.push_back(v);
    return t;
}

cv::Mat render_plot(const PlotSpec &spec)
{
    // legend column right of the axes: the image grows by its width, the axes keep theirs
    std::vector<std::size_t> shown;
    int lw = 0;
    for (std::size_t si = 0; si < spec.series.size(); ++si) {
        if (spec.series[si].label.empty())
            continue;
        shown.push_back(si);
        int base = 0;
        lw = std::max(lw, cv::getTextSize(spec.series[si].label, kFont, 0.45, 1, &base).width);
    }
    const int legend_w = shown.empty() ? 0 : lw + 60;
    const int W = std::max(300, spec.width) + legend_w, H = std::max(200, spec.height);
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    const int left = 90, right = 25 + legend_w, top = spec.title.empty() ? 25 : 50, bottom = 65;
    const cv::Rect area(left, top, W - left - right, H - top - bottom);

    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const auto &s : spec.series)
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]))
                continue;
            double e = i < s.err.size() && std::isfinite(s.err[i]) ? std::fabs(s.err[i]) : 0.0;
            x0 = std::min(x0, s.x[i]);
            x1 = std::max(x1, s.x[i]);
            y0 = std::min(y0, s.y[i] - e);
            y1 = std::max(y1, s.y[i] + e);
        }
    if (!std::isfinite(x0)) {
        x0 = 0;
        x1 = 1;
        y0 = 0;
        y1 = 1;
    }
    if (spec.xmin)
        x0 = *spec.xmin;
    if (spec.xmax)
        x1 = *spec.xmax;
    if (spec.ymin)
        y0 = *spec.ymin;
    if (spec.ymax)
        y1 = *spec.ymax;
    if (x1 <= x0) {  // one x value: centre it rather than put it on the frame
        double pad = std::fabs(x0) > 0 ? std::fabs(x0) * 0.1 : 0.5;
        if (!spec.xmin)
            x0 -= pad;
        x1 = x0 + 2 * pad;
        if (spec.xmin)
            x1 = x0 + 1;
    }
    if (y1 <= y0) {
        double pad = std::fabs(y0) > 0 ? std::fabs(y0) * 0.1 : 1.0;
        if (!spec.ymin)
            y0 -= pad;
        if (!spec.ymax)
            y1 += pad;
    } else {
        // a margin above the data unless the top is fixed, so the maximum is not on the frame
        double pad = 0.06 * (y1 - y0);
        if (!spec.ymax)
            y1 += pad;
        if (!spec.ymin && y0 != 0.0)
            y0 -= pad;
    }

    auto px = [&](double x) {
        return area.x + static_cast<int>(std::lround((x - x0) / (x1 - x0) * area.width));
    };
    auto py = [&](double y) {
        return area.y + area.height -
               static_cast<int>(std::lround((y - y0) / (y1 - y0) * area.height));
    };

    // grid and ticks
    auto xt = nice_ticks(x0, x1, 8), yt = nice_ticks(y0, y1, 6);
    double xs = xt.size() > 1 ? xt[1] - xt[0] : 1.0, ys = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
    for (double v : xt) {
        int X = px(v);
        cv::line(img, {X, area.y}, {X, area.y + area.height}, cv::Scalar(230, 230, 230), 1);
        cv::line(img, {X, area.y + area.height}, {X, area.y + area.height + 5}, cv::Scalar(0, 0, 0), 1);
        text(img, fmt_tick(v, xs), {X, area.y + area.height + 22}, 0.45, 1, 1, 0);
    }
    for (double v : yt) {
        int Y = py(v);
        cv::line(img, {area.x, Y}, {area.x + area.width, Y}, cv::Scalar(230, 230, 230), 1);
        cv::line(img, {area.x - 5, Y}, {area.x, Y}, cv::Scalar(0, 0, 0), 1);
        text(img, fmt_tick(v, ys), {area.x - 8, Y}, 0.45, 1, 2, 1);
    }
    cv::rectangle(img, area, cv::Scalar(0, 0, 0), 1);

    // series, clipped to the plot area
    cv::Mat roi = img(area);
    for (std::size_t si = 0; si < spec.series.size(); ++si) {
        const auto &s = spec.series[si];
        cv::Scalar col = s.color ? *s.color : kPalette[si % 10];
        bool have_prev = false;
        cv::Point prev;
        double dash_phase = 0.0;
        for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
                have_prev = false;
                continue;
            }
            cv::Point p(px(s.x[i]) - area.x, py(s.y[i]) - area.y);
            if (have_prev) {
                if (!s.dashed) {
                    cv::line(roi, prev, p, col, s.thickness, cv::LINE_AA);
                } else {
                    double len = std::hypot(p.x - prev.x, p.y - prev.y);
                    const double on = 9.0, period = 15.0;
                    for (double t = 0; t < len;) {
                        double ph = std::fmod(dash_phase + t, period);
                        double seg = ph < on ? on - ph : period - ph;
                        double t2 = std::min(len, t + seg);
                        if (ph < on) {
                            cv::Point a(prev.x + static_cast<int>((p.x - prev.x) * t / len),
                                        prev.y + static_cast<int>((p.y - prev.y) * t / len));
                            cv::Point b(prev.x + static_cast<int>((p.x - prev.x) * t2 / len),
                                        prev.y + static_cast<int>((p.y - prev.y) * t2 / len));
                            cv::line(roi, a, b, col, s.thickness, cv::LINE_AA);
                        }
                        t = t2 + 1e-9;
                    }
                    dash_phase = std::fmod(dash_phase + len, period);
                }
            }
            if (s.markers)
                cv::circle(roi, p, 4, col, cv::FILLED, cv::LINE_AA);
            if (i < s.err.size() && std::isfinite(s.err[i]) && s.err[i] != 0.0) {
                double e = std::fabs(s.err[i]);
                int ya = py(s.y[i] + e) - area.y, yb = py(s.y[i] - e) - area.y;
                cv::line(roi, {p.x, ya}, {p.x, yb}, col, 1, cv::LINE_AA);
                cv::line(roi, {p.x - 4, ya}, {p.x + 4, ya}, col, 1, cv::LINE_AA);
                cv::line(roi, {p.x - 4, yb}, {p.x + 4, yb}, col, 1, cv::LINE_AA);
            }
            prev = p;
            have_prev = true;
        }
    }

    // labels and title
    if (!spec.title.empty())
        text(img, spec.title, {W / 2, 32}, 0.65, 2, 1, 0);
    if (!spec.xlabel.empty())
        text(img, spec.xlabel, {area.x + area.width / 2, H - 18}, 0.55, 1, 1, 0);
    if (!spec.ylabel.empty()) {
        int base = 0;
        cv::Size sz = cv::getTextSize(spec.ylabel, kFont, 0.55, 1, &base);
        cv::Mat lab(sz.height + base + 6, sz.width + 6, CV_8UC3, cv::Scalar(255, 255, 255));
        cv::putText(lab, spec.ylabel, {3, sz.height + 2}, kFont, 0.55, cv::Scalar(0, 0, 0), 1,
                    cv::LINE_AA);
        cv::Mat rot;
        cv::rotate(lab, rot, cv::ROTATE_90_COUNTERCLOCKWISE);
        int yy = std::max(0, area.y + area.height / 2 - rot.rows / 2);
        if (rot.rows + yy <= H && rot.cols + 8 <= left)
            rot.copyTo(img(cv::Rect(8, yy, rot.cols, rot.rows)));
    }

    // legend in its column right of the axes
    if (!shown.empty()) {
        int row = 20, bw = lw + 50, bh = static_cast<int>(shown.size()) * row + 10;
        cv::Rect box(area.x + area.width + 15, area.y, bw, bh);
        cv::rectangle(img, box, cv::Scalar(255, 255, 255), cv::FILLED);
        cv::rectangle(img, box, cv::Scalar(120, 120, 120), 1);
        for (std::size_t k = 0; k < shown.size(); ++k) {
            const auto &s = spec.series[shown[k]];
            cv::Scalar col = s.color ? *s.color : kPalette[shown[k] % 10];
            int Y = box.y + 15 + static_cast<int>(k) * row;
            if (s.dashed) {
                cv::line(img, {box.x + 8, Y}, {box.x + 18, Y}, col, s.thickness, cv::LINE_AA);
                cv::line(img, {box.x + 26, Y}, {box.x + 36, Y}, col, s.thickness, cv::LINE_AA);
            } else {
                cv::line(img, {box.x + 8, Y}, {box.x + 36, Y}, col, s.thickness, cv::LINE_AA);
            }
            if (s.markers)
                cv::circle(img, {box.x + 22, Y}, 4, col, cv::FILLED, cv::LINE_AA);
            text(img, s.label, {box.x + 44, Y}, 0.45, 1, 0, 1);
        }
    }
    return img;
}

void save_plot_png(const PlotSpec &spec, const std::string &path)
{
    cv::Mat img = render_plot(spec);
    AtomicPath ap(path);
    bool ok = false;
    try {
        ok = cv::imwrite(ap.tmp(), img, {cv::IMWRITE_PNG_COMPRESSION, 9});
    } catch (const cv::Exception &e) {
        throw InputError(path + ": cannot write PNG (" + e.what() + ")");
    }
    if (!ok)
        throw InputError(path + ": cannot write PNG");
    ap.commit();
}

}  // namespace pft::host
