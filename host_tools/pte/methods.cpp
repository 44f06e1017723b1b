#include "methods.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <cstring>
#include <map>
#include <mutex>

#include "../common/errors.hpp"
#include "../common/json_field.hpp"
#include "sim.hpp"

namespace pft::host::pte {


std::string method_label(const std::string &name)
{
    if (name == "pte")
        return "PTE-TBD";
    if (name == "dp")
        return "DP-TBD";
    if (name == "dbt")
        return "Kalman DBT";
    return name;
}

namespace {

void input_from(const Scenario &s, pft_pte_input_t &in)
{
    pft_pte_input_default(&in);
    in.n_range = static_cast<uint16_t>(s.radar.cells);
    in.n_doppler = 1;
    in.noise_sigma = to_real(s.background.sigma);
    if (s.clutter()) {
        in.noise = PFT_PTE_NOISE_CFAR;
        in.noise_sigma = to_real(0.05 * s.background.sigma);  // floor of the CFAR estimate
        in.cfar_ref = 8;  // 8 cells per side: about the texture correlation length [A]
    }
}

/** Input-stage overrides shared by the three methods. */
void input_override(const Field &f, pft_pte_input_t &in)
{
    if (f.has("noise"))
        in.noise = f.choice_or("noise", "fixed", {"fixed", "cfar"}) == "cfar" ? PFT_PTE_NOISE_CFAR
                                                                              : PFT_PTE_NOISE_FIXED;
    if (f.has("noise_sigma"))
        in.noise_sigma = to_real(f.number_in("noise_sigma", 1.0, 1e-6, 1e4));
    if (f.has("cfar_ref"))
        in.cfar_ref = static_cast<uint8_t>(f.integer_in("cfar_ref", 16, 1, PFT_PTE_MAX_CFAR_REF));
    if (f.has("cfar_guard"))
        in.cfar_guard = static_cast<uint8_t>(f.integer_in("cfar_guard", 2, 0, 64));
    if (f.has("zeta_clip"))
        in.zeta_clip = to_real(f.number_in("zeta_clip", 20.0, 0.1, 1000.0));
    if (f.has("seq_mode"))
        in.seq_mode = f.choice_or("seq_mode", "ignore", {"ignore", "use"}) == "use" ? PFT_SEQ_USE : PFT_SEQ_IGNORE;
    if (f.has("max_gap"))
        in.max_gap = static_cast<uint16_t>(f.integer_in("max_gap", PFT_SEQ_DEFAULT_GAP, 1, PFT_SEQ_MAX_GAP));
}

uint8_t u8(const Field &f, const char *k, int64_t d, int64_t lo, int64_t hi)
{
    return static_cast<uint8_t>(f.integer_in(k, d, lo, hi));
}
void real(const Field &f, const char *k, pft_real_t &v, double lo, double hi)
{
    if (f.has(k))
        v = to_real(f.number_in(k, 0.0, lo, hi));
}
void real2(const Field &f, const char *k, pft_real_t v[2], double lo, double hi)
{
    if (!f.has(k))
        return;
    if (f.at(k).is_array()) {
        auto a = f.numbers(k, 2);
        for (int i = 0; i < 2; ++i) {
            if (a[i] < lo || a[i] > hi)
                f.at(k).fail("values must be within [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
            v[i] = to_real(a[i]);
        }
    } else {
        v[0] = v[1] = to_real(f.number_in(k, 0.0, lo, hi));
    }
}
void int2(const Field &f, const char *k, uint8_t v[2], int64_t lo, int64_t hi)
{
    if (!f.has(k))
        return;
    if (f.at(k).is_array()) {
        Field a = f.at(k);
        if (a.size() != 2)
            a.fail("expected 2 integers");
        for (std::size_t i = 0; i < 2; ++i) {
            int64_t x = a.at(i).as_int();
            if (x < lo || x > hi)
                a.at(i).fail("out of range");
            v[i] = static_cast<uint8_t>(x);
        }
    } else {
        v[0] = v[1] = static_cast<uint8_t>(f.integer_in(k, 0, lo, hi));
    }
}

std::mutex g_mc_mu;
std::map<std::string, double> g_mc_cache;

template <class Cfg>
std::string cfg_key(const std::string &name, const Cfg &c, const Scenario &s)
{
    std::string k = name + "|" + std::to_string(s.methods.pfa) + "|" + std::to_string(s.methods.mc_runs) +
                    "|" + std::to_string(s.methods.mc_seed) + "|" + s.methods.threshold_background + "|";
    k.append(reinterpret_cast<const char *>(&c), sizeof(Cfg));
    if (s.methods.threshold_background == "scenario")
        k += s.raw.dump();
    return k;
}

/** Threshold of a K-frame DP (input stage `in`, gate) from target-free sequences of the
 *  scenario's own background: the best merit of `batches` disjoint batches, of which a
 *  fraction pfa exceed the returned value. */
double scenario_threshold(const Scenario &s, const pft_pte_input_t &in, uint8_t k, const uint8_t gate[2])
{
    pft_pte_dp_config_t c;
    pft_pte_dp_config_default(&c);
    c.in = in;
    c.frames = k;
    c.gate[0] = gate[0];
    c.gate[1] = gate[1];
    c.threshold = PFT_REAL_MAX;
    c.max_targets = 1;
    std::vector<uint64_t> w(pft_pte_dp_workspace_size(&c) / 8 + 1);
    pft_pte_dp_t dp;
    if (pft_pte_dp_init(&dp, &c, w.data(), w.size() * 8) != PFT_OK)
        throw InputError("threshold Monte Carlo: DP configuration refused");
    Scenario bg = s;
    bg.snr_db = -400.0;  // target amplitude ~ 1e-20: background only
    const int chunk = 1000 / k * k;
    std::vector<double> peaks;
    peaks.reserve(s.methods.mc_runs);
    uint64_t seed = s.methods.mc_seed;
    std::vector<pft_real_t> z(in.n_range);
    while (peaks.size() < s.methods.mc_runs) {
        Sequence q = simulate(bg, seed++, chunk);
        pft_pte_dp_reset(&dp);
        for (int f = 0; f < q.frames && peaks.size() < s.methods.mc_runs; ++f) {
            for (int u = 0; u < q.cells; ++u)
                z[u] = to_real(q.z[f][u]);
            pft_pte_dp_update_real(&dp, z.data());
            pft_real_t peak = PFT_REAL_MIN;
            if ((f + 1) % k == 0 && pft_pte_dp_peak(&dp, &peak) == PFT_OK)
                peaks.push_back(from_real(peak));
        }
    }
    std::sort(peaks.begin(), peaks.end(), std::greater<double>());
    std::size_t i = static_cast<std::size_t>(std::floor(s.methods.pfa * peaks.size()));
    return peaks[std::min(i, peaks.size() - 1)];
}

}  // namespace

MethodSpec make_spec(const Scenario &s, const std::string &name)
{
    MethodSpec m;
    m.name = name;
    if (name == "pte") {
        pft_pte_config_default(&m.pte);
        input_from(s, m.pte.in);
        m.pte.op = PFT_PTE_OP_TABLE;  // what AUTO selects for the range-time frames simulated here
        Field f(s.methods.pte, s.file, "methods.pte");
        f.only({"noise", "noise_sigma", "cfar_ref", "cfar_guard", "zeta_clip", "seq_mode", "max_gap", "init_frames", "init_gate",
                "init_threshold", "init_period", "init_spread", "max_len", "n_dir", "motion", "sigma_r", "q_sd", "acc_sd0",
                "q_amp", "dtheta_min", "c_step", "scan_steps", "scan_sigmas", "sigma_w_max", "eta_t",
                "max_misses", "max_tracks", "dup_cells", "op", "short_len", "man_z", "man_acc_sd", "step_budget",
                "line_budget", "steady_dirs", "slope_hold"});
        input_override(f, m.pte.in);
        pft_pte_config_t &c = m.pte;
        c.init_frames = u8(f, "init_frames", c.init_frames, 2, PFT_PTE_MAX_FRAMES);
        int2(f, "init_gate", c.init_gate, 0, PFT_PTE_MAX_GATE);
        c.init_period = u8(f, "init_period", c.init_period, 1, 255);
        c.init_spread = u8(f, "init_spread", c.init_spread, 0, 255);
        c.max_len = u8(f, "max_len", c.max_len, 2, PFT_PTE_MAX_FRAMES);
        int2(f, "n_dir", c.n_dir, 1, PFT_PTE_MAX_DIRS);
        if (f.has("motion"))
            c.motion = f.choice_or("motion", "ca", {"cv", "ca"}) == "cv" ? PFT_PTE_MOTION_CV : PFT_PTE_MOTION_CA;
        if (f.has("op"))
            c.op = f.choice_or("op", "table", {"exact", "table"}) == "exact" ? PFT_PTE_OP_EXACT : PFT_PTE_OP_TABLE;
        real2(f, "sigma_r", c.sigma_r, 1e-3, 100);
        real2(f, "q_sd", c.q_sd, 0, 1);
        real2(f, "acc_sd0", c.acc_sd0, 0, 0.1);
        real(f, "q_amp", c.q_amp, 0, 100);
        real(f, "dtheta_min", c.dtheta_min, 1e-4, 10);
        real(f, "c_step", c.c_step, 0.01, 4);
        c.scan_steps = u8(f, "scan_steps", c.scan_steps, 1, PFT_PTE_MAX_SCAN_STEPS);
        real(f, "scan_sigmas", c.scan_sigmas, 0.1, 100);
        real(f, "sigma_w_max", c.sigma_w_max, 0.05, 14.0 / 6.0);
        real(f, "eta_t", c.eta_t, -100, 150);
        c.max_misses = u8(f, "max_misses", c.max_misses, 1, 255);
        c.max_tracks = u8(f, "max_tracks", c.max_tracks, 1, PFT_PTE_MAX_TRACKS);
        real(f, "dup_cells", c.dup_cells, 0, 1000);
        c.short_len = u8(f, "short_len", c.short_len, 0, PFT_PTE_MAX_FRAMES);
        real(f, "man_z", c.man_z, 1e-3, 100);
        real(f, "man_acc_sd", c.man_acc_sd, 0, 0.1);
        c.step_budget = u8(f, "step_budget", c.step_budget, 0, PFT_PTE_MAX_TRACKS);
        c.line_budget = static_cast<uint16_t>(f.integer_in("line_budget", c.line_budget, 0, 65535));
        c.steady_dirs = u8(f, "steady_dirs", c.steady_dirs, 0, PFT_PTE_MAX_DIRS);
        real(f, "slope_hold", c.slope_hold, 0, 0.5);
        if (const char *bad = nullptr; pft_pte_config_check(&c, &bad) != PFT_OK)
            f.fail(std::string("invalid PTE-TBD configuration: ") + (bad ? bad : "?") + " (pft_pte_config_check)");
        if (f.has("init_threshold")) {
            c.init_threshold = to_real(f.number_in("init_threshold", 0, -1e4, 1e4));
        } else {
            std::string key = cfg_key("pte", c, s);
            std::lock_guard<std::mutex> lk(g_mc_mu);
            auto it = g_mc_cache.find(key);
            if (it == g_mc_cache.end()) {
                double v;
                if (s.methods.threshold_background == "scenario") {
                    v = scenario_threshold(s, c.in, c.init_frames, c.init_gate);
                } else {
                    std::vector<uint64_t> w(pft_pte_workspace_size(&c) / 8 + 1);
                    pft_pte_t p;
                    pft_real_t vt = 0;
                    if (pft_pte_init(&p, &c, w.data(), w.size() * 8) != PFT_OK ||
                        pft_pte_threshold(&p, to_real(s.methods.pfa), s.methods.mc_runs, s.methods.mc_seed,
                                                &vt) != PFT_OK)
                        throw InputError("PTE-TBD initiation threshold Monte Carlo refused (pfa * mc_runs must be < 64)");
                    v = from_real(vt);
                }
                it = g_mc_cache.emplace(key, v).first;
            }
            c.init_threshold = to_real(it->second);
            m.threshold_from_mc = true;
        }
        m.threshold = from_real(c.init_threshold);
    } else if (name == "dp") {
        pft_pte_dp_config_default(&m.dp);
        input_from(s, m.dp.in);
        Field f(s.methods.dp, s.file, "methods.dp");
        f.only({"noise", "noise_sigma", "cfar_ref", "cfar_guard", "zeta_clip", "seq_mode", "max_gap", "frames", "gate", "amplitude",
                "threshold", "max_targets", "cancel"});
        input_override(f, m.dp.in);
        pft_pte_dp_config_t &c = m.dp;
        c.frames = u8(f, "frames", c.frames, 2, PFT_PTE_MAX_FRAMES);
        int2(f, "gate", c.gate, 0, PFT_PTE_MAX_GATE);
        real(f, "amplitude", c.amplitude, 0, 100);
        c.max_targets = u8(f, "max_targets", c.max_targets, 1, PFT_PTE_MAX_TRACKS);
        c.cancel = u8(f, "cancel", c.cancel, 0, 255);
        if (const char *bad = nullptr; pft_pte_dp_config_check(&c, &bad) != PFT_OK)
            f.fail(std::string("invalid DP-TBD configuration: ") + (bad ? bad : "?") + " (pft_pte_dp_config_check)");
        if (f.has("threshold")) {
            c.threshold = to_real(f.number_in("threshold", 0, -1e4, 1e4));
        } else {
            std::string key = cfg_key("dp", c, s);
            std::lock_guard<std::mutex> lk(g_mc_mu);
            auto it = g_mc_cache.find(key);
            if (it == g_mc_cache.end()) {
                double v;
                if (s.methods.threshold_background == "scenario") {
                    v = scenario_threshold(s, c.in, c.frames, c.gate);
                } else {
                    std::vector<uint64_t> w(pft_pte_dp_workspace_size(&c) / 8 + 1);
                    pft_pte_dp_t d;
                    pft_real_t vt = 0;
                    if (pft_pte_dp_init(&d, &c, w.data(), w.size() * 8) != PFT_OK ||
                        pft_pte_dp_threshold(&d, to_real(s.methods.pfa), s.methods.mc_runs, s.methods.mc_seed,
                                               &vt) != PFT_OK)
                        throw InputError("DP-TBD threshold Monte Carlo refused (pfa * mc_runs must be < 64)");
                    v = from_real(vt);
                }
                it = g_mc_cache.emplace(key, v).first;
            }
            c.threshold = to_real(it->second);
            m.threshold_from_mc = true;
        }
        m.threshold = from_real(c.threshold);
    } else if (name == "dbt") {
        pft_pte_dbt_config_default(&m.dbt);
        input_from(s, m.dbt.in);
        m.dbt.gate = PFT_PTE_DBT_GATE_1AXIS;  // what gate 0 selects for range-time frames
        Field f(s.methods.dbt, s.file, "methods.dbt");
        f.only({"noise", "noise_sigma", "cfar_ref", "cfar_guard", "zeta_clip", "seq_mode", "max_gap", "threshold", "sigma_r", "q",
                "vel_var0", "gate", "confirm_m", "confirm_n", "max_misses", "max_tracks", "max_dets"});
        input_override(f, m.dbt.in);
        pft_pte_dbt_config_t &c = m.dbt;
        real(f, "threshold", c.threshold, -100, 1000);
        real2(f, "sigma_r", c.sigma_r, 1e-3, 100);
        real2(f, "q", c.q, 0, 100);
        real2(f, "vel_var0", c.vel_var0, 1e-6, 100);
        real(f, "gate", c.gate, 1e-3, 1e4);
        c.confirm_m = u8(f, "confirm_m", c.confirm_m, 1, 8);
        c.confirm_n = u8(f, "confirm_n", c.confirm_n, 1, 8);
        c.max_misses = u8(f, "max_misses", c.max_misses, 1, 255);
        c.max_tracks = u8(f, "max_tracks", c.max_tracks, 1, PFT_PTE_DBT_MAX_TRACKS);
        c.max_dets = static_cast<uint16_t>(f.integer_in("max_dets", c.max_dets, 1, PFT_PTE_DBT_MAX_DETS));
        if (const char *bad = nullptr; pft_pte_dbt_config_check(&c, &bad) != PFT_OK)
            f.fail(std::string("invalid DBT configuration: ") + (bad ? bad : "?") + " (pft_pte_dbt_config_check)");
        m.threshold = from_real(c.threshold);
    } else {
        throw InputError("unknown method \"" + name + "\" (pte, dp, dbt)");
    }
    return m;
}

namespace {
nlohmann::json input_json(const pft_pte_input_t &in)
{
    return {{"n_range", in.n_range}, {"n_doppler", in.n_doppler},
            {"noise", in.noise == PFT_PTE_NOISE_CFAR ? "cfar" : "fixed"},
            {"noise_sigma", from_real(in.noise_sigma)}, {"cfar_ref", in.cfar_ref},
            {"cfar_guard", in.cfar_guard}, {"zeta_clip", from_real(in.zeta_clip)},
            {"seq_mode", in.seq_mode == PFT_SEQ_USE ? "use" : "ignore"}, {"max_gap", in.max_gap}};
}
nlohmann::json pair(const pft_real_t v[2]) { return {from_real(v[0]), from_real(v[1])}; }
}  // namespace

std::string MethodSpec::label() const
{
    if (name == "pte")
        return "PTE-TBD M=" + std::to_string(pte.max_len) +
               (pte.short_len > 0 ? " Ms=" + std::to_string(pte.short_len) : std::string());
    if (name == "dp")
        return "DP-TBD K=" + std::to_string(dp.frames);
    return method_label(name);
}

nlohmann::json MethodSpec::settings() const
{
    nlohmann::json j;
    if (name == "pte") {
        const auto &c = pte;
        j = {{"input", input_json(c.in)}, {"init_frames", c.init_frames},
             {"init_gate", {c.init_gate[0], c.init_gate[1]}}, {"init_threshold", from_real(c.init_threshold)},
             {"init_period", c.init_period}, {"init_spread", c.init_spread}, {"max_len", c.max_len}, {"n_dir", {c.n_dir[0], c.n_dir[1]}},
             {"motion", c.motion == PFT_PTE_MOTION_CA ? "ca" : "cv"},
             {"op", c.op == PFT_PTE_OP_TABLE ? "table" : "exact"},
             {"sigma_r", pair(c.sigma_r)}, {"q_sd", pair(c.q_sd)}, {"acc_sd0", pair(c.acc_sd0)},
             {"q_amp", from_real(c.q_amp)},
             {"dtheta_min", from_real(c.dtheta_min)}, {"c_step", from_real(c.c_step)},
             {"scan_steps", c.scan_steps}, {"scan_sigmas", from_real(c.scan_sigmas)},
             {"sigma_w_max", from_real(c.sigma_w_max)}, {"eta_t", from_real(c.eta_t)},
             {"max_misses", c.max_misses}, {"max_tracks", c.max_tracks}, {"dup_cells", from_real(c.dup_cells)},
             {"short_len", c.short_len}, {"man_z", from_real(c.man_z)},
             {"man_acc_sd", from_real(c.man_acc_sd)}, {"step_budget", c.step_budget},
             {"line_budget", c.line_budget}, {"steady_dirs", c.steady_dirs},
             {"slope_hold", from_real(c.slope_hold)}};
    } else if (name == "dp") {
        const auto &c = dp;
        j = {{"input", input_json(c.in)}, {"frames", c.frames}, {"gate", {c.gate[0], c.gate[1]}},
             {"amplitude", from_real(c.amplitude)}, {"threshold", from_real(c.threshold)},
             {"max_targets", c.max_targets}, {"cancel", c.cancel}};
    } else {
        const auto &c = dbt;
        j = {{"input", input_json(c.in)}, {"threshold", from_real(c.threshold)}, {"sigma_r", pair(c.sigma_r)},
             {"q", pair(c.q)}, {"vel_var0", pair(c.vel_var0)}, {"gate", from_real(c.gate)},
             {"confirm_m", c.confirm_m}, {"confirm_n", c.confirm_n}, {"max_misses", c.max_misses},
             {"max_tracks", c.max_tracks}, {"max_dets", c.max_dets}};
    }
    j["threshold_from_monte_carlo"] = threshold_from_mc;
    return j;
}

Method::Method(const MethodSpec &spec) : spec_(spec)
{
    pft_status_t st;
    if (spec.name == "pte") {
        ws_bytes_ = pft_pte_workspace_size(&spec.pte);
        work_.assign(ws_bytes_ / 8 + 1, 0);
        st = pft_pte_init(&pte_, &spec.pte, work_.data(), work_.size() * 8);
    } else if (spec.name == "dp") {
        ws_bytes_ = pft_pte_dp_workspace_size(&spec.dp);
        work_.assign(ws_bytes_ / 8 + 1, 0);
        st = pft_pte_dp_init(&dp_, &spec.dp, work_.data(), work_.size() * 8);
    } else {
        ws_bytes_ = pft_pte_dbt_workspace_size(&spec.dbt);
        work_.assign(ws_bytes_ / 8 + 1, 0);
        st = pft_pte_dbt_init(&dbt_, &spec.dbt, work_.data(), work_.size() * 8);
    }
    if (st != PFT_OK)
        throw InputError(method_label(spec.name) + ": init refused (" + pft_status_str(st) + ")");
}

const std::vector<Report> &Method::update(const float *z, uint32_t seq)
{
    pft_frame_t f{};
    f.data = z;
    f.format = PFT_PIX_F32;
    f.seq = seq;
    std::size_t n = 0;
    pft_status_t st;
    rep_.resize(PFT_PTE_DBT_MAX_TRACKS > PFT_PTE_MAX_TRACKS ? PFT_PTE_DBT_MAX_TRACKS : PFT_PTE_MAX_TRACKS);
    if (spec_.name == "pte") {
        f.width = spec_.pte.in.n_range;
        f.height = 1;
        f.stride_bytes = f.width * 4u;
        st = pft_pte_update(&pte_, &f);
        n = pft_pte_reports(&pte_, rep_.data(), rep_.size());
    } else if (spec_.name == "dp") {
        f.width = spec_.dp.in.n_range;
        f.height = 1;
        f.stride_bytes = f.width * 4u;
        st = pft_pte_dp_update(&dp_, &f);
        n = pft_pte_dp_reports(&dp_, rep_.data(), rep_.size());
    } else {
        f.width = spec_.dbt.in.n_range;
        f.height = 1;
        f.stride_bytes = f.width * 4u;
        st = pft_pte_dbt_update(&dbt_, &f);
        n = pft_pte_dbt_reports(&dbt_, rep_.data(), rep_.size());
    }
    if (st != PFT_OK)
        throw InputError(method_label(spec_.name) + ": frame refused (" + pft_status_str(st) + ")");
    n = std::min(n, rep_.size());
    out_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const pft_pte_report_t &r = rep_[i];
        Report &o = out_[i];
        o.id = r.id;
        o.detected = r.detected;
        o.pos = from_real(r.pos[0]);
        o.vel = from_real(r.vel[0]);
        o.var = from_real(r.var[0]);
        o.amplitude = from_real(r.amplitude);
        o.score = from_real(r.score);
        o.age = r.age;
    }
    return out_;
}

}  // namespace pft::host::pte
