// FNV-1a 64-bit over raw bytes: used to hash configs (packing cache keys) and
// full states (determinism tests). Not cryptographic; stable across platforms
// of the same endianness.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace orodem {

class Fnv1a {
public:
    void add_bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t k = 0; k < n; ++k) {
            h_ ^= p[k];
            h_ *= 0x100000001b3ULL;
        }
    }
    template <class T>
    void add(const T& v) { add_bytes(&v, sizeof(T)); }
    template <class T>
    void add_span(std::span<const T> s) { add_bytes(s.data(), s.size_bytes()); }
    void add_string(std::string_view s) { add(s.size()); add_bytes(s.data(), s.size()); }
    std::uint64_t value() const { return h_; }

private:
    std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace orodem
