#include "scenario_dir.hpp"

#include <filesystem>
#include <system_error>

#ifndef PFT_HOST_SCENARIO_DIR
#define PFT_HOST_SCENARIO_DIR ""
#endif
#ifndef PFT_HOST_SCENARIO_RELDIR
#define PFT_HOST_SCENARIO_RELDIR "../share/pftrack/scenarios"
#endif

namespace fs = std::filesystem;

namespace pft::host {

std::string scenario_file(const std::string &relative)
{
    std::error_code ec;
    const fs::path exe = fs::canonical("/proc/self/exe", ec);
    if (!ec) {
        const fs::path installed = exe.parent_path() / PFT_HOST_SCENARIO_RELDIR / relative;
        if (fs::is_regular_file(installed, ec))
            return installed.lexically_normal().string();
    }
    return (fs::path(PFT_HOST_SCENARIO_DIR) / relative).string();
}

}  // namespace pft::host
