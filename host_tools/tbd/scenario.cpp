#include "scenario.hpp"

#include <cmath>
#include <set>

#include "../common/json_field.hpp"

namespace pft::host::tbd {

double Scenario::peak(double intensity) const
{
    return intensity * dx * dy / (2.0 * M_PI * psf_sigma * psf_sigma);
}

const Target *Scenario::target_by_id(int id) const
{
    for (const auto &t : targets)
        if (t.id == id)
            return &t;
    return nullptr;
}

double sigma_from_snr(double peak, double snr_db) { return peak * std::pow(10.0, -snr_db / 20.0); }
double snr_from_sigma(double peak, double sigma) { return 20.0 * std::log10(peak / sigma); }

namespace {

/** "targets": ids, lives, initial states, motion, spawning. */
void parse_targets(const Field &root, Scenario &s)
{
    Field ts = root.at("targets");
    std::set<int> ids;
    for (std::size_t i = 0; i < ts.size(); ++i) {
        Field t = ts.at(i);
        t.only({"id", "birth_frame", "death_frame", "state", "motion", "spawn_from", "note"});
        Target tg;
        tg.id = static_cast<int>(t.integer_in("id", static_cast<int64_t>(i) + 1, 1, 1000000));
        if (!ids.insert(tg.id).second)
            t.at("id").fail("duplicate target id " + std::to_string(tg.id));
        tg.birth = static_cast<int>(t.at("birth_frame").as_int());
        tg.death = static_cast<int>(t.at("death_frame").as_int());
        if (tg.birth < 1 || tg.birth > s.frames)
            t.at("birth_frame").fail("must be within 1.." + std::to_string(s.frames));
        if (tg.death < tg.birth)
            t.at("death_frame").fail("must be >= birth_frame (" + std::to_string(tg.birth) + ")");
        if (tg.death > s.frames)
            t.at("death_frame").fail("must be <= frames (" + std::to_string(s.frames) + ")");
        auto st = t.numbers("state", 5);
        for (int k = 0; k < 5; ++k)
            tg.x0[k] = st[k];
        if (tg.x0[4] <= 0.0)
            t.at("state").fail("intensity (5th element) must be positive");
        std::string mo = t.choice_or("motion", "cv", {"cv", "line"});
        tg.motion = mo == "line" ? Motion::Line : Motion::StochasticCV;
        tg.spawn_from = static_cast<int>(t.integer_in("spawn_from", 0, 0, 1000000));
        s.targets.push_back(tg);
    }
    for (std::size_t i = 0; i < s.targets.size(); ++i) {
        const Target &tg = s.targets[i];
        if (!tg.spawn_from)
            continue;
        Field f = ts.at(i).at("spawn_from");
        const Target *p = s.target_by_id(tg.spawn_from);
        if (!p)
            f.fail("no target with id " + std::to_string(tg.spawn_from));
        if (p == &tg || p >= &tg)
            f.fail("must name a target listed before this one");
        if (tg.birth < p->birth || tg.birth > p->death)
            f.fail("target " + std::to_string(p->id) + " is not present at frame " +
                   std::to_string(tg.birth));
    }

}

/** "noise": exactly one of snr_db and sigma (the other derived with the reference intensity). */
void parse_noise(const Field &root, Scenario &s)
{
    s.ref_intensity = s.targets.empty() ? 20.0 : s.targets[0].x0[4];
    {
        Field n = root.at("noise");
        n.only({"snr_db", "sigma", "ref_intensity"});
        s.ref_intensity = n.number_in("ref_intensity", s.ref_intensity, 1e-9, 1e9);
        bool has_snr = n.has("snr_db"), has_sig = n.has("sigma");
        if (has_snr == has_sig)
            n.fail("give exactly one of snr_db or sigma");
        double A = s.peak(s.ref_intensity);
        if (has_snr) {
            s.snr_db = n.number_req_in("snr_db", -40.0, 80.0);
            s.noise_sigma = sigma_from_snr(A, s.snr_db);
        } else {
            s.noise_sigma = n.number_req_in("sigma", 1e-9, 1e9);
            s.snr_db = snr_from_sigma(A, s.noise_sigma);
        }
    }

}

/** "filter": mode, kind, preset, sizes and the overrides of the preset. */
void parse_filter(const Field &f, FilterSettings &F)
{
    f.only({"mode", "kind", "preset", "particles", "track_particles", "max_targets", "pb", "pd",
            "eta", "gamma", "i_min", "i_max", "vel_mean", "vel_var", "birth_correction", "theta1",
            "dis_r", "dis_prev", "dis_ratio", "dis_ratio_test", "theta_end", "d_margin",
            "d_current", "force_constraint", "window", "kf_variant", "q1", "q2", "noise_sigma",
            "seed_offset", "d_region", "residual_search", "residual_tracks",
            "residual_margin", "end_lr_frames", "end_lr_max", "handover_gate", "birth_peaks",
            "peak_gamma", "birth_share", "confirm_frames", "seq_mode", "max_gap"});
    F.mode = f.choice_or("mode", "multi", {"multi", "single"});
    F.kind = f.choice_or("kind", "rbpf", {"rbpf", "pf"});
    F.preset = f.choice_or("preset", "paper", {"paper", "recommended", "bounded"});
    F.particles_given = f.has("particles");
    F.particles = static_cast<uint32_t>(f.integer_in("particles", 6000, 1, 4194304));
    F.track_particles = static_cast<uint32_t>(f.integer_in("track_particles", 500, 1, 4194304));
    F.max_targets = static_cast<uint32_t>(f.integer_in("max_targets", 4, 1, 1000));
    F.seed_offset = static_cast<uint64_t>(f.integer_in("seed_offset", 0, 0, INT64_MAX));
    auto num = [&](const char *k, double lo, double hi, std::optional<double> &dst) {
        if (f.has(k))
            dst = f.number_req_in(k, lo, hi);
    };
    auto integer = [&](const char *k, int lo, int hi, std::optional<int> &dst) {
        if (f.has(k))
            dst = static_cast<int>(f.integer_in(k, 0, lo, hi));
    };
    auto flag = [&](const char *k, std::optional<bool> &dst) {
        if (f.has(k))
            dst = f.at(k).as_bool();
    };
    auto pair = [&](const char *k, bool positive, std::optional<std::array<double, 2>> &dst) {
        if (!f.has(k))
            return;
        auto v = f.numbers(k, 2);
        if (positive && (v[0] <= 0 || v[1] <= 0))
            f.at(k).fail("values must be positive");
        dst = std::array<double, 2>{v[0], v[1]};
    };
    num("pb", 0.0, 1.0, F.pb);
    num("pd", 0.0, 1.0, F.pd);
    num("eta", 0.0, 1.0, F.eta);
    num("gamma", -1e4, 1e4, F.gamma);
    num("i_min", 0.0, 1e4, F.i_min);
    num("i_max", 0.0, 1e4, F.i_max);
    if (F.i_min && F.i_max && *F.i_max <= *F.i_min)
        f.at("i_max").fail("must exceed i_min");
    num("theta1", 0.0, 1.0, F.theta1);
    num("dis_ratio", 1e-6, 1.0, F.dis_ratio);
    num("theta_end", 0.0, 1.0, F.theta_end);
    num("q1", 0.0, 1e4, F.q1);
    num("q2", 0.0, 1e4, F.q2);
    num("noise_sigma", 1e-6, 1e4, F.noise_sigma);
    pair("vel_mean", false, F.vel_mean);
    pair("vel_var", true, F.vel_var);
    flag("birth_correction", F.birth_correction);
    flag("dis_ratio_test", F.dis_ratio_test);
    flag("d_current", F.d_current);
    flag("force_constraint", F.force_constraint);
    integer("dis_r", 0, 15, F.dis_r);
    integer("dis_prev", 1, 15, F.dis_prev);
    integer("d_margin", 0, 255, F.d_margin);
    integer("window", 0, 4, F.window);
    flag("residual_search", F.residual_search);
    flag("residual_tracks", F.residual_tracks);
    integer("residual_margin", 0, 8, F.residual_margin);
    integer("end_lr_frames", 0, 16, F.end_lr_frames);
    integer("handover_gate", 0, 64, F.handover_gate);
    integer("birth_peaks", 0, 4096, F.birth_peaks);  // PFT_TBD_MAX_PEAKS
    integer("confirm_frames", 0, 16, F.confirm_frames);
    num("peak_gamma", -1e4, 1e4, F.peak_gamma);
    num("birth_share", 0.0, 0.95, F.birth_share);
    num("end_lr_max", -1e4, 1e4, F.end_lr_max);
    if (f.has("d_region"))
        F.d_region = f.choice_or("d_region", "window", {"window", "pixel", "none"});
    if (f.has("kf_variant"))
        F.kf_variant = f.choice_or("kf_variant", "exact", {"exact", "paper"});
    if (f.has("seq_mode"))
        F.seq_mode = f.choice_or("seq_mode", "ignore", {"ignore", "use"});
    integer("max_gap", 1, 64, F.max_gap);  // PFT_SEQ_MAX_GAP
}

/** "eval" and "output". */
void parse_eval_output(const Field &root, Scenario &s)
{
    if (root.has("eval")) {
        Field e = root.at("eval");
        e.only({"runs", "base_seed", "d_c", "d_assoc", "gospa_c", "gospa_p", "drop_prob", "drop_frames"});
        s.eval.runs = static_cast<unsigned>(e.integer_in("runs", 100, 1, 10000000));
        s.eval.base_seed = static_cast<uint64_t>(e.integer_in("base_seed", 1, 0, INT64_MAX));
        s.eval.d_c = e.number_in("d_c", 1.0, 1e-9, 1e9);
        s.eval.d_assoc = e.number_in("d_assoc", 3.0, 1e-9, 1e9);
        s.eval.gospa_c = e.number_in("gospa_c", 0.0, 0.0, 1e9);
        s.eval.gospa_p = e.number_in("gospa_p", 2.0, 1.0, 1e6);
        s.eval.loss = parse_frame_loss(e);
    }
    if (root.has("output")) {
        Field o = root.at("output");
        o.only({"format", "gain", "offset"});
        s.output.format = o.choice_or("format", "pgm", {"pgm", "raw"});
        s.output.gain = o.number_in("gain", 256.0, 1e-6, 65535.0);
        s.output.offset = o.number_in("offset", 32768.0, 0.0, 65535.0);
    }
}

}  // namespace

Scenario parse_scenario(const nlohmann::json &j, const std::string &file)
{
    Scenario s;
    s.file = file;
    s.raw = j;
    Field root(j, file);
    root.only({"kind", "name", "description", "image", "psf_sigma", "noise", "frames", "model",
               "targets", "filter", "eval", "output", "reference"});
    if (root.string("kind") != "tbd")
        root.at("kind").fail("expected \"tbd\"");
    s.name = root.string_or("name", "");
    s.description = root.string_or("description", "");

    if (root.has("image")) {
        Field im = root.at("image");
        im.only({"width", "height", "dx", "dy"});
        s.width = static_cast<int>(im.integer_in("width", 20, 3, 8192));
        s.height = static_cast<int>(im.integer_in("height", 20, 3, 8192));
        check_frame_area(file + ": image", static_cast<std::uint64_t>(s.width),
                         static_cast<std::uint64_t>(s.height));
        s.dx = im.number_in("dx", 1.0, 1e-3, 1e3);
        s.dy = im.number_in("dy", 1.0, 1e-3, 1e3);
    }
    s.psf_sigma = root.number_in("psf_sigma", 0.7, 0.05, 100.0);
    s.frames = static_cast<int>(root.integer_in("frames", 30, 1, 1000000));

    if (root.has("model")) {
        Field m = root.at("model");
        m.only({"T", "q1", "q2"});
        s.T = m.number_in("T", 1.0, 1e-6, 1e6);
        s.q1 = m.number_in("q1", 0.005, 0.0, 1e6);
        s.q2 = m.number_in("q2", 0.01, 0.0, 1e6);
    }

    parse_targets(root, s);
    parse_noise(root, s);
    if (root.has("filter"))
        parse_filter(root.at("filter"), s.filter);
    parse_eval_output(root, s);
    if (root.has("reference"))
        s.reference = j.at("reference");
    return s;
}

}  // namespace pft::host::tbd
