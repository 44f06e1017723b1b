// Range-time images as PNG: the simulated (or recorded) profiles as grey levels, time
// downwards and range across, with the truth (one line per target while it is active: the
// first green, then blue, magenta, yellow, cycling) and each method's declared points (red:
// detected at that frame, orange: coasting) in one panel per method.
#pragma once
#include <string>
#include <vector>

#include "methods.hpp"
#include "sim.hpp"

namespace pft::host::pte {

struct Panel {
    std::string title;
    const std::vector<std::vector<Report>> *points = nullptr;  ///< [frame] (nullptr: image only)
};

/** Writes the panels side by side; lo/hi: grey-level range of the profile values; truths:
 *  [target][frame] (nullptr: no truth), drawn in the panels that have points. */
void save_rangetime_png(const std::string &path, const std::vector<std::vector<float>> &z,
                        const std::vector<std::vector<Truth>> *truths, const std::vector<Panel> &panels,
                        double lo, double hi, const std::string &caption);

}  // namespace pft::host::pte
