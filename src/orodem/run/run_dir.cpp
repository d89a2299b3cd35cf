#include "orodem/run/run_dir.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"

namespace fs = std::filesystem;

namespace orodem {

std::string choose_run_dir(const std::string& out, const std::string& config_path) {
    auto usable = [](const fs::path& p) { return !fs::exists(p) || (fs::is_directory(p) && fs::is_empty(p)); };
    if (!out.empty()) {
        std::error_code ec;
        if (fs::exists(out, ec) && !fs::is_directory(out, ec))
            throw ConfigError(fmt::format("--out {}: is a file, not a directory; choose a new directory", out));
        if (!usable(out))
            throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory "
                                          "(runs are never overwritten)", out));
        return out;
    }
    const std::string stem = fs::path(config_path).stem().string();
    for (int k = 1;; ++k) {
        const fs::path p = fs::path("runs") / (k == 1 ? stem : fmt::format("{}-{}", stem, k));
        if (usable(p)) return p.string();
    }
}

void require_run_dir(const std::string& dir) {
    std::error_code ec;
    if (!fs::exists(dir, ec))
        throw ConfigError(fmt::format("'{}': no such run directory", dir));
    if (!fs::is_directory(dir, ec))
        throw ConfigError(fmt::format("'{}': not a run directory (not a directory)", dir));
    if (!fs::exists(fs::path(dir) / "config.toml", ec))
        throw ConfigError(fmt::format("'{}': not a run directory (no config.toml)", dir));
}

std::size_t series_rows(const std::string& path) {
    if (!fs::exists(path)) return 0;
    const std::string text = read_file(path);
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    return lines > 0 ? lines - 1 : 0;
}

std::uint64_t free_bytes(const std::string& path) {
    struct statvfs s {};
    if (::statvfs(path.c_str(), &s) != 0) throw_io_error("cannot query free space of", path);
    return static_cast<std::uint64_t>(s.f_bavail) * static_cast<std::uint64_t>(s.f_frsize);
}

void check_free_space(const std::string& dir, const std::string& last_snapshot, std::uint64_t outputs_left,
                      std::uint64_t checkpoint_size) {
    const std::string name = fs::path(last_snapshot).stem().string();
    const std::uint64_t vtu = file_bytes(dir + "/" + last_snapshot);
    std::uint64_t pictures = 0;
    for (const char* kind : {"horizons", "displacement"}) {
        std::error_code ec;
        const auto n = fs::file_size(fmt::format("{}/figures/{}_{}.png", dir, kind, name), ec);
        if (!ec) pictures = std::max<std::uint64_t>(pictures, n);
    }
    const std::uint64_t need = outputs_left * (vtu + 2 * pictures) + 3 * checkpoint_size + (2u << 20);
    const std::uint64_t have = free_bytes(dir);
    if (have < need)
        throw IoError(fmt::format(
            "not enough free space for {}: the rest of the run needs about {:.1f} MB ({} outputs x ({:.2f} MB "
            "snapshot + 2 x {:.2f} MB pictures) + 3 x {:.2f} MB checkpoints + 2 MB), {:.1f} MB are free; free some "
            "space or choose --out on another disk, then resume with --resume",
            dir, static_cast<double>(need) / 1e6, outputs_left, static_cast<double>(vtu) / 1e6,
            static_cast<double>(pictures) / 1e6, static_cast<double>(checkpoint_size) / 1e6,
            static_cast<double>(have) / 1e6));
}

}  // namespace orodem
