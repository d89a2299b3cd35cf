// FixedRetroside: Experiments 1 and 2 ([42], [44]). Every disc that touches
// the retroside base wall (positive normal force) is held fixed in space from
// then on (ParticleStore::fix: zero velocity, zero inverse mass). Checked
// after each step; the fixed set only grows.
#pragma once

#include <cstddef>

#include "orodem/engine/boundary.hpp"

namespace orodem {

class FixedRetroside : public Boundary {
public:
    explicit FixedRetroside(std::size_t wall) : wall_(wall) {}
    std::string_view name() const override { return "fixed-retroside"; }
    ForceHook force_hook() const override { return ForceHook::none; }
    void after_step(Simulation& sim) override;
    std::size_t fixed_count() const { return fixed_; }
    void save_state(ByteWriter& w) const override;
    void load_state(ByteReader& r) override;

private:
    std::size_t wall_;
    std::size_t fixed_ = 0;
};

}  // namespace orodem
