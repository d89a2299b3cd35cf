// The output nearest a requested S (orodem render --at, orodem faults --at):
// a request beyond the run's outputs, by more than half the spacing of the
// outputs at that end, or NaN, is refused with the range there is, instead
// of silently giving the last (or first) output.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

namespace orodem {

/// The index of the value of S_values (ascending, not empty) nearest S; ConfigError (exit 2) when S is NaN or
/// lies outside [first - half the first spacing, last + half the last spacing]. `what` names the option.
inline std::size_t nearest_output(const std::vector<double>& S_values, double S, const char* what) {
    const std::size_t n = S_values.size();
    const double lo = S_values.front(), hi = S_values.back();
    const double tol_lo = n > 1 ? 0.5 * (S_values[1] - lo) : 0.5, tol_hi = n > 1 ? 0.5 * (hi - S_values[n - 2]) : 0.5;
    if (!(S >= lo - tol_lo && S <= hi + tol_hi))
        throw ConfigError(fmt::format("{} {}: the run's outputs are at S = {:.2f} to {:.2f}; choose an S in that range",
                                      what, S, lo, hi));
    std::size_t best = 0;
    for (std::size_t k = 1; k < n; ++k)
        if (std::fabs(S_values[k] - S) < std::fabs(S_values[best] - S)) best = k;
    return best;
}

}  // namespace orodem
