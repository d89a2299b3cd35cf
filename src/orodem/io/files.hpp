// Checked file writing. Every write goes to "<path>.tmp-<pid>-<n>" (unique to the
// process and the call), is flushed and fsync'ed, then renamed over <path>, so a crash or a full disk never leaves
// a half-written file under the final name. Failures throw IoError naming the
// path and the OS error.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>

namespace orodem {

/// Writes bytes to path atomically (tmp + fsync + rename).
void write_file_atomic(const std::string& path, std::string_view bytes);

/// Reads a whole regular file; throws IoError if it cannot be opened or read,
/// is not a regular file (a device such as /dev/zero, a FIFO or a socket would
/// block or never end) or is longer than max_bytes (0: no limit).
std::string read_file(const std::string& path, std::uint64_t max_bytes = 0);

/// Creates a directory and its parents; throws IoError on failure.
void make_dirs(const std::string& path);
/// The size of a file [bytes]; throws IoError if it cannot be queried.
std::uint64_t file_bytes(const std::string& path);
/// Cuts a file back to `bytes` (its length at a checkpoint); throws IoError
/// if it is shorter than that (changed since) or cannot be cut.
void truncate_file(const std::string& path, std::uint64_t bytes);
/// Removes a file or a directory tree if present; throws IoError on failure.
void remove_path(const std::string& path);

/// One writer per run directory or sweep folder: an advisory lock (flock) on
/// the directory itself, held while the object lives (the process's life,
/// for the commands that take it). The kernel drops it when the process
/// ends, however it ends, so a dead writer leaves no stale lock; children
/// started with exec do not inherit it. No file is added to the directory.
class DirLock {
public:
    DirLock() = default;
    DirLock(const DirLock&) = delete;
    DirLock& operator=(const DirLock&) = delete;
    DirLock(DirLock&& o) noexcept : fd_(o.fd_), id_(o.id_) { o.fd_ = -1; }
    DirLock& operator=(DirLock&& o) noexcept;
    ~DirLock();
    bool held() const { return fd_ >= 0; }

private:
    friend DirLock lock_dir(const std::string& dir, const std::string& what, double wait_s);
    void release();
    int fd_ = -1;
    std::pair<unsigned long, unsigned long> id_{};  // the directory's device and inode
};

/// Locks `dir` for this process. When another process holds it: waits up to
/// wait_s seconds for it, then throws ConfigError (exit 2, nothing changed)
/// naming `what`, the directory and the holder's pid (from /proc/locks).
DirLock lock_dir(const std::string& dir, const std::string& what, double wait_s = 0.0);
/// The pid of the process holding a flock on path (/proc/locks), or 0.
long lock_holder(const std::string& path);

/// An append-only text file (log.txt, series.csv) whose every line is
/// written and flushed at once, and whose errors throw IoError.
class LineFile {
public:
    LineFile() = default;
    explicit LineFile(const std::string& path);
    LineFile(const LineFile&) = delete;
    LineFile& operator=(const LineFile&) = delete;
    LineFile(LineFile&& o) noexcept : f_(o.f_), path_(std::move(o.path_)) { o.f_ = nullptr; }
    LineFile& operator=(LineFile&& o) noexcept;
    ~LineFile();
    void line(std::string_view text);
    /// Makes every line written so far durable (fsync): a checkpoint is
    /// written only after the files it expects are on disk.
    void sync();
    bool is_open() const { return f_ != nullptr; }

private:
    std::FILE* f_ = nullptr;
    std::string path_;
};

}  // namespace orodem
