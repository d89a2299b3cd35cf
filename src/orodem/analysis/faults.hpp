// Fault detection (issue: structures; docs/physics.md "Faults"): the
// localized shear zones of one output interval, from the incremental
// maximum shear strain γ of each disc (analysis/strain.hpp).
//
//  1. Smoothing: each disc's γ is replaced by the mean over the discs within
//     smooth_radius (itself included), which removes single-grain
//     rearrangements.
//  2. Hot discs: smoothed γ above max(k_median · median, k_mean · mean) of
//     the interval. Relative to the median alone, a wedge whose incoming
//     plate rides rigidly on the belt (most discs, γ ~ 1e-3) would flag the
//     whole wedge; the mean term keeps the threshold a few times the
//     deforming material's typical strain. A uniform (affine) deformation has
//     mean = median and no disc above 2.5 times it: no fault.
//  3. Zones: hot discs closer than link_radius are connected (components).
//  4. Lines: a zone is fitted by its principal axis (weighted least squares
//     of the positions); a zone that two lines fit at more than
//     split_angle_deg to each other (a V or an X of conjugate shears meeting
//     at their root) is split by two-line clustering (assign each disc to
//     the nearer line, refit, repeat), at most twice.
//  5. Faults: lines of at least min_discs discs, min_length long and
//     min_elongation times longer than wide (length and width are four
//     standard deviations of the positions along and across the axis).
//
// For each fault, the line is the principal axis of its discs weighted by
// their raw γ (the ridge of the strain, not the smoothed zone around it):
// root = the point of the line at the mean height of the deepest tenth of
// its discs, tip = at that of the highest tenth (for a line within 10° of
// the horizontal, the line's lower and higher ends, two standard deviations
// from its centre); vergence from root to tip: a
// fault rising toward the proside (−x, the incoming plate) is pro-vergent
// (its hanging wall moves toward the proside), one rising toward +x
// retro-vergent; dip = the line's angle, 0-90°, or, for a long fault whose
// middle half along the line is itself a line (four times longer than
// wide), that half's: the dip at mid-depth of a listric fault; slip over the
// interval ≈ 2 mean(γ) · width (engineering shear across the zone's width).
// On synthetic faults (tests/unit/test_faults.cpp) the dip is within 1° and
// the root within 1.5 m of the imposed ones.
//
// Tracking (FaultTracker) gives a fault the id of the nearest known fault of
// the same vergence whose root and tip are each within one h0 of its own and
// whose dip is within 25°, each known fault taken at most once, nearest pair
// first; a fault without one starts a new id. Known faults not found in an
// output are listed as inactive with their last geometry.
//
// All pure functions of their inputs with fixed summation orders
// (neighbours ascending): the same positions give the same faults.
#pragma once

#include <cstdint>
#include <vector>

#include "orodem/core/vec2.hpp"

namespace orodem {

struct FaultParams {
    double smooth_radius = 3.0;     // γ averaged over this radius [m]
    double link_radius = 2.25;      // hot discs closer than this are one zone [m]
    double k_median = 5.0;          // threshold: k_median · median(γ_smoothed) ... [-]
    double k_mean = 2.5;            // ... or k_mean · mean(γ_smoothed), the larger [-]
    std::size_t min_discs = 15;     // smallest fault [discs]
    double min_length = 7.5;        // shortest fault [m]
    double min_elongation = 2.5;    // length / width [-]
    double split_angle_deg = 20.0;  // two lines at more than this: a V, split [deg]
};

/// The defaults for a material of mean disc diameter d_mean [m] in a layer of
/// thickness h0 [m]: smoothing over 2 d_mean, links of 1.5 d_mean, faults at
/// least h0/2 long.
FaultParams fault_params(double d_mean, double h0);

struct Fault {
    std::int64_t id = -1;        // track id (FaultTracker); -1 before tracking
    int vergence = 0;            // +1 pro-vergent (rises toward −x), −1 retro-vergent
    double dip_deg = 0.0;        // dip at mid-depth [deg], 0-90
    Vec2 root;                   // deepest point [m]
    Vec2 tip;                    // highest point [m]
    double length = 0.0;         // [m]
    double width = 0.0;          // [m]
    double slip = 0.0;           // slip over the interval [m]; 0 when inactive
    std::uint32_t discs = 0;     // discs in the zone
    bool active = true;          // found in this output
    double first_S = 0.0;        // first output it was found at [-]
    double last_S = 0.0;         // last output it was found at [-]
};

/// The dips the detector is made to find faults at [deg]: the thrusts and
/// back-thrusts of a wedge (its tests plant faults of 30° and 45°). A line
/// flatter than kFaultDipMinDeg is shear along the base or a slide of
/// surface discs, one steeper than kFaultDipMaxDeg a collapsing column, not
/// a thrust; the fault table keeps them, the strain maps do not draw them.
inline constexpr double kFaultDipMinDeg = 10.0;
inline constexpr double kFaultDipMaxDeg = 75.0;

struct FaultScan {
    std::vector<Fault> faults;       // in the order of their zone's first disc
    double threshold = 0.0;          // smoothed γ above which a disc is hot [-]
    std::vector<std::int32_t> zone;  // per disc: its fault's index in `faults`, or −1
};

/// x: positions at the end of the interval [m]; shear: each disc's
/// incremental γ (NaN: undefined, left out).
FaultScan detect_faults(const std::vector<Vec2>& x, const std::vector<double>& shear, const FaultParams& p);

class FaultTracker {
public:
    /// Gives the faults of the output at S their ids and returns every known
    /// fault, ordered by id: those found now active with this geometry, the
    /// others inactive with their last one. h0 [m] sets the reach.
    std::vector<Fault> update(std::vector<Fault> found, double S, double h0);

    std::vector<Fault> known;    // every fault ever found, by id (the checkpointed state)
    std::int64_t next_id = 1;
};

/// The paper's stage of an output ([45]-[52]) from its faults (x relative to
/// the S point, y from the base, h0 [m]): 0 no active fault; 3 an active
/// retro-vergent fault rooted on the base (root within h0/4 of it) more than
/// one h0 into the retroside (retrowedge accretion); else 2 an active
/// pro-vergent fault rooted on the base more than one h0 into the proside
/// (thrusting has propagated into the incoming plate); else 1 (the block
/// uplift between the shears rooted at the S point).
int classify_stage(const std::vector<Fault>& faults, double h0);

/// The stage reached by an output whose faults give `now` (classify_stage),
/// after outputs that reached `reached` and whose last gave `last`: a stage
/// counts once two consecutive outputs show it (or a later one), and is kept
/// (the stages are an evolution; one output's detection is noisy):
/// max(reached, min(now, last)).
int stage_reached(int reached, int last, int now);

/// Active pro- and retro-vergent faults, and the root x of the most proside
/// active pro-vergent fault (the frontal thrust; NaN when none) [m].
struct FaultCounts {
    int pro = 0;
    int retro = 0;
    double front_x = 0.0;
};
FaultCounts count_faults(const std::vector<Fault>& faults);

}  // namespace orodem
