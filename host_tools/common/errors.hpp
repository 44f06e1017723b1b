// Shared error type of the host tools: every bad input (file, JSON, field, option) is reported
// as an InputError with a message that names the culprit; main() prints it and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace pft::host {

struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace pft::host
