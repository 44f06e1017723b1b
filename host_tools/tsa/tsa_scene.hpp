// Semi-synthetic airborne sequences for the "tsa" kind: a textured vehicle driving over a real
// aerial photograph (opencv-doc's aero1.jpg / aero3.jpg), seen by a camera that swings,
// reverses and zooms, with sensor noise and blur, and exact ground truth.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

namespace pft::host::tsa {

struct SceneSpec {
    std::string name, description;
    std::vector<std::string> backgrounds{"aero1.jpg", "aero3.jpg"};  ///< run i uses [i % n]
    int width = 640, height = 480, frames = 250;
    double world_scale = 2.0;       ///< background upscaled by this to make the ground plane
    // target (ground vehicle), sizes in image pixels at zoom 1
    double target_w = 25, target_h = 30;
    double speed = 0.5;             ///< ground speed, image px/frame at zoom 1
    double heading_deg = -90;       ///< direction of travel (image axes, -90 = up)
    int accel_frame = -1;           ///< sudden acceleration starts here (-1: none)
    int accel_frames = 20;          ///< ... and lasts this many frames
    double accel = 0;               ///< px/frame^2 along the heading
    // camera
    /// "legs": constant-speed legs of equal length, the swing speed flipping sign at each of the
    /// `reversals` instants (the first scenarios); "sine": a sinusoidal swing of amplitude
    /// swing_amplitude (speed swing_speed at the centre, gentle turns at the ends) with
    /// `reversals` sudden reversals mid-swing (the direction flips where the speed is above
    /// 0.7 swing_speed); in both the speed changes by at most swing_accel per frame
    std::string profile = "legs";
    double swing_speed = 12;        ///< max swing speed, image px/frame (x)
    int reversals = 9;              ///< direction reversals of the swing over the sequence
    double swing_accel = 2.0;       ///< max swing acceleration, px/frame^2
    double swing_amplitude = 200;   ///< "sine": half the x excursion of the swing, px
    double swing_y = 0.15;          ///< y swing as a fraction of the x swing
    double jitter = 0.4;            ///< camera vibration, px (sd per frame)
    double zoom = 0.1;              ///< relative zoom amplitude (1 +- zoom over the sequence)
    double rotation_deg = 0;        ///< camera roll amplitude, degrees (sinusoid, two periods)
    // sensor
    double noise_sigma = 4;         ///< additive Gaussian noise, grey levels
    double blur_sigma = 0.7;        ///< Gaussian blur, px (0: none)
    /// motion blur along the apparent motion: exposure as a fraction of the frame time (the
    /// blur length is exposure x the image speed of the ground; 0: none)
    double motion_blur = 0;
    double gain_flicker = 0;        ///< per-frame gain 1 + N(0, gain_flicker^2), clamped to [0.5, 1.5]
    // forced loss: frames [blank_frame, blank_frame + blank_frames) are blank (mid grey and noise)
    int blank_frame = -1;
    int blank_frames = 0;
    uint64_t seed_base = 1;

    bool blank(int k) const { return blank_frame >= 0 && k >= blank_frame && k < blank_frame + blank_frames; }
};

struct TruthRow {
    int frame;
    double cx, cy;                  ///< target centre in the image
    cv::Rect2d box;                 ///< axis-aligned box of the target in the image
    double cam_vx;                  ///< camera swing velocity (px/frame), for plots
    double gain = 1.0;              ///< the frame's sensor gain (gain flicker; 1 without it)
    double blur_px = 0.0;           ///< length of the frame's motion blur, px (0 without it)
    bool reversal = false;          ///< a sudden reversal of the swing was taken at this frame
};

SceneSpec parse_scene(const nlohmann::json &j, const std::string &file);
nlohmann::json scene_to_json(const SceneSpec &s);

/** Finds a data file shipped by opencv-doc (plain or .gz, decompressed to a temp dir) or given
 *  as a path; InputError naming the places searched. */
std::string find_data_file(const std::string &name);

/** Renders the whole sequence of run `seed` (BGR frames) and its truth. */
void render_sequence(const SceneSpec &s, uint64_t seed, std::vector<cv::Mat> &frames,
                     std::vector<TruthRow> &truth, int max_frames = -1);

}  // namespace pft::host::tsa
