// Sleeping zones: skip the force work of material that moves rigidly.
//
// In a wedge experiment most of the incoming plate rides on the belt at the
// belt speed, and the far retroside rests on its fixed base, long before the
// deformation reaches them; computing their contacts every step changes
// nothing. At each neighbour rebuild (every skin/2 of motion, about 5,000
// steps in the paper-size runs):
//
//   1. before the rebuild, every awake disc's displacement since the last
//      rebuild is compared with the rigid motion u t of its side (u_left
//      left of x_split, u_right right of it); a departure above `tolerance`
//      makes it active. Elastic vibration (sub-micrometre amplitudes) stays
//      below the tolerance; slip on the base, folding and thrusting do not.
//   2. the sleeping zones are everything more than `buffer_left` left of
//      the leftmost active disc and `buffer_right` right of the rightmost
//      (never across x_split);
//   3. after the rebuild (slots now sorted by x column of cells) each
//      sleeping zone is a whole number of cell columns, so the awake discs
//      are one slot range [awake_.disc_begin, awake_.disc_end), and the pairs that can
//      touch an awake disc are those owned by the awake columns and the one
//      sleeping column next to each side: one pair range [awake_.pair_begin,
//      awake_.pair_end) (a pair never spans more than two adjacent columns, as
//      the cell edge is at least the contact cut-off).
//
// A sleeping disc gets v = u, ω = 0, inv_mass = inv_inertia = 0 (the fixed
// discs' trick: the integrator needs no branch), so the drift moves it by
// exactly u dt and it acts on its awake neighbours as an infinitely heavy
// body moving at u. Its contacts keep their tangential history (the relative
// motion inside a rigid zone is zero). A rebuild step evaluates every pair
// and disc, which keeps wall forces and contact counts current for the
// diagnostics. Waking restores the disc's inverse mass and inertia; its
// velocity is u, which it had when it fell asleep. Fixed discs stay fixed.
//
// Lazy drift: inside Simulation::advance(), only the drift range (the awake
// discs and both discs of every pair evaluated between rebuilds) drifts each
// step; the discs outside it (sleeping or fixed, constant v and ω) catch up
// x += n dt v at once before a rebuild and when advance() returns, so no
// caller ever sees a stale position. Their motion enters the rebuild test as
// u t. The awake discs' trajectories are bit for bit those of drifting every
// disc every step; the sleepers' positions differ by the round-off of n
// additions against one product (1e-13 m). advance() is chunked at fixed
// steps by the run loop, so results do not depend on interruptions.
//
// Everything here is serial, in slot order, once per rebuild: deterministic
// at any thread count, and cheap (O(N) per rebuild).
#include <algorithm>
#include <cmath>
#include <limits>

#include "orodem/engine/simulation.hpp"

namespace orodem {

void Simulation::sleep_bounds(SleepDecision& d) const {
    const SleepParams& sp = params.sleep;
    const ParticleStore& p = particles;
    const std::vector<Vec2>& x_ref = builder_.x_ref();
    const double elapsed = static_cast<double>(step_count - awake_.last_rebuild_step) * params.dt;
    const double inf = std::numeric_limits<double>::infinity();
    if (x_ref.size() != p.size() || elapsed <= 0.0) {
        d = SleepDecision{};  // no motion to judge (a rebuild forced right after another): all awake
        return;
    }
    double act_min = inf, act_max = -inf;
    const double tol2 = sp.tolerance * sp.tolerance;
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.flags[i] & (kFlagAsleep | kFlagFixed)) continue;  // rigid by construction
        const Vec2 u = x_ref[i].x < sp.x_split ? sp.u_left : sp.u_right;
        if (norm2(p.x[i] - x_ref[i] - elapsed * u) > tol2) {
            act_min = std::min(act_min, p.x[i].x);
            act_max = std::max(act_max, p.x[i].x);
        }
    }
    d.active_min = act_min;
    d.active_max = act_max;
    d.x_lo = sp.left ? std::min(act_min, sp.x_split) - sp.buffer_left : -inf;
    d.x_hi = sp.right ? std::max(act_max, sp.x_split) + sp.buffer_right : inf;
}

void Simulation::apply_sleep(double x_lo, double x_hi) {
    ParticleStore& p = particles;
    const std::size_t n = p.size();
    const GridInfo& g = builder_.grid();
    int lo = 0, hi = g.nx;  // sleeping columns: [0, lo) and [hi, nx)
    if (params.sleep.enabled && !params.periodic_x && n > 0) {
        if (std::isfinite(x_lo))
            lo = static_cast<int>(std::clamp(std::floor((x_lo - g.x0) / g.cell), 0.0, static_cast<double>(g.nx)));
        if (std::isfinite(x_hi))
            hi = static_cast<int>(std::clamp(std::ceil((x_hi - g.x0) / g.cell), static_cast<double>(lo),
                                             static_cast<double>(g.nx)));
    }
    const std::uint32_t a = n ? builder_.column_start(lo) : 0, b = n ? builder_.column_start(hi) : 0;
    for (std::size_t s = 0; s < n; ++s) {
        const bool sleep = s < a || s >= b;
        const bool asleep = (p.flags[s] & kFlagAsleep) != 0;
        if (sleep && !asleep && !(p.flags[s] & kFlagFixed)) {
            p.flags[s] |= kFlagAsleep;
            ++p.inertia_epoch;
            p.inv_mass[s] = 0.0;
            p.inv_inertia[s] = 0.0;
            p.v[s] = p.x[s].x < params.sleep.x_split ? params.sleep.u_left : params.sleep.u_right;
            p.omega[s] = 0.0;
            p.force[s] = {};
            p.torque[s] = 0.0;
        } else if (!sleep && asleep) {
            p.flags[s] &= static_cast<std::uint8_t>(~kFlagAsleep);
            if (!(p.flags[s] & kFlagFixed)) p.set_free_inertia(s, params.m_inertia_min);
        }
    }
    awake_.disc_begin = a;
    awake_.disc_end = b;
    const std::uint32_t owner_lo = n ? builder_.column_start(std::max(lo - 1, 0)) : 0;
    const std::uint32_t owner_hi = n ? builder_.column_start(std::min(hi + 1, g.nx)) : 0;
    awake_.pair_begin = n ? contacts.begin[owner_lo] : 0;
    awake_.pair_end = n ? contacts.begin[owner_hi] : 0;
    set_drift_range();
}

void Simulation::set_drift_range() {
    // The smallest slot range holding every awake disc and both discs of
    // every pair evaluated between rebuilds: what a step reads.
    const auto n = static_cast<std::uint32_t>(particles.size());
    std::uint32_t b = n, e = 0;  // empty
    if (awake_.disc_begin < std::min(awake_.disc_end, n)) {
        b = awake_.disc_begin;
        e = std::min(awake_.disc_end, n);
    }
    const std::size_t pe = std::min<std::size_t>(awake_.pair_end, contacts.size());
    for (std::size_t k = awake_.pair_begin; k < pe; ++k) {
        const std::uint32_t lo = std::min(contacts.i[k], contacts.j[k]), hi = std::max(contacts.i[k], contacts.j[k]);
        if (hi >= n) continue;  // a guard: the checkpoint reader refuses such pairs before a restore
        b = std::min(b, lo);
        e = std::max(e, hi + 1);
    }
    awake_.drift_begin = b < e ? b : 0;
    awake_.drift_end = b < e ? e : 0;
}

void Simulation::catch_up_drift() {
    // The discs outside the drift range have inv_mass = 0 and a constant v
    // and ω since the last rebuild: awake_.drift_lag steps of x += v dt in one.
    if (awake_.drift_lag == 0) return;
    ParticleStore& p = particles;
    const double t = static_cast<double>(awake_.drift_lag) * params.dt;
    const std::size_t n = p.size();
    auto drift = [&](std::size_t from, std::size_t to) {
        for (std::size_t i = from; i < to; ++i) {
            p.x[i] += t * p.v[i];
            p.theta[i] += t * p.omega[i];
        }
    };
    drift(0, std::min<std::size_t>(awake_.drift_begin, n));
    drift(std::min<std::size_t>(awake_.drift_end, n), n);
    awake_.drift_lag = 0;
}

}  // namespace orodem
