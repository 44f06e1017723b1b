// Small reusable line-plot helper drawn with OpenCV: axes, "nice" ticks, grid, title,
// solid/dashed lines, optional markers and error bars, and a legend in its own column right of
// the axes (never over the data). The y range covers the data and the error bars with a margin
// above, so no curve is clipped at its maximum. Used for the eval figures (existence
// probability and RMSE against frame, RMSE against SNR).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace pft::host {

struct PlotSeries {
    std::string label;
    std::vector<double> x, y;  ///< NaN y values break the line
    std::vector<double> err;   ///< optional: half-width of an error bar at each point (NaN: none)
    std::optional<cv::Scalar> color;  ///< BGR; default: from the palette
    bool dashed = false;
    bool markers = false;
    int thickness = 2;
};

struct PlotSpec {
    std::string title, xlabel, ylabel;
    std::vector<PlotSeries> series;
    std::optional<double> ymin, ymax, xmin, xmax;  ///< fixed limits, else from the data
    int width = 900, height = 560;
};

/** Renders the plot into a BGR image. */
cv::Mat render_plot(const PlotSpec &spec);
/** Renders and writes a PNG atomically (InputError on failure). */
void save_plot_png(const PlotSpec &spec, const std::string &path);
/** "Natural" order of labels: runs of digits compare as numbers ("N=6000" < "N=36000"). */
bool natural_less(const std::string &a, const std::string &b);
/** Ticks at 1/2/5 x 10^k covering [lo, hi], about `target` of them. */
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace pft::host
