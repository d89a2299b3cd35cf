// The Slurm side of a sweep (slurm.hpp): the batch scripts' text, sbatch,
// squeue and sacct as child processes (io/process: run_program), and the job
// list DIR/slurm/jobs.csv.
#include "orodem/run/slurm.hpp"


#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/process.hpp"

namespace orodem {

namespace fs = std::filesystem;

namespace {

/// Single-quoted for bash.
std::string sh_quote(const std::string& s) {
    std::string q = "'";
    for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

/// The first line of a program's output, for one-line errors.
std::string first_line(const std::string& s) {
    const std::string t = trimmed(s);
    const auto nl = t.find('\n');
    return nl == std::string::npos ? t : t.substr(0, nl);
}

/// The #SBATCH lines both scripts share.
std::string common_directives(const SlurmOptions& o) {
    std::string s = fmt::format("#SBATCH --nodes=1\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
    if (!o.partition.empty()) s += fmt::format("#SBATCH --partition={}\n", o.partition);
    if (!o.time.empty()) s += fmt::format("#SBATCH --time={}\n", o.time);
    for (const auto& a : o.sbatch_args) s += fmt::format("#SBATCH {}\n", a);
    return s;
}

}  // namespace

std::string slurm_dir(const std::string& sweep_dir) { return sweep_dir + "/slurm"; }

std::string slurm_array_script(const std::string& sweep_dir, const std::vector<std::string>& members,
                               const std::string& exe, const SlurmOptions& o) {
    const std::string name = fs::path(sweep_dir).filename().string();
    std::string list;
    for (std::size_t k = 0; k < members.size(); ++k)
        list += fmt::format("  {}  # task {}\n", sh_quote(members[k]), k);
    return fmt::format(
        "#!/bin/bash\n"
        "# orodem sweep --scheduler slurm: one array task per member of the sweep in\n"
        "# {dir}\n"
        "# Task k runs member k of the list below (sweep.toml's order) with --threads\n"
        "# equal to its CPUs: a finished member is kept, an interrupted one resumed from\n"
        "# its checkpoint, the others started. Its output goes to the member's\n"
        "# console.txt. SIGTERM {sig} s before the time limit makes it checkpoint and stop;\n"
        "# `orodem resume {dir} --scheduler slurm` then submits the unfinished members\n"
        "# again (by hand: sbatch --array=1,3 {dir}/slurm/array.sh).\n"
        "#SBATCH --job-name=orodem-{name}\n"
        "#SBATCH --array={array}\n"
        "{common}"
        "#SBATCH --signal=B:TERM@{sig}\n"
        "#SBATCH --output={dir}/slurm/slurm-%A_%a.out\n"
        "set -eu\n"
        "members=(\n{list})\n"
        "member={qdir}/\"${{members[$SLURM_ARRAY_TASK_ID]}}\"\n"
        "exec >>\"$member/console.txt\" 2>&1\n"
        "exec {exe} sweep-member \"$member\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"\n",
        fmt::arg("dir", sweep_dir), fmt::arg("qdir", sh_quote(sweep_dir)), fmt::arg("name", name),
        fmt::arg("array", members.empty() ? std::string("0") : fmt::format("0-{}", members.size() - 1)),
        fmt::arg("common", common_directives(o)), fmt::arg("sig", o.signal_before_s), fmt::arg("list", list),
        fmt::arg("exe", sh_quote(exe)));
}

std::string slurm_settle_script(const std::string& sweep_dir, const std::string& exe, const SlurmOptions& o) {
    const std::string name = fs::path(sweep_dir).filename().string();
    return fmt::format(
        "#!/bin/bash\n"
        "# orodem sweep --scheduler slurm: the packings that several members of the sweep in\n"
        "# {dir}\n"
        "# share, settled once before the array starts (it waits for this job:\n"
        "# --dependency=afterok). The log is {dir}/log.txt.\n"
        "#SBATCH --job-name=orodem-{name}-settle\n"
        "{common}"
        "#SBATCH --output={dir}/slurm/slurm-%j.out\n"
        "set -eu\n"
        "exec {exe} sweep-settle {qdir} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"\n",
        fmt::arg("dir", sweep_dir), fmt::arg("qdir", sh_quote(sweep_dir)), fmt::arg("name", name),
        fmt::arg("common", common_directives(o)), fmt::arg("exe", sh_quote(exe)));
}

std::string array_ranges(const std::vector<int>& ids) {
    std::string s;
    for (std::size_t i = 0; i < ids.size();) {
        std::size_t j = i;
        while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
        if (!s.empty()) s += ",";
        s += j == i ? fmt::format("{}", ids[i]) : fmt::format("{}-{}", ids[i], ids[j]);
        i = j + 1;
    }
    return s;
}

void require_slurm_command(const std::string& program) {
    if (find_on_path(program).empty())
        throw MissingToolError(fmt::format("{} is not installed or not on PATH: a sweep with --scheduler slurm "
                                           "needs Slurm's commands (Debian package slurm-client; on this machine "
                                           "scripts/local-slurm start sets up a single-node Slurm)",
                                           program));
}

std::string sbatch(const std::vector<std::string>& args, const std::string& script) {
    require_slurm_command("sbatch");
    std::vector<std::string> argv = {"sbatch", "--parsable"};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.push_back(script);
    const ProgramResult r = run_program(argv);
    // --parsable: "<id>" or "<id>;<cluster>"; anything else is sbatch's message.
    const std::string out = trimmed(r.output);
    const std::string last = out.substr(out.rfind('\n') == std::string::npos ? 0 : out.rfind('\n') + 1);
    const std::string id = last.substr(0, last.find(';'));
    const bool numeric = !id.empty() && std::all_of(id.begin(), id.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (r.status != 0 || !numeric)
        throw SchedulerError(fmt::format("sbatch {} refused the job{}: {}", script,
                                         r.status > 0 ? fmt::format(" (exit status {})", r.status) : std::string(),
                                         out.empty() ? std::string("no message") : first_line(out)));
    return id;
}

std::vector<SlurmJob> read_slurm_jobs(const std::string& sweep_dir) {
    const std::string path = slurm_dir(sweep_dir) + "/jobs.csv";
    std::vector<SlurmJob> jobs;
    if (!fs::exists(path)) return jobs;
    std::istringstream in(read_file(path));
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (number == 1 || line.empty()) continue;  // the header
        SlurmJob j;
        std::istringstream row(line);
        std::getline(row, j.id, ',');
        std::getline(row, j.kind, ',');
        std::getline(row, j.tasks);
        // The tasks may hold commas: the rest of the row, quoted.
        if (j.tasks.size() >= 2 && j.tasks.front() == '"' && j.tasks.back() == '"') j.tasks = j.tasks.substr(1, j.tasks.size() - 2);
        if (j.id.empty() || (j.kind != "array" && j.kind != "settle"))
            throw ConfigError(fmt::format("{}:{}: not a row of orodem's job list (job_id,kind,tasks): '{}'", path,
                                          number, line));
        jobs.push_back(j);
    }
    return jobs;
}

void record_slurm_job(const std::string& sweep_dir, const SlurmJob& job) {
    const std::string path = slurm_dir(sweep_dir) + "/jobs.csv";
    std::string text = fs::exists(path) ? read_file(path) : std::string("job_id,kind,tasks\n");
    text += fmt::format("{},{},\"{}\"\n", job.id, job.kind, job.tasks);
    write_file_atomic(path, text);
}

bool slurm_state_active(const std::string& state) {
    static const char* const active[] = {"PENDING", "RUNNING", "CONFIGURING", "COMPLETING", "SUSPENDED",
                                         "REQUEUED", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED",
                                         "REQUEUE_HOLD", "REQUEUE_FED", "RESV_DEL_HOLD"};
    return std::any_of(std::begin(active), std::end(active), [&](const char* a) { return state == a; });
}

bool slurm_state_pending(const std::string& state) { return state == "PENDING"; }

bool slurm_state_failed(const std::string& state) {
    return state == "FAILED" || state == "OUT_OF_MEMORY" || state == "NODE_FAIL";
}

SlurmQueue slurm_task_states(const std::vector<std::string>& ids) {
    SlurmQueue q;
    if (ids.empty()) return q;
    // sacct first (the older record), then squeue overrides with the live state.
    auto rank = [&](const std::string& id) {
        return static_cast<int>(std::find(ids.begin(), ids.end(), id) - ids.begin());
    };
    std::map<int, int> from_job;  // task id -> rank of the job its state came from
    auto take = [&](const std::string& job, const std::string& task, const std::string& state,
                    const std::string& source) {
        const int r = rank(job);
        if (r >= static_cast<int>(ids.size()) || task.empty()) return;
        if (!std::all_of(task.begin(), task.end(), [](char ch) { return ch >= '0' && ch <= '9'; })) return;
        const int k = std::atoi(task.c_str());
        const auto at = from_job.find(k);
        if (at != from_job.end() && at->second > r) return;
        from_job[k] = r;
        // CANCELLED by 0 -> CANCELLED
        q.tasks[k] = SlurmTaskState{job + "_" + task, state.substr(0, state.find(' ')), source};
    };
    std::string list;
    for (const auto& id : ids) list += (list.empty() ? "" : ",") + id;
    if (!find_on_path("sacct").empty()) {
        const ProgramResult r = run_program({"sacct", "-n", "-P", "-X", "-j", list, "-o", "JobID,State"});
        if (r.status == 0) {
            q.sacct = true;
            std::istringstream in(r.output);
            std::string line;
            while (std::getline(in, line)) {
                const auto bar = line.find('|'), us = line.find('_');
                if (bar == std::string::npos || us == std::string::npos || us > bar) continue;
                take(line.substr(0, us), line.substr(us + 1, bar - us - 1), trimmed(line.substr(bar + 1)), "sacct");
            }
        }
    }
    if (!find_on_path("squeue").empty()) {
        // Every task of this user's jobs (-r: one line per array task), filtered here:
        // squeue -j refuses the whole list when one job has left its memory.
        const ProgramResult r = run_program({"squeue", "-h", "-r", "--me", "-o", "%F|%K|%T"});
        if (r.status == 0) {
            q.squeue = true;
            std::istringstream in(r.output);
            std::string line;
            while (std::getline(in, line)) {
                const auto b1 = line.find('|'), b2 = line.find('|', b1 == std::string::npos ? 0 : b1 + 1);
                if (b1 == std::string::npos || b2 == std::string::npos) continue;
                take(line.substr(0, b1), line.substr(b1 + 1, b2 - b1 - 1), trimmed(line.substr(b2 + 1)), "squeue");
            }
        }
    }
    return q;
}

}  // namespace orodem
