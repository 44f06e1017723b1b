// TBD scenario files (kind "tbd"): image, PSF, noise, frames, targets with birth/death,
// initial state and motion, filter settings, evaluation settings. See docs/host_tools.md.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/frame_loss.hpp"

namespace pft::host::tbd {

enum class Motion { StochasticCV, Line };

struct Target {
    int id = 0;
    int birth = 1;                    ///< first frame present (1-based, inclusive)
    int death = 1;                    ///< last frame present (inclusive)
    std::array<double, 5> x0{};       ///< state at the birth frame: x, vx, y, vy, I
    Motion motion = Motion::StochasticCV;
    int spawn_from = 0;               ///< id of a target whose true position at `birth` replaces x0's position
};

/** Filter settings: the library's defaults of the chosen preset (pft_tbd_config_default for
 *  "paper", pft_tbd_config_recommended for "recommended", pft_tbd_config_bounded for "bounded"),
 *  then every field the file gives. */
struct FilterSettings {
    std::string mode = "multi";       ///< "multi" (two-layer manager) or "single" (one filter)
    std::string kind = "rbpf";        ///< "rbpf" or "pf"
    std::string preset = "paper";     ///< "paper", "recommended" or "bounded" (library defaults to start from)
    uint32_t particles = 6000;        ///< search layer (multi) or the single filter
    bool particles_given = false;     ///< the file gave "particles" (else the preset's n_search)
    uint32_t track_particles = 500;   ///< per track layer (multi)
    uint32_t max_targets = 4;
    uint64_t seed_offset = 0;         ///< filter seed = run seed + seed_offset
    // overrides of the preset (absent: the library's value)
    std::optional<double> pb, pd, eta, gamma, i_min, i_max, theta1, dis_ratio, theta_end, end_lr_max, peak_gamma, birth_share;
    std::optional<double> q1, q2, noise_sigma;  ///< model mismatch studies (absent: the scenario's)
    std::optional<std::array<double, 2>> vel_mean, vel_var;
    std::optional<bool> birth_correction, dis_ratio_test, d_current, force_constraint;
    std::optional<bool> residual_search, residual_tracks;
    std::optional<int> dis_r, dis_prev, d_margin, window, residual_margin, end_lr_frames, handover_gate;
    std::optional<int> birth_peaks, confirm_frames;
    std::optional<std::string> d_region;  ///< "window" | "pixel" | "none"
    std::optional<std::string> kf_variant;
    std::optional<std::string> seq_mode;  ///< "ignore" | "use": frame sequence numbers (docs/design.md)
    std::optional<int> max_gap;
};

struct EvalSettings {
    unsigned runs = 100;
    uint64_t base_seed = 1;
    double d_c = 1.0;                 ///< correct-point distance (pixels)
    double d_assoc = 3.0;             ///< track-to-target association gate (pixels)
    double gospa_c = 0.0;             ///< GOSPA/OSPA cut-off (pixels; 0: d_assoc)
    double gospa_p = 2.0;             ///< GOSPA/OSPA order
    FrameLoss loss;                   ///< drop_prob, drop_frames: frames lost in a run (common/frame_loss.hpp)
};

struct OutputSettings {
    std::string format = "pgm";       ///< "pgm" (16-bit) or "raw" (float32)
    double gain = 256.0;              ///< PGM: raw = offset + gain * z
    double offset = 32768.0;
};

struct Scenario {
    std::string file, name, description;
    int width = 20, height = 20;
    double dx = 1.0, dy = 1.0;
    double psf_sigma = 0.7;
    double snr_db = 6.0;              ///< derived from sigma when the file gives sigma
    double noise_sigma = 0.0;
    double ref_intensity = 20.0;
    int frames = 30;
    double T = 1.0, q1 = 0.005, q2 = 0.01;
    std::vector<Target> targets;
    FilterSettings filter;
    EvalSettings eval;
    OutputSettings output;
    nlohmann::json reference;         ///< paper figures to print beside ours (optional)
    nlohmann::json raw;               ///< the file as read

    /** Peak pixel amplitude A = I dx dy / (2 pi Sigma^2) for intensity I. */
    double peak(double intensity) const;
    const Target *target_by_id(int id) const;
};

/** Parses and validates; InputError naming the bad field. */
Scenario parse_scenario(const nlohmann::json &j, const std::string &file);

/** sigma = A 10^(-SNR/20) */
double sigma_from_snr(double peak, double snr_db);
double snr_from_sigma(double peak, double sigma);

}  // namespace pft::host::tbd
