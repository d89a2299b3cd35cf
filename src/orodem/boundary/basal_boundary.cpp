#include "orodem/boundary/basal_boundary.hpp"

#include "orodem/core/bytes.hpp"
#include "orodem/core/parallel.hpp"

namespace orodem {

void BasalBoundary::size_slots(std::size_t n) {
    traction_.resize(n);
    touching_.resize(n);
    sliding_slot_.resize(n);
}

void BasalBoundary::tally() {
    const std::size_t n = traction_.size();
    total_traction_ = deterministic_sum(n, [&](std::size_t c) { return traction_[c]; });
    on_base_ = 0;
    sliding_ = 0;
    for (std::size_t c = 0; c < n; ++c) {
        on_base_ += touching_[c];
        sliding_ += sliding_slot_[c];
    }
}

void BasalBoundary::save_state(ByteWriter& w) const {
    w.put(total_traction_);
    w.put(static_cast<std::uint64_t>(on_base_));
    w.put(static_cast<std::uint64_t>(sliding_));
}

void BasalBoundary::load_state(ByteReader& r) {
    total_traction_ = r.get<double>();
    on_base_ = static_cast<std::size_t>(r.get<std::uint64_t>());
    sliding_ = static_cast<std::size_t>(r.get<std::uint64_t>());
}

}  // namespace orodem
