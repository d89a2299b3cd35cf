// Rng: xoshiro256** seeded through splitmix64. Its whole state is four
// uint64 words, so it can be checkpointed and resumed bit-exactly, and its
// output is identical on every platform (unlike std:: distributions).
#pragma once

#include <array>
#include <cstdint>

namespace orodem {

class Rng {
public:
    explicit Rng(std::uint64_t seed) {
        std::uint64_t z = seed;
        for (auto& w : s_) {
            z += 0x9e3779b97f4a7c15ULL;
            std::uint64_t t = z;
            t = (t ^ (t >> 30)) * 0xbf58476d1ce4e5b9ULL;
            t = (t ^ (t >> 27)) * 0x94d049bb133111ebULL;
            w = t ^ (t >> 31);
        }
    }
    std::uint64_t next_u64() {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }
    /// Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
    /// Uniform in [a, b).
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    const std::array<std::uint64_t, 4>& state() const { return s_; }
    void set_state(const std::array<std::uint64_t, 4>& s) { s_ = s; }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::array<std::uint64_t, 4> s_{};
};

}  // namespace orodem
