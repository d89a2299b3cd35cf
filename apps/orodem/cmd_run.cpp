// orodem run CONFIG [--out DIR] [--resume]: a new run directory and the run
// in it, or (--resume) the run in DIR continued (run/runner.hpp); orodem
// resume DIR --s-max S: the run in DIR extended to S (extend_run).
#include <filesystem>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/run/run_dir.hpp"
#include "orodem/run/runner.hpp"

#include "cli.hpp"
#include "commands.hpp"

namespace orodem {

int cmd_run(const CommonArgs& a, const std::string& out_arg, bool resume) {
    const Config c = load_for_run(a);
    const RunNumbers n = check_runnable(c);
    set_threads(c);
    TerminalObserver terminal;
    if (resume) return resume_run(c, n, out_arg, terminal);
    const std::string dir = choose_run_dir(out_arg, c.path);
    check_run_time(c, n, a.force, "the run");
    make_dirs(dir);
    return start_run_in(c, n, dir, terminal);
}

int cmd_extend(const std::string& dir, double s_max, int threads) {
    if (std::filesystem::exists(dir + "/sweep.toml"))
        throw ConfigError(fmt::format("orodem resume {} --s-max {:g}: {} is a sweep's folder; --s-max extends one run: "
                                      "orodem resume {}/<member> --s-max {:g} for each member",
                                      dir, s_max, dir, dir, s_max));
    require_run_dir(dir);
    CommonArgs a{dir + "/config.toml", {}, threads};
    const Config saved = load_for_run(a);
    for (const auto& [key, value] : extension_overrides(saved, s_max, dir)) a.sets.push_back(key + "=" + value);
    const Config c = load_for_run(a);
    const RunNumbers n = check_runnable(c);
    set_threads(c);
    TerminalObserver terminal;
    return extend_run(saved, c, n, dir, terminal);
}

}  // namespace orodem
