// Helpers shared by the tests: small hand-built simulations.
#pragma once

#include <omp.h>

#include <initializer_list>

#include "orodem/engine/simulation.hpp"
#include "orodem/physics/contact_law.hpp"

namespace orodem::test {

/// Runs the enclosing scope on one OpenMP thread and restores the setting.
/// Small hand-built systems have nothing to share between threads;
/// thread-count independence is tested by tests/unit/test_determinism.cpp.
struct SerialOmp {
    int saved = omp_get_max_threads();
    SerialOmp() { omp_set_num_threads(1); }
    ~SerialOmp() { omp_set_num_threads(saved); }
    SerialOmp(const SerialOmp&) = delete;
    SerialOmp& operator=(const SerialOmp&) = delete;
};

struct DiscSpec {
    Vec2 x;
    double r;
    Vec2 v{};
    double omega = 0.0;
    std::int32_t cluster = -1;
};

/// A simulation of the given discs (density rho) with law, dt, gravity and
/// walls; skin defaults to 0.4 × the smallest radius. Call initialize() after
/// any further changes.
inline Simulation make_sim(std::initializer_list<DiscSpec> discs, const LawParams& law, double dt,
                           Vec2 gravity = {0.0, 0.0}, double rho = 1.0) {
    Simulation sim;
    double r_min = 1e300;
    for (const auto& d : discs) {
        const std::size_t s = sim.particles.add(d.x, d.r, rho, d.cluster);
        sim.particles.v[s] = d.v;
        sim.particles.omega[s] = d.omega;
        r_min = std::min(r_min, d.r);
    }
    sim.params.law = law;
    sim.params.dt = dt;
    sim.params.gravity = gravity;
    sim.params.skin = 0.4 * r_min;
    return sim;
}

}  // namespace orodem::test
