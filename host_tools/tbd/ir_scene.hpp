// Backgrounds of the tbd_ir simulator: the scene the sensor drifts over, in sensor counts,
// band-limited by the optics blur. Either built in (procedural sky: fractal clouds with soft
// edges, a sky gradient, an optional horizon with textured ground and structures) or read
// from a folder of 8- or 16-bit images, with the objects of their YOLO label files
// (`class cx cy w h`, fractions of the image) kept as scene objects.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "ir_scenario.hpp"

namespace pft::host::tbd_ir {

/** A labelled object of a background image, in scene pixels (0-based centre) and pixels. */
struct SceneObject {
    int cls = 0;
    double x = 0, y = 0, w = 0, h = 0;
    double snr_db = NAN;  ///< peak over the local background / temporal sigma (NaN: not positive)
};

struct Scene {
    cv::Mat counts;                  ///< CV_32F, sensor counts, after the optics blur
    std::vector<SceneObject> objects;
    std::string source;              ///< "procedural" or the image file
    int image_bits = 0;              ///< bits of the image file (0: procedural)
    int mirrored_px = 0;             ///< border added by mirroring (the image was too small)
};

/** Image files of a background folder (or the scenario's `files`), in natural name order;
 *  InputError when there is none. */
std::vector<std::string> background_files(const Background &b);

/** YOLO label file `class cx cy w h` (fractions) -> objects in pixels of a w x h image;
 *  InputError naming the file and line on a malformed line. */
std::vector<SceneObject> read_yolo_labels(const std::string &path, int width, int height);

/** Procedural scene of scene_w x scene_h; the frame of height frame_h starts at row y0 (the
 *  horizon is placed relative to it). Deterministic in `seed`. */
Scene procedural_scene(const IrScenario &s, int scene_w, int scene_h, double y0, int frame_h,
                       uint64_t seed);

/** The background image `file` scaled to the sensor's counts and blurred; objects from its
 *  label file when background.labels. */
Scene image_scene(const IrScenario &s, const std::string &file);

/** Peak of an object above its local background (counts) in a scene: max over the box minus
 *  the median of a ring 3 px outside it. */
double object_amplitude(const cv::Mat &counts, const SceneObject &o);

/** Fractal noise (sum of octaves of bicubically interpolated random grids, persistence 0.5)
 *  of w x h, cells from `scale` px down to `min_cell` px, normalised to mean 0 and deviation 1. */
cv::Mat fractal_noise(int w, int h, double scale, double min_cell, cv::RNG &rng);

}  // namespace pft::host::tbd_ir
