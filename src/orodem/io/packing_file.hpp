// Settled packings on disk, so that sweeps and reruns never repeat the
// settling. A packing is identified by a hash of everything that shapes it
// (packing section, material, gravity, timestep settings, format version);
// the cache file is <cache_dir>/packing-<hash>.bin.
//
// Format (little-endian): magic "ORODEMPK", u32 version, u64 key, u64 N,
// then per disc x, y, radius (f64), cluster (i32), initial_depth (f64), and
// a trailing u64 FNV-1a checksum of everything before it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "orodem/io/config.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

std::uint64_t packing_key(const Config& c);
/// Cache directory: packing.cache_dir, else $XDG_CACHE_HOME/orodem, else ~/.cache/orodem.
std::string packing_cache_dir(const Config& c);
std::string packing_cache_path(const Config& c);

/// The packing file's bytes (the format above), and writing them (atomic; the folder made first).
std::string encode_packing(const ParticleStore& p, std::uint64_t key);
void save_packing(const std::string& path, std::string_view bytes);
void save_packing(const std::string& path, const ParticleStore& p, std::uint64_t key);
/// The packing in `bytes` if intact with this key and every value sane (finite positions, positive radii, cluster
/// ids of the file); nullopt (and *why set) otherwise.
std::optional<ParticleStore> decode_packing(const std::string& bytes, std::uint64_t key, double density,
                                            std::string* why = nullptr);
/// The packing at path if it exists and is intact with this key; nullopt
/// (and *why set) if missing, corrupt or made from other parameters.
std::optional<ParticleStore> load_packing(const std::string& path, std::uint64_t key, double density,
                                          std::string* why = nullptr);

}  // namespace orodem
