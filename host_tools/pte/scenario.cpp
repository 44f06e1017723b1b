#include "scenario.hpp"

#include <algorithm>
#include <cmath>

#include "../common/json_field.hpp"

namespace pft::host::pte {

double Scenario::amplitude() const { return background.sigma * std::pow(10.0, snr_db / 20.0); }

namespace {

std::array<double, 3> vec3(const Field &f, const std::string &key, std::array<double, 3> dflt)
{
    if (!f.has(key))
        return dflt;
    auto v = f.numbers(key, 3);
    return {v[0], v[1], v[2]};
}

Motion parse_motion(const Field &t, Motion m)
{
    t.only({"motion", "start_m", "speed_mps", "turn_rate_rad_s", "phases_s", "centre_m", "radius_m",
            "rate_rad_s", "direction", "velocity_mps", "start_s", "end_s", "note"});
    std::string mk = t.choice_or("motion", "air_turn", {"air_turn", "circle", "line"});
    m.kind = mk == "air_turn" ? MotionKind::AirTurn : mk == "circle" ? MotionKind::Circle : MotionKind::Line;
    m.start = vec3(t, "start_m", m.start);
    m.speed = t.number_in("speed_mps", m.speed, 0.0, 1e5);
    m.turn_rate = t.number_in("turn_rate_rad_s", m.turn_rate, -100.0, 100.0);
    if (t.has("phases_s")) {
        auto v = t.numbers("phases_s", 3);
        for (int k = 0; k < 3; ++k) {
            if (v[k] < 0)
                t.at("phases_s").fail("durations must be >= 0");
            m.phases[k] = v[k];
        }
    }
    m.centre = vec3(t, "centre_m", m.centre);
    m.radius = t.number_in("radius_m", m.radius, 0.0, 1e7);
    m.rate = t.number_in("rate_rad_s", m.rate, -100.0, 100.0);
    m.direction = static_cast<int>(t.integer_in("direction", 1, -1, 1));
    if (m.direction == 0)
        t.at("direction").fail("must be +1 (counter-clockwise) or -1");
    m.velocity = vec3(t, "velocity_mps", m.velocity);
    m.start_s = t.number_in("start_s", 0.0, 0.0, 1e9);
    m.end_s = t.number_in("end_s", 1e300, 0.0, 1e300);
    if (m.end_s < m.start_s)
        t.at("end_s").fail("must be >= start_s");
    return m;
}

}  // namespace

Scenario parse_scenario(const nlohmann::json &j, const std::string &file)
{
    Scenario s;
    s.file = file;
    s.raw = j;
    Field root(j, file);
    root.only({"kind", "name", "description", "radar", "frames", "target", "targets", "signal", "background",
               "methods", "eval", "output", "reference"});
    if (root.string("kind") != "pte" && root.string("kind") != "radar")  // "radar": the former name
        root.at("kind").fail("expected \"pte\"");
    s.name = root.string_or("name", "");
    s.description = root.string_or("description", "");

    if (root.has("radar")) {
        Field r = root.at("radar");
        r.only({"position_m", "range_min_m", "range_res_m", "cells", "frame_period_s"});
        s.radar.position = vec3(r, "position_m", s.radar.position);
        s.radar.range_min = r.number_in("range_min_m", s.radar.range_min, 0.0, 1e9);
        s.radar.range_res = r.number_in("range_res_m", s.radar.range_res, 1e-3, 1e6);
        s.radar.cells = static_cast<int>(r.integer_in("cells", s.radar.cells, 4, 8192));
        s.radar.frame_period = r.number_in("frame_period_s", s.radar.frame_period, 1e-6, 1e3);
    }
    s.frames = static_cast<int>(root.integer_in("frames", s.frames, 1, 1000000));

    if (root.has("target") == root.has("targets"))
        root.fail("give either \"target\" (one target) or \"targets\" (a list)");
    if (root.has("target")) {
        s.motion = parse_motion(root.at("target"), s.motion);
        s.targets = {s.motion};
    } else {
        Field v = root.at("targets");
        if (v.size() < 1 || v.size() > 8)
            v.fail("expected a list of 1..8 targets");
        for (std::size_t i = 0; i < v.size(); ++i)
            s.targets.push_back(parse_motion(v.at(i), Motion{}));
        s.motion = s.targets[0];
    }

    if (root.has("signal")) {
        Field g = root.at("signal");
        g.only({"psf_sigma_cells", "snr_db"});
        s.psf_sigma = g.number_in("psf_sigma_cells", s.psf_sigma, 0.05, 100.0);
        s.snr_db = g.number_in("snr_db", s.snr_db, -60.0, 100.0);
    }
    if (root.has("background")) {
        Field b = root.at("background");
        b.only({"type", "sigma", "shape", "cnr_db", "range_corr_cells", "time_corr_frames"});
        s.background.type = b.choice_or("type", "gaussian", {"gaussian", "k_clutter"});
        s.background.sigma = b.number_in("sigma", 1.0, 1e-6, 1e6);
        s.background.shape = b.number_in("shape", 1.0, 0.5, 20.0);
        double two_nu = 2.0 * s.background.shape;
        if (std::fabs(two_nu - std::round(two_nu)) > 1e-9)
            b.at("shape").fail("2 * shape must be an integer (texture = chi-square with 2 nu dof / 2 nu)");
        s.background.cnr_db = b.number_in("cnr_db", 20.0, -40.0, 100.0);
        s.background.range_corr = b.number_in("range_corr_cells", 8.0, 0.0, 1e6);
        s.background.time_corr = b.number_in("time_corr_frames", 100.0, 0.0, 1e9);
    }
    if (root.has("methods")) {
        Field m = root.at("methods");
        m.only({"pte", "dp", "dbt", "pfa", "mc_runs", "mc_seed", "threshold_background"});
        if (m.has("pte"))
            s.methods.pte = m.at("pte").node();
        if (m.has("dp"))
            s.methods.dp = m.at("dp").node();
        if (m.has("dbt"))
            s.methods.dbt = m.at("dbt").node();
        for (const char *k : {"pte", "dp", "dbt"})
            if (m.has(k) && !m.at(k).is_object())
                m.at(k).fail("expected an object");
        s.methods.pfa = m.number_in("pfa", s.methods.pfa, 1e-6, 0.5);
        s.methods.mc_runs = static_cast<uint32_t>(m.integer_in("mc_runs", s.methods.mc_runs, 10, 10000000));
        s.methods.mc_seed = static_cast<uint64_t>(m.integer_in("mc_seed", 12345, 0, INT64_MAX));
        s.methods.threshold_background = m.choice_or("threshold_background", "", {"gaussian", "scenario"});
    }
    if (s.methods.threshold_background.empty())
        s.methods.threshold_background = s.clutter() ? "scenario" : "gaussian";
    if (root.has("eval")) {
        Field e = root.at("eval");
        e.only({"runs", "base_seed", "d_c", "snr_db", "methods", "drop_prob"});
        s.eval.drop_prob = e.number_in("drop_prob", 0.0, 0.0, 0.9);
        s.eval.runs = static_cast<unsigned>(e.integer_in("runs", 100, 1, 10000000));
        s.eval.base_seed = static_cast<uint64_t>(e.integer_in("base_seed", 1, 0, INT64_MAX));
        s.eval.d_c = e.number_in("d_c", 3.0, 1e-6, 1e6);
        if (e.has("snr_db")) {
            Field v = e.at("snr_db");
            for (std::size_t i = 0; i < v.size(); ++i)
                s.eval.snr_db.push_back(v.at(i).as_number());
        }
        if (e.has("methods")) {
            Field v = e.at("methods");
            s.eval.methods.clear();
            for (std::size_t i = 0; i < v.size(); ++i) {
                std::string n = v.at(i).as_string();
                if (n != "pte" && n != "dp" && n != "dbt")
                    v.at(i).fail("unknown method \"" + n + "\" (pte, dp, dbt)");
                s.eval.methods.push_back(n);
            }
            if (s.eval.methods.empty())
                v.fail("at least one method");
        }
    }
    if (root.has("output")) {
        Field o = root.at("output");
        o.only({"format", "gain", "offset"});
        s.output.format = o.choice_or("format", "pgm", {"pgm", "raw"});
        s.output.gain = o.number_in("gain", s.output.gain, 1e-6, 1e9);
        s.output.offset = o.number_in("offset", s.output.offset, 0.0, 65535.0);
    }
    if (root.has("reference"))
        s.reference = root.at("reference").node();
    return s;
}

std::array<double, 3> target_position(const Motion &m, double t)
{
    t = std::max(t - m.start_s, 0.0);
    std::array<double, 3> p = m.start;
    if (m.kind == MotionKind::Line) {
        for (int k = 0; k < 3; ++k)
            p[k] += m.velocity[k] * t;
        return p;
    }
    if (m.kind == MotionKind::Circle) {
        double a0 = std::atan2(m.start[1] - m.centre[1], m.start[0] - m.centre[0]);
        double a = a0 + m.direction * m.rate * t;
        return {m.centre[0] + m.radius * std::cos(a), m.centre[1] + m.radius * std::sin(a), m.start[2]};
    }
    // AirTurn: +Z, then a turn from +Z towards -Y, then straight on
    double t1 = std::min(t, m.phases[0]);
    p[2] += m.speed * t1;
    if (t <= m.phases[0])
        return p;
    double w = m.turn_rate;
    double t2 = std::min(t - m.phases[0], m.phases[1]);
    double phi = w * t2;
    if (std::fabs(w) > 1e-12) {
        p[2] += m.speed / w * std::sin(phi);
        p[1] += m.speed / w * (std::cos(phi) - 1.0);
    } else {
        p[2] += m.speed * t2;
    }
    if (t <= m.phases[0] + m.phases[1])
        return p;
    double t3 = t - m.phases[0] - m.phases[1];
    p[2] += m.speed * std::cos(phi) * t3;
    p[1] -= m.speed * std::sin(phi) * t3;
    return p;
}

double slant_range(const RadarGeom &g, const std::array<double, 3> &p)
{
    double dx = p[0] - g.position[0], dy = p[1] - g.position[1], dz = p[2] - g.position[2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double range_cells(const RadarGeom &g, double range_m) { return (range_m - g.range_min) / g.range_res; }

}  // namespace pft::host::pte
