#include "orodem/io/files.hpp"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
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

std::string read_file(const std::string& path, std::uint64_t max_bytes) {
    // stat before open: opening a FIFO without a writer blocks, /dev/zero never ends.
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw_io_error("cannot open", path);
    if (!S_ISREG(st.st_mode))
        throw IoError(fmt::format("cannot read '{}': not a regular file ({}); give a file", path,
                                  S_ISDIR(st.st_mode) ? "a directory" : "a device, FIFO or socket"));
    if (max_bytes != 0 && static_cast<std::uint64_t>(st.st_size) > max_bytes)
        throw IoError(fmt::format("cannot read '{}': {} bytes, more than the {} such a file can have", path,
                                  st.st_size, max_bytes));
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

namespace {
// The directories this process holds (device, inode): a second lock_dir of
// one of them in the same process (a sweep member's run inside the member's
// lock) is granted without a second flock, which would conflict with the
// first.
std::set<std::pair<dev_t, ino_t>>& held_dirs() {
    static std::set<std::pair<dev_t, ino_t>> held;
    return held;
}
}  // namespace

DirLock& DirLock::operator=(DirLock&& o) noexcept {
    if (this != &o) {
        release();
        fd_ = o.fd_;
        id_ = o.id_;
        o.fd_ = -1;
    }
    return *this;
}

DirLock::~DirLock() { release(); }

void DirLock::release() {
    if (fd_ < 0) return;
    held_dirs().erase(id_);
    ::close(fd_);  // closing the last descriptor drops the flock
    fd_ = -1;
}

long lock_holder(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return 0;
    std::ifstream locks("/proc/locks");
    std::string line;
    // "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF": pid, then major:minor:inode
    while (std::getline(locks, line)) {
        std::istringstream in(line);
        std::string n, kind, mode, rw, dev;
        long pid = 0;
        if (!(in >> n >> kind >> mode >> rw >> pid >> dev) || kind != "FLOCK") continue;
        const auto colon = dev.rfind(':');
        if (colon == std::string::npos) continue;
        if (std::strtoull(dev.c_str() + colon + 1, nullptr, 10) == static_cast<unsigned long long>(st.st_ino)) return pid;
    }
    return 0;
}

DirLock lock_dir(const std::string& dir, const std::string& what, double wait_s) {
    DirLock lock;
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0) throw_io_error("cannot open", dir);
    if (held_dirs().count({st.st_dev, st.st_ino})) return lock;  // held by this process already (an outer lock)
    lock.fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (lock.fd_ < 0) throw_io_error("cannot open", dir);
    lock.id_ = {st.st_dev, st.st_ino};
    const auto t0 = std::chrono::steady_clock::now();
    while (::flock(lock.fd_, LOCK_EX | LOCK_NB) != 0) {
        if (errno == EINTR) continue;
        if (errno != EWOULDBLOCK) throw_io_error("cannot lock", dir);
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= wait_s) {
            const long pid = lock_holder(dir);
            throw ConfigError(fmt::format(
                "{} '{}' is in use by another orodem{}: one process writes it at a time, so nothing was changed; "
                "wait for it to end, or stop it{}",
                what, dir, pid > 0 ? fmt::format(" (pid {})", pid) : "",
                pid > 0 ? fmt::format(" (kill {}: it checkpoints and stops)", pid) : ""));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    held_dirs().insert(lock.id_);
    return lock;
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
