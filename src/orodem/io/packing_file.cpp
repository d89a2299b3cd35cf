#include "orodem/io/packing_file.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/hash.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {
constexpr char kMagic[8] = {'O', 'R', 'O', 'D', 'E', 'M', 'P', 'K'};
constexpr std::uint32_t kVersion = 1;

template <class T>
void put(std::string& b, const T& v) { b.append(reinterpret_cast<const char*>(&v), sizeof(T)); }

template <class T>
bool get(const std::string& b, std::size_t& at, T& v) {
    if (at + sizeof(T) > b.size()) return false;
    std::memcpy(&v, b.data() + at, sizeof(T));
    at += sizeof(T);
    return true;
}
}  // namespace

std::uint64_t packing_key(const Config& c) {
    Fnv1a h;
    h.add(kVersion);
    const PackingConfig& p = c.packing;
    h.add_string(name_of(p.kind));
    h.add(p.r_min); h.add(p.r_max); h.add(p.length); h.add(p.h0); h.add(p.seed);
    h.add(p.settle_ke_ratio); h.add(p.settle_damping_ratio); h.add(p.wall_mu);
    const MaterialConfig& m = c.material;
    h.add(m.density); h.add(m.k_n); h.add(m.k_s_over_k_n); h.add(m.mu); h.add(m.cohesion);
    h.add(m.clamp_normal);
    h.add(c.numerics.dt); h.add(c.numerics.safety); h.add(c.numerics.skin); h.add(c.numerics.gravity);
    return h.value();
}

std::string packing_cache_dir(const Config& c) {
    if (!c.packing.cache_dir.empty()) return c.packing.cache_dir;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/orodem";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/orodem";
    return ".orodem-cache";
}

std::string packing_cache_path(const Config& c) {
    return fmt::format("{}/packing-{:016x}.bin", packing_cache_dir(c), packing_key(c));
}

std::string encode_packing(const ParticleStore& p, std::uint64_t key) {
    std::string b;
    b.append(kMagic, sizeof kMagic);
    put(b, kVersion);
    put(b, key);
    put(b, static_cast<std::uint64_t>(p.size()));
    for (std::uint32_t id = 0; id < p.size(); ++id) {
        const std::size_t s = p.slot_of_id[id];
        put(b, p.x[s].x); put(b, p.x[s].y); put(b, p.radius[s]);
        put(b, p.cluster[s]); put(b, p.initial_depth[s]);
    }
    Fnv1a h;
    h.add_bytes(b.data(), b.size());
    put(b, h.value());
    return b;
}

void save_packing(const std::string& path, std::string_view bytes) {
    const auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) make_dirs(dir.string());
    write_file_atomic(path, bytes);
}

void save_packing(const std::string& path, const ParticleStore& p, std::uint64_t key) {
    save_packing(path, encode_packing(p, key));
}

std::optional<ParticleStore> load_packing(const std::string& path, std::uint64_t key, double density,
                                          std::string* why) {
    auto reason = [&](const std::string& r) -> std::optional<ParticleStore> {
        if (why) *why = r;
        return std::nullopt;
    };
    if (!std::filesystem::exists(path)) return reason("no cached packing");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return reason("not a regular file");
    std::string b;
    try {
        b = read_file(path);
    } catch (const std::exception& e) {
        return reason(e.what());
    }
    return decode_packing(b, key, density, why);
}

std::optional<ParticleStore> decode_packing(const std::string& b, std::uint64_t key, double density,
                                            std::string* why) {
    auto reason = [&](const std::string& r) -> std::optional<ParticleStore> {
        if (why) *why = r;
        return std::nullopt;
    };
    if (b.size() < sizeof kMagic + 4 + 8 + 8 + 8 || std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
        return reason("not a packing file");
    Fnv1a h;
    h.add_bytes(b.data(), b.size() - 8);
    std::uint64_t stored = 0;
    std::memcpy(&stored, b.data() + b.size() - 8, 8);
    if (stored != h.value()) return reason("checksum mismatch (corrupt file)");
    std::size_t at = sizeof kMagic;
    std::uint32_t version = 0;
    std::uint64_t file_key = 0, n = 0;
    get(b, at, version); get(b, at, file_key); get(b, at, n);
    if (version != kVersion) return reason(fmt::format("format version {} (this program reads {})", version, kVersion));
    if (file_key != key) return reason("made from other parameters");
    const std::size_t rec = 3 * 8 + 4 + 8;
    if (b.size() != at + n * rec + 8) return reason("truncated");
    // A checksum guards against damage, not against a file made to pass it:
    // every value is checked before it is used (a bad one is a corrupt cache,
    // settled again, never a crash).
    constexpr double kMaxCoordinate = 1e9, kMaxRadius = 1e6;  // [m]
    ParticleStore p;
    for (std::uint64_t k = 0; k < n; ++k) {
        double x = 0, y = 0, r = 0, depth = 0;
        std::int32_t cl = 0;
        get(b, at, x); get(b, at, y); get(b, at, r); get(b, at, cl); get(b, at, depth);
        if (!(std::fabs(x) <= kMaxCoordinate && std::fabs(y) <= kMaxCoordinate))
            return reason(fmt::format("disc {} at ({}, {}) m: not a position", k, x, y));
        if (!(r > 0.0 && r <= kMaxRadius)) return reason(fmt::format("disc {} has radius {} m", k, r));
        if (cl < -1 || (cl >= 0 && static_cast<std::uint64_t>(cl) >= n))  // -1: a free disc; else at most n clusters
            return reason(fmt::format("disc {} has cluster id {}", k, cl));
        if (!std::isfinite(depth)) return reason(fmt::format("disc {} has initial depth {}", k, depth));
        const std::size_t s = p.add({x, y}, r, density, cl);
        p.initial_depth[s] = depth;
    }
    return p;
}

}  // namespace orodem
