// orodem run CONFIG [--out DIR] [--resume]: a new run directory and the run
// in it, or (--resume) the run in DIR continued (run/runner.hpp).
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
    make_dirs(dir);
    return start_run_in(c, n, dir, terminal);
}

}  // namespace orodem
