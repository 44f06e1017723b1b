// Where `pft` finds its shipped scenarios (host_tools/scenarios, installed to
// share/pftrack/scenarios).
#pragma once
#include <string>

namespace pft::host {

/** The shipped scenario file `relative` (e.g. "tbd/two_case1.json"): under
 *  <dir of the pft executable>/../share/pftrack/scenarios when `pft` runs installed (the path
 *  from bin to share comes from the build's install directories), else in the source tree
 *  the executable was built from. */
std::string scenario_file(const std::string &relative);

}  // namespace pft::host
