// The force transmitted across a vertical section x = x_c of the layer
// (issue "findings", stage 1 at low μ_bp): the resultant of the pair forces
// (contacts and cluster bonds) that the discs with centres at x < x_c exert
// on those at x ≥ x_c. For a plate carried in +x against a wedge it is the
// push the plate delivers through that section, to be compared with the
// layer's passive (Rankine) strength ½ K_p ρ_b g h0² (docs/validation.md).
//
// Pairs are read as the last step left them: force on i in f[k], force on j
// −f[k] (Newton's third law). Sleeping pairs keep the force of their last
// evaluation (engine/sleep.cpp); the wedge runs take the section 1 h0 ahead
// of the prowedge toe, inside the awake region. Sequential over pairs in
// their order, so the sum does not depend on the thread count. Read-only.
#pragma once

#include "orodem/core/vec2.hpp"
#include "orodem/state/contacts.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// Σ over pairs with one disc on each side of x = x_c of the force on the
/// disc at x ≥ x_c [N per metre of depth]; a periodic partner is taken at
/// its image x_j + shift W.
Vec2 section_force(const ParticleStore& p, const ContactStore& c, double x_c, double period_x);

}  // namespace orodem
