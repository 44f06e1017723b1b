// Shared error type of the host tools: every bad input (file, JSON, field, option) is reported
// as an InputError with a message that names the culprit; main() prints it and exits non-zero.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace pft::host {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/** Largest frame the host tools accept (sidecars, --raw, scenarios), in pixels: 2^24, e.g.
 *  4096 x 4096 or 8192 x 2048. Checked before anything is allocated or simulated; the
 *  simulators and the overlay hold several float copies of a frame. */
constexpr std::uint64_t kMaxFramePixels = std::uint64_t(1) << 24;

/** Throws an InputError naming `where` when width x height exceeds kMaxFramePixels. */
inline void check_frame_area(const std::string &where, std::uint64_t width, std::uint64_t height)
{
    if (width * height > kMaxFramePixels)
        throw InputError(where + ": " + std::to_string(width) + " x " + std::to_string(height) +
                         " pixels per frame is more than the host tools' limit of " +
                         std::to_string(kMaxFramePixels) + " (e.g. 4096 x 4096)");
}

}  // namespace pft::host
