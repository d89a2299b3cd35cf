#include "orodem/boundary/servo_wall.hpp"

#include <algorithm>
#include <cmath>

#include "orodem/core/bytes.hpp"
#include "orodem/engine/simulation.hpp"

namespace orodem {

ServoWalls::ServoWalls(std::vector<BoxSide> sides, double alpha, double integral_steps)
    : sides_(std::move(sides)), alpha_(alpha), integral_steps_(integral_steps) {
    const std::size_t n = sides_.size();
    std::size_t max_wall = 0;
    for (const BoxSide& s : sides_) max_wall = std::max(max_wall, s.wall);
    side_of_wall_.assign(n ? max_wall + 1 : 0, -1);
    for (std::size_t s = 0; s < n; ++s) side_of_wall_[sides_[s].wall] = static_cast<std::int32_t>(s);
    servo_.assign(n, 0);
    target_.assign(n, 0.0);
    v_max_.assign(n, 0.0);
    integral_.assign(n, 0.0);
    force_.assign(n, Vec2{});
    n_.assign(n, 0);
    stress_.assign(n, 0.0);
    elastic_.assign(n, 0.0);
    sum_stress_.assign(n, 0.0);
}

void ServoWalls::set_servo(std::size_t s, double target, double v_max) {
    if (!servo_[s]) integral_[s] = 0.0;
    servo_[s] = 1;
    target_[s] = target;
    v_max_[s] = v_max;
}

double ServoWalls::length(const Simulation& sim, std::size_t s) const {
    const BoxSide& b = sides_[s];
    if (b.span_a == BoxSide::kNoSpan || b.span_b == BoxSide::kNoSpan) return 1.0;
    const Vec2 t{-b.outward.y, b.outward.x};  // along the side
    return std::fabs(dot(sim.walls[b.span_b].a - sim.walls[b.span_a].a, t));
}

void ServoWalls::after_step(Simulation& sim) {
    const std::size_t ns = sides_.size();
    for (std::size_t s = 0; s < ns; ++s) {
        force_[s] = {};
        elastic_[s] = 0.0;
        n_[s] = 0;
    }
    // The forces the engine gathered this step (as Simulation::wall_force),
    // and the spring part k_n δ of each touching contact.
    const ParticleStore& p = sim.particles;
    const WallContactStore& ws = sim.wall_contacts;
    const std::size_t nw = side_of_wall_.size();
    const double k_n = sim.params.law.k_n, dt = sim.params.dt;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::uint32_t k = ws.begin[i]; k < ws.begin[i + 1]; ++k) {
            const std::size_t w = ws.wall[k];
            if (w >= nw || side_of_wall_[w] < 0) continue;
            const std::size_t s = static_cast<std::size_t>(side_of_wall_[w]);
            force_[s] -= ws.f[k];
            Vec2 cp;
            if (!wall_contact_point(sim.walls[w], p.x[i], cp)) continue;
            const Vec2 d = p.x[i] - cp;
            const double dist = norm(d);
            const double delta = p.radius[i] - dist;
            if (delta <= 0.0 || dist == 0.0) continue;
            ++n_[s];
            elastic_[s] += k_n * delta * -dot((1.0 / dist) * d, sides_[s].outward);
        }
    for (std::size_t s = 0; s < ns; ++s) {
        const double len = length(sim, s);
        stress_[s] = dot(force_[s], sides_[s].outward) / len;
        elastic_[s] /= len;
        sum_stress_[s] += stress_[s];
        if (!servo_[s]) continue;
        const double contacts = static_cast<double>(std::max<std::size_t>(n_[s], 1));
        const double gain = alpha_ * len / (k_n * contacts * dt);  // G [m/s per Pa]
        const double p_part = gain * (elastic_[s] - target_[s]);
        double v = p_part + integral_[s];
        if (std::fabs(v) > v_max_[s]) v = std::copysign(v_max_[s], v);  // clamped: the integral waits
        else integral_[s] += p_part / integral_steps_;
        sim.walls[sides_[s].wall].velocity = v * sides_[s].outward;
    }
    ++samples_;
}

double ServoWalls::mean_stress(std::size_t s) const {
    return samples_ ? sum_stress_[s] / static_cast<double>(samples_) : stress_[s];
}

void ServoWalls::reset_means() {
    std::fill(sum_stress_.begin(), sum_stress_.end(), 0.0);
    samples_ = 0;
}

void ServoWalls::save_state(ByteWriter& w) const {
    w.put(alpha_);
    w.put(integral_steps_);
    w.put_vector(integral_);
    w.put_vector(elastic_);
    w.put_vector(servo_);
    w.put_vector(target_);
    w.put_vector(v_max_);
    w.put_vector(force_);
    w.put(static_cast<std::uint64_t>(n_.size()));
    for (std::size_t c : n_) w.put(static_cast<std::uint64_t>(c));
    w.put_vector(stress_);
    w.put_vector(sum_stress_);
    w.put(samples_);
}

void ServoWalls::load_state(ByteReader& r) {
    alpha_ = r.get<double>();
    integral_steps_ = r.get<double>();
    r.get_vector(integral_);
    r.get_vector(elastic_);
    r.get_vector(servo_);
    r.get_vector(target_);
    r.get_vector(v_max_);
    r.get_vector(force_);
    n_.resize(static_cast<std::size_t>(r.get<std::uint64_t>()));
    for (std::size_t& c : n_) c = static_cast<std::size_t>(r.get<std::uint64_t>());
    r.get_vector(stress_);
    r.get_vector(sum_stress_);
    samples_ = r.get<std::uint64_t>();
}

}  // namespace orodem
