#include "image.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "../common/errors.hpp"
#include "../common/output.hpp"

namespace pft::host::pte {

void save_rangetime_png(const std::string &path, const std::vector<std::vector<float>> &z,
                        const std::vector<std::vector<Truth>> *truths, const std::vector<Panel> &panels,
                        double lo, double hi, const std::string &caption)
{
    const int frames = static_cast<int>(z.size());
    const int cells = frames ? static_cast<int>(z[0].size()) : 0;
    if (!frames || !cells || panels.empty())
        throw InputError(path + ": nothing to draw");
    const int sx = std::max(1, 300 / cells), sy = std::max(1, 600 / frames);
    const int pw = cells * sx, ph = frames * sy, gap = 12, top = 30, bottom = 30;
    cv::Mat grey(frames, cells, CV_8UC1);
    for (int k = 0; k < frames; ++k)
        for (int u = 0; u < cells; ++u) {
            double v = (z[k][u] - lo) / (hi - lo) * 255.0;
            // 16 grey levels: enough for the eye, and noise images compress about 2x better as PNG
            grey.at<uint8_t>(k, u) = static_cast<uint8_t>(static_cast<int>(std::clamp(v, 0.0, 255.0)) & 0xF0);
        }
    cv::Mat big;
    cv::resize(grey, big, cv::Size(pw, ph), 0, 0, cv::INTER_NEAREST);
    cv::Mat bgr;
    cv::cvtColor(big, bgr, cv::COLOR_GRAY2BGR);
    const int n = static_cast<int>(panels.size());
    cv::Mat img(ph + top + bottom, n * pw + (n + 1) * gap, CV_8UC3, cv::Scalar(255, 255, 255));
    auto xpix = [&](double r) { return static_cast<int>(std::lround((r + 0.5) * sx)); };
    auto ypix = [&](int k) { return k * sy + sy / 2; };
    for (int p = 0; p < n; ++p) {
        int x0 = gap + p * (pw + gap);
        cv::Mat roi = img(cv::Rect(x0, top, pw, ph));
        bgr.copyTo(roi);
        if (truths && panels[p].points) {
            static const cv::Scalar colours[] = {{0, 200, 0}, {255, 140, 0}, {200, 0, 200}, {0, 200, 220}};
            for (std::size_t t = 0; t < truths->size(); ++t) {
                const std::vector<Truth> &tr = (*truths)[t];
                for (int k = 1; k < frames && k < static_cast<int>(tr.size()); ++k)
                    if (tr[k - 1].active && tr[k].active)
                        cv::line(roi, cv::Point(xpix(tr[k - 1].r), ypix(k - 1)), cv::Point(xpix(tr[k].r), ypix(k)),
                                 colours[t % 4], 1, cv::LINE_AA);
            }
        }
        if (panels[p].points) {
            const auto &pts = *panels[p].points;
            for (int k = 0; k < frames && k < static_cast<int>(pts.size()); ++k)
                for (const Report &r : pts[k]) {
                    cv::Scalar col = r.detected ? cv::Scalar(0, 0, 230) : cv::Scalar(0, 150, 255);
                    cv::circle(roi, cv::Point(xpix(r.pos), ypix(k)), std::max(1, sx / 2), col, -1);
                }
        }
        cv::putText(img, panels[p].title, cv::Point(x0, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                    cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    cv::putText(img, caption, cv::Point(gap, top + ph + 20), cv::FONT_HERSHEY_SIMPLEX, 0.42,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    AtomicPath ap(path);
    bool ok = false;
    try {
        // zlib level 9: the 16-level noise compresses about 4x better than at OpenCV's default
        ok = cv::imwrite(ap.tmp(), img, {cv::IMWRITE_PNG_COMPRESSION, 9});
    } catch (const cv::Exception &e) {
        throw InputError(path + ": cannot write PNG (" + e.what() + ")");
    }
    if (!ok)
        throw InputError(path + ": cannot write PNG");
    ap.commit();
}

}  // namespace pft::host::pte
