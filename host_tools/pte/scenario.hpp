// Radar scenario files (kind "pte", formerly "radar"): range window and frame period, target motion (the
// paper's turning air target, a circling boat, or a straight line), signal, background
// (Gaussian noise or K-distributed sea clutter), per-method settings and evaluation settings.
// Used by `pft sim|run|eval|bench|demo` for the multi-frame TBD comparison of He et al. 2015
// (PTE-TBD, DP-TBD, Kalman DBT; docs/algorithms.md 5 and 6).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace pft::host::pte {

struct RadarGeom {
    std::array<double, 3> position{0.0, 0.0, 0.0};  ///< radar position (m)
    double range_min = 103000.0;   ///< centre of cell 0 (m)
    double range_res = 20.0;       ///< cell size (m)
    int cells = 150;               ///< range cells per profile
    double frame_period = 0.1;     ///< s
};

enum class MotionKind { AirTurn, Circle, Line };

struct Motion {
    MotionKind kind = MotionKind::AirTurn;
    // AirTurn: +Z at speed for t1, coordinated turn (rate) from +Z into -Y for t2, -Y for t3
    std::array<double, 3> start{98668.0, 35912.0, 0.0};
    double speed = 200.0;          ///< m/s
    double turn_rate = 0.05 * 3.14159265358979323846;  ///< rad/s
    std::array<double, 3> phases{10.0, 10.0, 10.0};    ///< s
    // Circle: centre, radius, angular rate, sign (+1 counter-clockwise seen from above)
    std::array<double, 3> centre{41800.0, 41000.0, 0.0};
    double radius = 400.0;
    double rate = 0.2 * 3.14159265358979323846;
    int direction = 1;
    // Line: start (above) and velocity (m/s)
    std::array<double, 3> velocity{0.0, 0.0, 0.0};
    double start_s = 0.0;          ///< the target exists from this time on (its motion's t = 0)
    double end_s = 1e300;          ///< ... until this time (s)
    bool active(double t) const { return t >= start_s && t <= end_s; }
};

struct Background {
    std::string type = "gaussian";  ///< "gaussian" or "k_clutter"
    double sigma = 1.0;             ///< total noise (+clutter) standard deviation, input units
    double shape = 1.0;             ///< K-clutter texture shape nu (2 nu integer)
    double cnr_db = 20.0;           ///< clutter-to-thermal-noise ratio
    double range_corr = 8.0;        ///< texture correlation length, cells
    double time_corr = 100.0;       ///< texture correlation time, frames
};

/** Per-method overrides of the library defaults (JSON objects, fields named as in the C
 *  config structs; see methods.cpp). */
struct MethodSettings {
    nlohmann::json pte = nlohmann::json::object();
    nlohmann::json dp = nlohmann::json::object();
    nlohmann::json dbt = nlohmann::json::object();
    double pfa = 1e-3;              ///< DP / PTE initiation per-batch false-alarm probability
    uint32_t mc_runs = 20000;       ///< Monte Carlo runs (batches) of the threshold
    uint64_t mc_seed = 12345;
    /** Background of the threshold Monte Carlo: "gaussian" (the library's noise-only run,
     *  pft_pte_*threshold) or "scenario" (target-free sequences of the scenario's own
     *  background, e.g. K-clutter, through the same input stage and DP; default for clutter). */
    std::string threshold_background;
};

struct EvalSettings {
    unsigned runs = 100;
    uint64_t base_seed = 1;
    double d_c = 3.0;               ///< correct-point distance (cells)
    std::vector<double> snr_db;     ///< sweep (empty: the scenario's SNR only)
    std::vector<std::string> methods{"pte", "dp", "dbt"};
    double drop_prob = 0.0;         ///< each frame after the first is lost with this probability (per run seed)
};

struct OutputSettings {
    std::string format = "pgm";     ///< "pgm" (16-bit) or "raw" (float32)
    double gain = 2000.0;           ///< PGM: raw = offset + gain * z
    double offset = 32768.0;
};

struct Scenario {
    std::string file, name, description;
    RadarGeom radar;
    int frames = 300;
    Motion motion;                  ///< the first target (`target`, or `targets[0]`)
    std::vector<Motion> targets;    ///< every target (one for `target`)
    double psf_sigma = 0.6;         ///< cells
    double snr_db = 6.0;            ///< SNR (Gaussian) or SCNR (clutter): 20 log10(A / sigma)
    Background background;
    MethodSettings methods;
    EvalSettings eval;
    OutputSettings output;
    nlohmann::json reference;       ///< paper figures (optional)
    nlohmann::json raw;

    /** Peak amplitude A for the scenario's SNR: sigma 10^(SNR/20). */
    double amplitude() const;
    bool clutter() const { return background.type == "k_clutter"; }
};

Scenario parse_scenario(const nlohmann::json &j, const std::string &file);

/** Target position (m) at time t (s). */
/** Position at scenario time t of a target whose motion starts at m.start_s. */
std::array<double, 3> target_position(const Motion &m, double t);
/** Range (m) from the radar. */
double slant_range(const RadarGeom &g, const std::array<double, 3> &p);
/** Range in cell coordinates (cell u centred at u). */
double range_cells(const RadarGeom &g, double range_m);

}  // namespace pft::host::pte
