// orodem sweep and orodem resume. A sweep is one run per value of a config
// key, DIR/<key>=<value>/, then the overlay plots. The paper's sweeps take
// hours per member, so a sweep must survive what a single run survives:
// before the first member runs, DIR/sweep.toml records the sweep and every
// member's resolved config.toml is written, and `orodem resume DIR` then
// goes through the members in order: a finished one is kept, an interrupted
// one is resumed from its checkpoint (bit for bit as if never stopped), one
// not started yet is started. A member that goes unstable does not stop the
// others: it is reported, skipped on resume, and the sweep exits with 3.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/io/sweep_manifest.hpp"

namespace orodem {

namespace fs = std::filesystem;

namespace {

/// Splits "key=v1,v2,..." into the key and its values.
std::pair<std::string, std::vector<std::string>> parse_vary(const std::string& text) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw ConfigError(fmt::format("--vary '{}': expected key=v1,v2,..., e.g. --vary wedge.mu_bp=0.1,0.2,0.3", text));
    std::vector<std::string> values;
    std::string rest = text.substr(eq + 1);
    for (std::size_t pos = 0;;) {
        const auto comma = rest.find(',', pos);
        values.push_back(rest.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
        if (comma == std::string::npos) break;
        pos = comma + 1;
    }
    for (const auto& v : values)
        if (v.empty()) throw ConfigError(fmt::format("--vary '{}': empty value in the list", text));
    for (std::size_t i = 0; i < values.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (values[i] == values[j])
                throw ConfigError(fmt::format("--vary '{}': the value {} is listed twice; each value is one run",
                                              text, values[i]));
    return {text.substr(0, eq), values};
}

/// Runs, continues or keeps one member; its exit status (0 when kept).
int run_member(const Config& c, const std::string& dir, const std::string& label) {
    if (!is_wedge(c)) {
        // A settled layer is not checkpointed: done when its packing is written, else settled again.
        if (fs::exists(dir + "/packing.bin")) {
            fmt::print("sweep: {}: finished already, kept ({})\n", label, dir);
            return 0;
        }
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().filename() != "config.toml") fs::remove_all(e.path());
        fmt::print("sweep: {} -> {}\n", label, dir);
        return start_run_in(c, dir);
    }
    if (!fs::exists(dir + "/log.txt")) {
        fmt::print("sweep: {} -> {}\n", label, dir);
        return start_run_in(c, dir);
    }
    if (last_run_event_is(dir, "finished:")) {
        fmt::print("sweep: {}: finished already, kept ({})\n", label, dir);
        return 0;
    }
    if (last_run_event_is(dir, "UNSTABLE:") || last_run_event_is(dir, "STOPPED:")) {
        // Resuming would repeat the same failure from the same state.
        fmt::print(stderr, "orodem: sweep: {}: ended with an error before (see {}/log.txt); skipped\n", label, dir);
        return static_cast<int>(ExitCode::unstable);
    }
    fmt::print("sweep: {}: continuing {}\n", label, dir);
    return resume_run(c, dir);
}

/// The members of the sweep in root, in order; then the overlay plots. The
/// configs come from the members' config.toml (threads >= 0 overrides run.threads).
int run_members(const std::string& root, const SweepManifest& m, int threads) {
    std::vector<std::string> dirs;
    std::vector<std::string> failed;
    bool all_wedges = true;
    for (const auto& v : m.values) {
        const std::string dir = sweep_member_dir(root, m, v);
        const std::string label = fmt::format("{} = {}", m.key, v);
        if (!fs::exists(dir + "/config.toml"))
            throw ConfigError(fmt::format("{}/config.toml: missing; the sweep folder {} was changed since orodem sweep "
                                          "wrote it, so it cannot be continued",
                                          dir, root));
        CommonArgs one;
        one.config = dir + "/config.toml";
        one.threads = threads;
        const Config c = load(one);
        check_runnable(c);
        set_threads(c);
        all_wedges = all_wedges && is_wedge(c);
        int rc = 0;
        try {
            rc = run_member(c, dir, label);
        } catch (const InterruptedError&) {
            // While settling (not checkpointed): the member settles again when the sweep continues.
            fmt::print(stderr, "orodem: the sweep stopped at {}; continue it with: orodem resume {}\n", label, root);
            throw;
        } catch (const InstabilityError& e) {
            // The run has logged it and kept its last good state; the other members still run.
            fmt::print(stderr, "orodem: sweep: {}: unstable: {}\n", label, e.what());
            rc = static_cast<int>(ExitCode::unstable);
        }
        if (rc == static_cast<int>(ExitCode::unstable)) {
            failed.push_back(label);
            continue;
        }
        if (rc != 0) {
            // Interrupted, stopped at the wall-time limit or by a full disk: with a checkpoint.
            fmt::print(stderr, "orodem: the sweep stopped at {}; continue it with: orodem resume {}\n", label, root);
            return rc;
        }
        dirs.push_back(dir);
    }
    // A sweep over the seeds is an ensemble: its mean over the seeds' band.
    if (all_wedges && !dirs.empty()) cmd_plot(dirs, root + "/plots.png", is_seed_key(m.key));
    fmt::print("sweep outputs in {}/\n", root);
    if (!failed.empty()) {
        std::string list;
        for (const auto& f : failed) list += (list.empty() ? "" : ", ") + f;
        fmt::print(stderr, "orodem: sweep: {} of {} runs went unstable ({}); the plots leave them out\n",
                   failed.size(), m.values.size(), list);
        return static_cast<int>(ExitCode::unstable);
    }
    return 0;
}

}  // namespace

int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg) {
    const auto [key, values] = parse_vary(vary);
    // Validate every member of the sweep before writing anything.
    std::vector<Config> configs;
    for (const auto& v : values) {
        CommonArgs one = a;
        one.sets.push_back(key + "=" + v);
        Config c = load(one);
        if (is_calibration(c))
            throw ConfigError(fmt::format("{}: run.experiment = \"{}\" is a calibration experiment, which sweeps "
                                          "its own [calibrate] lists: run it with orodem calibrate", c.path,
                                          c.run.experiment));
        check_runnable(c);
        configs.push_back(std::move(c));
    }
    const std::string stem = fs::path(a.config).stem().string();
    const std::string root = out_arg.empty() ? choose_run_dir("", stem + "-sweep") : out_arg;
    if (!out_arg.empty() && fs::exists(root) && !fs::is_empty(root))
        throw ConfigError(fmt::format("--out {}: directory exists and is not empty; choose a new directory{}", root,
                                      fs::exists(sweep_manifest_path(root))
                                          ? fmt::format(", or continue the sweep in it with: orodem resume {}", root)
                                          : std::string()));
    SweepManifest m{a.config, key, values, a.sets};
    make_dirs(root);
    for (std::size_t k = 0; k < values.size(); ++k) {
        const std::string dir = sweep_member_dir(root, m, values[k]);
        make_dirs(dir);
        write_file_atomic(dir + "/config.toml", to_toml(configs[k]));
    }
    write_file_atomic(sweep_manifest_path(root), to_toml(m));
    return run_members(root, m, a.threads);
}

int cmd_resume(const std::string& dir, int threads) {
    if (fs::exists(sweep_manifest_path(dir))) {
        const SweepManifest m = read_sweep_manifest(dir);
        fmt::print("continuing the sweep in {} ({} = {} values)\n", dir, m.key, m.values.size());
        return run_members(dir, m, threads);
    }
    CommonArgs a;
    a.config = dir + "/config.toml";
    a.threads = threads;
    return cmd_run(a, dir, true);
}

}  // namespace orodem
