#include "orodem/core/error.hpp"

#include <cerrno>
#include <cstring>

namespace orodem {

void throw_io_error(const std::string& what, const std::string& path) {
    const int err = errno;
    throw IoError(what + " '" + path + "': " + std::strerror(err));
}

}  // namespace orodem
