#include "orodem/io/pile_file.hpp"

#include <sstream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

ParticleStore read_pile_file(const std::string& path, double density) {
    std::istringstream in(read_file(path));
    ParticleStore p;
    std::string line;
    int lineno = 0;
    while (std::getline(in, line)) {
        ++lineno;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream ls(line);
        long long id = 0;
        double x = 0, y = 0, r = 0;
        if (!(ls >> id >> x >> y >> r) || r <= 0.0)
            throw ConfigError(fmt::format("{}:{}: expected 'id x y r' with r > 0, got '{}'", path, lineno, line));
        p.add({x, y}, r, density);
    }
    return p;
}

}  // namespace orodem
