// The inertia floor (wedge.inertia_floor, SimParams::m_inertia_min): a disc
// lighter than m_f moves with the mass m_f and the moment m_f R²/2, while its
// weight stays m g. Each test compares a number with its closed form:
//   free fall        v(t) = -g (m / m_f) t (velocity Verlet is exact for a
//                    constant force), kinetic energy ½ m_f v²;
//   resting on a     overlap δ = m g / k_n: the weight, not the inertia,
//   floor            presses it (2.25 times more with m_f in the weight);
//   collision        the dashpots follow the inertial masses, so the
//                    restitution is the requested one and the contact lasts
//                    sqrt(m_f / m) times longer (with the true masses in the
//                    dashpot e would be 0.63 instead of 0.5);
//   wedge setup      every free disc gets 1/max(m, m_f); the automatic dt
//                    grows by inertia_floor exactly, and the packing (its
//                    settling, its cache key) does not change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "orodem/io/config.hpp"
#include "orodem/io/packing_file.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

constexpr double kRho = 2500.0;  // [kg/m³]
constexpr double kR = 0.5;       // the light disc [m]
constexpr double kRf = 0.75;     // the floor's radius, 1.5 r_min [m]
constexpr double kG = 9.81;      // [m/s²]

double disc_mass(double r) { return kRho * M_PI * r * r; }  // [kg]

LawParams law_with_restitution(double e, bool clamp) {
    MaterialConfig mat;
    mat.density = kRho;
    mat.k_n = 1.0e8;
    mat.k_s_over_k_n = 1.0 / 3.0;
    mat.damping_kind = DampingKind::restitution;
    mat.damping_normal = e;
    mat.clamp_normal = clamp;
    return make_law(mat);
}

/// Applies the floor to every disc of sim, as make_wedge does.
void floor_inertia(Simulation& sim, double m_f) {
    sim.params.m_inertia_min = m_f;
    for (std::size_t s = 0; s < sim.particles.size(); ++s) sim.particles.set_free_inertia(s, m_f);
}

}  // namespace

TEST(InertiaFloor, ALightDiscFallsWithItsWeightOverTheFloorMass) {
    const test::SerialOmp serial;
    const double m = disc_mass(kR), m_f = disc_mass(kRf), dt = 1e-3;
    for (const bool floored : {false, true}) {
        Simulation sim = test::make_sim({{{0.0, 100.0}, kR}}, law_with_restitution(0.5, true), dt, {0.0, -kG}, kRho);
        if (floored) floor_inertia(sim, m_f);
        sim.initialize();
        for (int k = 0; k < 1000; ++k) sim.step();
        const double a = floored ? kG * m / m_f : kG;  // [m/s²]
        const double v = sim.particles.v[0].y;
        EXPECT_NEAR(v / (-a * sim.time), 1.0, 1e-12) << "floored " << floored;
        const double m_in = floored ? m_f : m;
        EXPECT_NEAR(sim.kinetic_energy() / (0.5 * m_in * v * v), 1.0, 1e-12) << "floored " << floored;
    }
}

TEST(InertiaFloor, ADiscRestingOnAFloorPressesWithItsOwnWeight) {
    const test::SerialOmp serial;
    const LawParams law = law_with_restitution(0.2, true);
    const double m = disc_mass(kR), m_f = disc_mass(kRf);
    const double dt = 0.1 * std::sqrt(m_f / law.k_n);
    Simulation sim = test::make_sim({{{0.0, kR}, kR}}, law, dt, {0.0, -kG}, kRho);
    sim.walls.push_back({{-10.0, 0.0}, {10.0, 0.0}, {}, 0.0, true, false, 0.0});
    floor_inertia(sim, m_f);
    sim.initialize();
    // The bounce decays by e = 0.2 per half period of about 30 steps.
    for (int k = 0; k < 20000; ++k) sim.step();
    const double overlap = kR - sim.particles.x[0].y;  // [m]
    EXPECT_NEAR(overlap / (m * kG / law.k_n), 1.0, 1e-6);
    EXPECT_NEAR(sim.particles.v[0].y, 0.0, 1e-9);
}

TEST(InertiaFloor, ACollisionKeepsItsRestitutionAndLastsLongerByTheRatioOfTheInertias) {
    const test::SerialOmp serial;
    const double e_req = 0.5;
    const LawParams law = law_with_restitution(e_req, false);  // unclamped: e is exactly the law's
    const double m = disc_mass(kR), m_f = disc_mass(kRf);
    double contact_time[2] = {};
    for (const bool floored : {false, true}) {
        const double m_in = floored ? m_f : m;
        const double dt = M_PI * std::sqrt(0.5 * m_in / law.k_n) / 2000.0;  // t_c / 2000
        const double v0 = 1.0;  // incoming relative speed [m/s]
        Simulation sim = test::make_sim({{{0.0, 0.0}, kR, {0.5 * v0, 0.0}}, {{2.0 * kR + 3.1 * v0 * dt, 0.0}, kR, {-0.5 * v0, 0.0}}},
                                        law, dt, {0.0, 0.0}, kRho);
        if (floored) floor_inertia(sim, m_f);
        sim.initialize();
        double t_touch = NAN, t_sep = NAN;
        auto overlap = [&] { return 2.0 * kR - norm(sim.particles.x[sim.particles.slot_of_id[1]] - sim.particles.x[sim.particles.slot_of_id[0]]); };
        double prev = overlap();
        for (int k = 0; k < 10000 && std::isnan(t_sep); ++k) {
            sim.step();
            const double d = overlap();
            if (std::isnan(t_touch) && prev <= 0.0 && d > 0.0) t_touch = sim.time - dt * d / (d - prev);
            if (!std::isnan(t_touch) && prev > 0.0 && d <= 0.0) t_sep = sim.time - dt * (-d) / (prev - d);
            prev = d;
        }
        ASSERT_FALSE(std::isnan(t_sep)) << "floored " << floored;
        const ParticleStore& p = sim.particles;
        const double v_out = p.v[p.slot_of_id[1]].x - p.v[p.slot_of_id[0]].x;
        // t_c/2000 resolves e and t_c to about 5e-4 (test_collision.cpp).
        EXPECT_NEAR(v_out / v0, e_req, 0.005) << "floored " << floored;
        contact_time[floored] = t_sep - t_touch;
    }
    EXPECT_NEAR(contact_time[1] / contact_time[0], std::sqrt(m_f / m), 1e-3 * std::sqrt(m_f / m));
}

// A wedge config with radii in [0.5, 1] m: the floor's tests.
const std::string kWedgeLayer =
    "[run]\nexperiment = \"exp1\"\n[packing]\nr_min = 0.5\nr_max = 1.0\nh0 = 10.0\n[wedge]\n";

TEST(InertiaFloor, TheMeanInertialMassRatioMatchesAnIntegralOverTheRadii) {
    const std::string text = kWedgeLayer;
    // Midpoint rule over R uniform in [0.5, 1] m, 2e5 cells: error about 1e-11.
    const auto integral = [](double f_r) {
        const int n = 200000;
        double own = 0.0, floored = 0.0;
        for (int k = 0; k < n; ++k) {
            const double r = 0.5 + 0.5 * (k + 0.5) / n;
            own += r * r;
            floored += std::max(r, f_r) * std::max(r, f_r);
        }
        return floored / own;
    };
    EXPECT_EQ(inertia_floor_mean_mass_ratio(parse_config(text, "run.toml", {})), 1.0);
    for (const double f : {1.2, 1.5, 2.0, 3.0}) {
        const Config c = parse_config(text + fmt::format("inertia_floor = {}\n", f), "run.toml", {});
        EXPECT_NEAR(inertia_floor_mean_mass_ratio(c), integral(std::min(f * 0.5, 1.0)), 1e-9) << f;
    }
    // f = 2: every disc moves as the largest, R² = 1 against the mean 7/12.
    const Config two = parse_config(text + "inertia_floor = 2\n", "run.toml", {});
    EXPECT_NEAR(inertia_floor_mean_mass_ratio(two), 12.0 / 7.0, 1e-12);
}

TEST(InertiaFloor, TheWedgeSetupFloorsTheLightDiscsAndStretchesTheTimestep) {
    const std::string text = kWedgeLayer;
    const Config off = parse_config(text, "run.toml", {});
    const Config on = parse_config(text + "inertia_floor = 1.5\n", "run.toml", {});
    const double m_f = disc_mass(kRf);
    EXPECT_EQ(inertia_floor_mass(off), 0.0);
    EXPECT_NEAR(inertia_floor_mass(on) / m_f, 1.0, 1e-15);
    EXPECT_NEAR(timestep_for(on).dt / timestep_for(off).dt, 1.5, 1e-12);
    // The packing settles as without the floor and is shared with such runs.
    EXPECT_EQ(timestep_for(on, false).dt, timestep_for(off).dt);
    EXPECT_EQ(packing_key(on), packing_key(off));

    ParticleStore layer;
    const double radii[] = {0.5, 0.6, 0.75, 0.9, 1.0};
    for (int k = 0; k < 5; ++k) layer.add({4.0 * k + 2.0, 1.0}, radii[k], on.material.density);
    for (const Config* c : {&off, &on}) {
        const WedgeSetup w = make_wedge(*c, layer);
        const ParticleStore& p = w.sim.particles;
        const double floor = c == &on ? m_f : 0.0;
        EXPECT_EQ(w.sim.params.m_inertia_min, floor);
        for (std::size_t s = 0; s < p.size(); ++s) {
            EXPECT_EQ(p.mass[s], layer.mass[s]);  // the weight's mass is the disc's own
            const double m_in = std::max(p.mass[s], floor);
            EXPECT_NEAR(p.inv_mass[s] * m_in, 1.0, 1e-15) << "R = " << p.radius[s];
            EXPECT_NEAR(p.inv_inertia[s] * 0.5 * m_in * p.radius[s] * p.radius[s], 1.0, 1e-15) << "R = " << p.radius[s];
        }
    }
}
