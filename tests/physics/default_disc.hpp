// The material the boundary and base tests share: the config defaults
// (k_n = 1e8 N/m, k_s = k_n/3, restitution 0.5, μ_i = 0.3), ρ = 2500 kg/m³,
// discs of R = 0.5 m (m = 1963.5 kg) and the default timestep
// dt = 0.1 sqrt(m/k_n) = 4.43e-4 s.
#pragma once

#include <cmath>

#include "orodem/io/config.hpp"
#include "orodem/setup/scenario.hpp"

namespace orodem::test {

constexpr double kRho = 2500.0;  // [kg/m³]
constexpr double kR = 0.5;       // [m]
constexpr double kG = 9.81;      // [m/s²]

inline LawParams default_law() { return make_law(MaterialConfig{}); }
inline double disc_mass() { return kRho * M_PI * kR * kR; }  // [kg]
inline double default_dt() { return choose_timestep(disc_mass(), default_law(), 0.0, kDefaultSafety).dt; }  // [s]

}  // namespace orodem::test
