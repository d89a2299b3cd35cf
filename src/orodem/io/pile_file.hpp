// Reader of the benchmark's plain pile file: '#' comment lines, then one
// disc a line, "id x y r". Discs get ids 0..N-1 in file order.
#pragma once

#include <string>

#include "orodem/state/particles.hpp"

namespace orodem {

/// Throws IoError if the file cannot be read, ConfigError if a line is malformed.
ParticleStore read_pile_file(const std::string& path, double density);

}  // namespace orodem
