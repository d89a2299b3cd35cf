// The base following the plate (two-way [flexure], run/wedge_flexure.hpp) on a
// small exp1 in process (h0 = 4 m, α = 4 h0, the plate solved every 100
// steps): after every solve the bases' height under any x of the model is
// −(w(x) − w_layer) of that solve, w linear between the plate's nodes, to
// round-off, and every base contact's point lies on that height; the fixed
// retroside discs ride with their base; and the bases' steps at the solves
// add no kinetic energy: the layer's kinetic energy relative to the rigid
// motion of its side, in the 100 steps after each solve, keeps below a bound
// set by the same run with one-way coupling (the base flat, the same solves).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/run/wedge_flexure.hpp"
#include "orodem/setup/wedge.hpp"
#include "layer_util.hpp"
#include "test_util.hpp"

using namespace orodem;

namespace {

Config flexure_config(const char* coupling) {
    return parse_config(std::string("[run]\nexperiment = \"exp1\"\n[wedge]\nv = 0.2\ns_max = 1.0\npro_margin = 4.0\n"
                                    "retro_length = 4.0\n[packing]\nkind = \"clusters\"\nr_min = 0.5\nr_max = 0.75\n"
                                    "h0 = 4.0\n[flexure]\nD = 5.3e8\ncoupling = \"") +
                            coupling + "\"\n",
                        "flexure.toml");
}

const ParticleStore& layer() {
    static const ParticleStore l = test::settled_cut_layer(flexure_config("one-way"));
    return l;
}

/// ½ Σ m |v − u|² over the free discs, u the belt speed left of the S point
/// and rest right of it [J]: the layer's motion beyond its side's rigid motion.
double peculiar_energy(const Simulation& sim, double v_belt) {
    const ParticleStore& p = sim.particles;
    double e = 0.0;
    for (std::size_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        if (p.inv_mass[s] == 0.0) continue;
        const Vec2 u{p.x[s].x < 0.0 ? v_belt : 0.0, 0.0};
        e += 0.5 * p.mass[s] * norm2(p.v[s] - u);
    }
    return e;
}

struct EnergyAfterSolves {
    double worst_rise = 0.0;  // the largest rise of the peculiar energy in the 100 steps after a solve [J]
    double mean = 0.0;        // its mean over the steps [J]
};

/// Runs c from its layer to S = 0.6 with the plate solved every 100 steps;
/// check(sim, flexure, state) after each solve from S = 0.1.
template <class Check>
EnergyAfterSolves run(const Config& c, Check&& check) {
    WedgeSetup w = make_wedge(c, layer());
    WedgeFlexure fl(c, w);
    FlexureState st;
    fl.start(w.sim, st);
    w.sim.initialize();
    const double v = c.wedge.v;
    const auto steps = static_cast<std::uint64_t>(std::llround(0.6 * c.packing.h0 / (v * w.sim.params.dt)));
    const std::uint64_t settle = steps / 6;  // S = 0.1: the cut layer's start-up over
    EnergyAfterSolves out;
    std::uint64_t counted = 0;
    while (w.sim.step_count < steps) {
        const double before = peculiar_energy(w.sim, v);
        fl.solve(w.sim, st);
        const bool measure = w.sim.step_count >= settle;
        if (measure) check(w.sim, fl, st);
        double peak = before;
        for (int k = 0; k < 100; ++k) {
            w.sim.step();
            const double e = peculiar_energy(w.sim, v);
            peak = std::max(peak, e);
            if (measure) {
                out.mean += e;
                ++counted;
            }
        }
        if (measure) out.worst_rise = std::max(out.worst_rise, peak - before);
    }
    out.mean /= static_cast<double>(std::max<std::uint64_t>(counted, 1));
    return out;
}

}  // namespace

TEST(FlexureBase, TheBaseIsMinusTheLastSolvesDeflectionAndTheLayerStaysSettled) {
    const test::SerialOmp serial;
    std::size_t checked = 0, contacts = 0, fixed = 0;
    const EnergyAfterSolves two = run(flexure_config("two-way"), [&](const Simulation& sim, const WedgeFlexure& fl,
                                                                     const FlexureState& st) {
        const FlexurePlate& pl = fl.plate();
        double w_range = 0.0;
        for (std::size_t k = 0; k < pl.size(); ++k) w_range = std::max(w_range, std::fabs(st.w[k] - fl.w_layer()));
        const double tol = 1e-12 * std::max(1.0, fl.w_layer());  // round-off [m]
        // The base's height between and at the nodes of the model.
        for (std::size_t k = 0; k + 1 < pl.size(); ++k) {
            if (pl.x(k) < -5.0 * 4.0 || pl.x(k + 1) > 4.0 * 4.0) continue;
            for (const double t : {0.0, 0.25, 0.5, 0.9}) {
                const double x = pl.x(k) + t * (pl.x(k + 1) - pl.x(k));
                const double w = st.w[k] + t * (st.w[k + 1] - st.w[k]);
                const Wall& base = sim.walls[x < 0.0 ? kWallProBase : kWallRetro];
                ASSERT_TRUE(base.profile);
                EXPECT_NEAR(base.profile->height(x), -(w - fl.w_layer()), tol) << x;
                EXPECT_NEAR(fl.base_height(x), -(w - fl.w_layer()), tol) << x;
                ++checked;
            }
        }
        // Every disc on a base touches the segment under its centre: the
        // contact point lies on that segment's line.
        const ParticleStore& p = sim.particles;
        const WallContactStore& ws = sim.wall_contacts;
        for (std::size_t s = 0; s < p.size(); ++s)
            for (std::uint32_t k = ws.begin[s]; k < ws.begin[s + 1]; ++k) {
                if (ws.wall[k] != kWallProBase && ws.wall[k] != kWallRetro) continue;
                Vec2 cp;
                if (!wall_contact_point(sim.walls[ws.wall[k]], p.x[s], cp)) continue;
                if (norm(p.x[s] - cp) >= p.radius[s]) continue;
                const BaseProfile& bp = *sim.walls[ws.wall[k]].profile;
                const std::size_t seg = bp.segment(p.x[s].x);
                const double on_line = bp.y[seg] + (cp.x - bp.node_x(seg)) * bp.inv_dx * (bp.y[seg + 1] - bp.y[seg]);
                EXPECT_NEAR(cp.y, on_line, 1e-9 * std::max(1.0, w_range)) << s;
                EXPECT_GT(p.x[s].y, cp.y) << s << ": a disc under its base";
                ++contacts;
                if (p.flags[s] & kFlagFixed) {
                    // A fixed disc rides with its base: it still overlaps it.
                    EXPECT_LT(norm(p.x[s] - cp), p.radius[s]);
                    ++fixed;
                }
            }
    });
    EXPECT_GT(checked, 1000u);
    EXPECT_GT(contacts, 1000u);
    EXPECT_GT(fixed, 100u);
    const EnergyAfterSolves one = run(flexure_config("one-way"), [](const Simulation&, const WedgeFlexure&, const FlexureState&) {});
    // The bound: the one-way run's own largest rise after a solve (its base
    // stays flat, so the rise is the layer's own motion), doubled; and the
    // mean within 1.5 times the one-way run's.
    EXPECT_LE(two.worst_rise, 2.0 * one.worst_rise) << "two-way " << two.worst_rise << " J, one-way " << one.worst_rise << " J";
    EXPECT_LE(two.mean, 1.5 * one.mean) << "two-way " << two.mean << " J, one-way " << one.mean << " J";
    std::printf("peculiar energy: worst rise after a solve %.4g J (one-way %.4g J), mean %.4g J (one-way %.4g J)\n",
                two.worst_rise, one.worst_rise, two.mean, one.mean);
}
