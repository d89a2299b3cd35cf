// Health checks of a running simulation (RELIABILITY-CHECKLIST 1, 2, 5): a
// non-finite position or velocity, an overlap beyond a fraction of the
// smaller radius, a speed beyond a bound, a disc outside the domain. One O(N)
// pass over the discs plus one over the candidate pairs; cheap enough to run
// every 1000 steps. The run loop turns a problem into InstabilityError (exit 3).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "orodem/core/vec2.hpp"

namespace orodem {

class Simulation;

struct HealthLimits {
    double max_overlap_ratio = 0.5;  // δ / min(R_i, R_j) [-]
    double max_speed = 0.0;          // |v| [m/s]; 0 = no check
    double x_min = -1e300, x_max = 1e300;  // domain box [m]
    double y_min = -1e300, y_max = 1e300;
};

struct HealthProblem {
    std::string what;     // "non-finite velocity", "overlap", "speed", "left the domain"
    std::uint32_t id = 0; // the disc (for an overlap, the first of the pair)
    Vec2 x;               // its position [m]
    std::string detail;   // numbers: the value and the limit, the partner disc
    std::string advice;   // the likely cause and what to change
};

/// The first problem found (in id order within each check), or none.
std::optional<HealthProblem> check_health(const Simulation& sim, const HealthLimits& lim);

/// Overlaps of the unbonded candidate pairs (RELIABILITY-CHECKLIST 2, 4): how
/// many touch, how many exceed `threshold` (δ / min(R_i, R_j)), and the worst.
struct OverlapSummary {
    std::size_t touching = 0;     // pairs with δ > 0
    std::size_t above = 0;        // pairs with δ / min(R_i, R_j) > threshold
    double worst = 0.0;           // largest δ / min(R_i, R_j) [-]
    std::uint32_t id_i = 0, id_j = 0;  // the worst pair (ids)
    Vec2 x_i, x_j;                // their positions [m]
};
OverlapSummary overlap_summary(const Simulation& sim, double threshold);

}  // namespace orodem
