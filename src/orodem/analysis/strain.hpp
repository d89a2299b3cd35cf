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
// `radius` over the reference positions (analysis/neighbour_grid.hpp): O(N).
// Pure function of its inputs; per disc, so its result does not depend on
// the order of the work.
//
// Finite strain from S = 0 (the "total" measures): the incremental gradients
// of the output intervals multiplied in order, F_total = F_k ⋯ F_2 F_1, each
// F_k fitted on the disc's neighbourhood at the start of its interval. This
// follows a neighbourhood that changes as the material deforms (a fit on the
// S = 0 neighbours alone fails once a shear zone has torn them apart). An
// interval in which a disc has no defined F (fewer than three neighbours:
// a grain rolling down a slope) leaves its F_total as it was.
#pragma once

#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

/// A 2x2 deformation gradient [[xx, xy], [yx, yy]] [-]; the identity by default.
struct Mat2 {
    double xx = 1.0, xy = 0.0, yx = 0.0, yy = 1.0;
};
constexpr Mat2 operator*(const Mat2& a, const Mat2& b) {
    return {a.xx * b.xx + a.xy * b.yx, a.xx * b.xy + a.xy * b.yy, a.yx * b.xx + a.yy * b.yx, a.yx * b.xy + a.yy * b.yy};
}

/// The measures of one deformation gradient (see the note above).
struct StrainMeasures {
    double shear = 0.0;       // maximum shear strain γ [-]
    double volumetric = 0.0;  // det F − 1 [-]
    double rotation = 0.0;    // [rad]
};
StrainMeasures strain_measures(const Mat2& F);

struct StrainField {
    std::vector<double> shear;       // maximum shear strain γ [-]
    std::vector<double> volumetric;  // det F − 1 [-]
    std::vector<double> rotation;    // [rad]
    std::vector<double> d2min;       // mean squared non-affine displacement [m²]
    std::vector<Mat2> F;             // the best-fit gradient (NaN where undefined) [-]
    std::vector<double> shear_total; // γ of the finite strain from S = 0 (filled by the run) [-]
};

/// F_total[i] ← F_inc[i] F_total[i] where F_inc[i] is defined. F_total is
/// resized to F_inc's size with identities when it is shorter.
void accumulate_gradient(std::vector<Mat2>& F_total, const std::vector<Mat2>& F_inc);

/// x0, x1: the positions of the same discs (same index) in the reference and
/// the current configuration [m]; radius: the neighbourhood radius [m].
StrainField local_strain(const std::vector<Vec2>& x0, const std::vector<Vec2>& x1, double radius);

}  // namespace orodem
