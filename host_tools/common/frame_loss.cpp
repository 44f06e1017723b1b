#include "frame_loss.hpp"

#include <random>

#include "errors.hpp"

namespace pft::host {

FrameLoss parse_frame_loss(const Field &e)
{
    FrameLoss l;
    l.drop_prob = e.number_in("drop_prob", 0.0, 0.0, 0.9);
    if (e.has("drop_frames")) {
        Field d = e.at("drop_frames");
        for (std::size_t i = 0; i < d.size(); ++i) {
            int64_t v = d.at(i).as_int();
            if (v < 2 || v > 1000000)
                d.at(i).fail("a 1-based frame number above 1 (the first frame is never lost)");
            l.drop_frames.push_back(static_cast<int>(v));
        }
    }
    return l;
}

std::vector<bool> lost_frame_mask(const FrameLoss &loss, int frames, uint64_t seed)
{
    std::vector<bool> lost(static_cast<std::size_t>(frames > 0 ? frames : 0), false);
    for (int d : loss.drop_frames)
        if (d >= 2 && d <= frames)
            lost[static_cast<std::size_t>(d - 1)] = true;
    if (loss.drop_prob > 0.0) {
        std::mt19937_64 gen(seed * 0x9E3779B97F4A7C15ull + 0xD1B54A32D192ED03ull);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int k = 1; k < frames; ++k)
            if (u(gen) < loss.drop_prob)
                lost[static_cast<std::size_t>(k)] = true;
    }
    return lost;
}

SimLoss sim_lost_frames(const FrameLoss &loss, int frames, uint64_t seed, const std::string &format,
                        const std::string &scenario_file)
{
    SimLoss l;
    l.mask = lost_frame_mask(loss, frames, seed);
    for (int k = 0; k < frames; ++k)
        if (l.mask[static_cast<std::size_t>(k)])
            l.numbers.push_back(k + 1);
    if (!l.numbers.empty() && format != "pgm")
        throw InputError(scenario_file + ": eval.drop_prob / eval.drop_frames lose frames, which only "
                         "one file per frame can show: use --format pgm");
    return l;
}

}  // namespace pft::host
