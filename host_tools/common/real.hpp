#pragma once
// Conversions between double (host side) and the library's pft_real_t of this build, shared by
// every host module.

#include <cmath>
#include <optional>

extern "C" {
#include "pft/pft_real.h"
}

namespace pft::host {

/** double -> pft_real_t of this build (q16: rounded to nearest, saturating). */
inline pft_real_t to_real(double v)
{
#ifdef PFT_NUMERIC_Q16
    double s = std::nearbyint(v * 65536.0);
    if (s > 2147483647.0)
        return PFT_REAL_MAX;
    if (s < -2147483647.0)
        return PFT_REAL_MIN;
    return static_cast<pft_real_t>(s);
#else
    return static_cast<pft_real_t>(v);
#endif
}

/** dst = to_real(*v) when v is set (an optional setting overriding a library default). */
inline void set_real_if(const std::optional<double> &v, pft_real_t &dst)
{
    if (v)
        dst = to_real(*v);
}

/** pft_real_t -> double. */
inline double from_real(pft_real_t v)
{
#ifdef PFT_NUMERIC_Q16
    return static_cast<double>(v) / 65536.0;
#else
    return static_cast<double>(v);
#endif
}

/** "float" or "q16". */
inline const char *numeric_name() { return PFT_NUMERIC_NAME; }

}  // namespace pft::host
