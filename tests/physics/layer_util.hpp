// The settled layer of a wedge config, for the physics tests that put one on
// the conveyor: generated, settled and cut to h0 as `orodem run` does, on one
// thread (the cache is not used).
#pragma once

#include "orodem/io/config.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "test_util.hpp"

namespace orodem::test {

inline ParticleStore settled_cut_layer(const Config& c) {
    const SerialOmp serial;
    Simulation s = make_settle_simulation(c);
    s.initialize();
    settle(s, c.packing, 0.05, {});
    ParticleStore p = std::move(s.particles);
    cut_layer(p, c.packing.h0);
    return p;
}

}  // namespace orodem::test
