// Local strain of the granular assembly between two configurations (issue:
// structures; docs/physics.md "Strain"). For each disc i, the neighbours j
// whose centres lie within `radius` of it in the reference configuration
// give the branch vectors r0 = x0_j − x0_i and r1 = x1_j − x1_i; the
// best-fit deformation gradient (least squares, Falk & Langer 1998) is
//   F = Y X⁻¹,  X = Σ r0 r0ᵀ,  Y = Σ r1 r0ᵀ,
// and the non-affine residual D²min = Σ |r1 − F r0|² / n over its n
// neighbours. From F, finite-strain measures that are exact for any
// deformation (a rigid rotation gives zero strain):
//   Green-Lagrange E = ½ (FᵀF − I);
//   maximum shear strain γ = sqrt(((E_xx − E_yy)/2)² + E_xy²), the radius of
//     E's Mohr circle (small deformations: half the engineering shear);
//   volumetric strain det F − 1 (area change; dilation positive);
//   rotation atan2(F_yx − F_xy, F_xx + F_yy), the angle of the rotation of
//     F's polar decomposition (counter-clockwise positive).
// A disc with fewer than three neighbours, or whose neighbours lie on one
// line (X singular), gets NaN. Neighbours are found with a cell grid of edge
// `radius` over the reference positions: O(N). Pure function of its inputs;
// per disc, so its result does not depend on the order of the work.
#pragma once

#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

struct StrainField {
    std::vector<double> shear;       // maximum shear strain γ [-]
    std::vector<double> volumetric;  // det F − 1 [-]
    std::vector<double> rotation;    // [rad]
    std::vector<double> d2min;       // mean squared non-affine displacement [m²]
};

/// x0, x1: the positions of the same discs (same index) in the reference and
/// the current configuration [m]; radius: the neighbourhood radius [m].
StrainField local_strain(const std::vector<Vec2>& x0, const std::vector<Vec2>& x1, double radius);

}  // namespace orodem
