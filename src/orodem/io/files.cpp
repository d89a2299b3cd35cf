#include "orodem/io/files.hpp"

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include "orodem/core/error.hpp"

namespace orodem {

std::string temporary_name(const std::string& path) {
    // Unique per process and per call: two processes writing the same file
    // (two runs settling the same packing into the cache) never share one.
    static std::atomic<unsigned> counter{0};
    return fmt::format("{}.tmp-{}-{}", path, ::getpid(), counter.fetch_add(1));
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
    const std::string tmp = temporary_name(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw_io_error("cannot create", tmp);
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (w < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            ::unlink(tmp.c_str());
            errno = err;
            throw_io_error("cannot write", tmp);
        }
        done += static_cast<std::size_t>(w);
    }
    if (::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        ::unlink(tmp.c_str());
        errno = err;
        throw_io_error("cannot flush to disk", tmp);
    }
    if (::close(fd) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        errno = err;
        throw_io_error("cannot close", tmp);
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        errno = err;
        throw_io_error("cannot rename into place", path);
    }
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw_io_error("cannot open", path);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw_io_error("cannot read", path);
    return ss.str();
}

void make_dirs(const std::string& path) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec) throw IoError("cannot create directory '" + path + "': " + ec.message());
}

LineFile::LineFile(const std::string& path) : path_(path) {
    f_ = std::fopen(path.c_str(), "ab");
    if (!f_) throw_io_error("cannot open for writing", path);
}

LineFile& LineFile::operator=(LineFile&& o) noexcept {
    if (this != &o) {
        if (f_) std::fclose(f_);
        f_ = o.f_;
        path_ = std::move(o.path_);
        o.f_ = nullptr;
    }
    return *this;
}

LineFile::~LineFile() {
    if (f_) std::fclose(f_);
}

void LineFile::line(std::string_view text) {
    if (!f_) return;
    if (std::fwrite(text.data(), 1, text.size(), f_) != text.size() || std::fputc('\n', f_) == EOF ||
        std::fflush(f_) != 0)
        throw_io_error("cannot write", path_);
}

void LineFile::sync() {
    if (!f_) return;
    if (std::fflush(f_) != 0 || ::fsync(::fileno(f_)) != 0) throw_io_error("cannot flush to disk", path_);
}

std::uint64_t file_bytes(const std::string& path) {
    std::error_code ec;
    const auto n = std::filesystem::file_size(path, ec);
    if (ec) throw IoError(fmt::format("cannot stat '{}': {}", path, ec.message()));
    return static_cast<std::uint64_t>(n);
}

void truncate_file(const std::string& path, std::uint64_t bytes) {
    const std::uint64_t now = file_bytes(path);
    if (now < bytes)
        throw IoError(fmt::format("'{}' has {} bytes, fewer than the {} it had at the checkpoint; the run directory "
                                  "was changed after the checkpoint, so it cannot be resumed exactly",
                                  path, now, bytes));
    if (::truncate(path.c_str(), static_cast<off_t>(bytes)) != 0) throw_io_error("cannot truncate", path);
}

void remove_path(const std::string& path) {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
    if (ec) throw IoError(fmt::format("cannot remove '{}': {}", path, ec.message()));
}

}  // namespace orodem
