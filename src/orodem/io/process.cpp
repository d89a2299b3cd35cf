#include "orodem/io/process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include <filesystem>

extern char** environ;

namespace orodem {

std::string find_on_path(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";  // posix_spawnp's own default
    std::size_t start = 0;
    while (start <= dirs.size()) {
        const std::size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string dir = dirs.substr(start, end - start);
        if (!dir.empty()) {
            const std::string candidate = dir + "/" + name;
            if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return candidate;
        }
        start = end + 1;
    }
    return "";
}

bool die_with_parent() {
    const char* parent = std::getenv("ORODEM_PARENT_PID");
    if (!parent || !*parent) return true;
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    return ::getppid() == static_cast<pid_t>(std::strtol(parent, nullptr, 10));  // not reparented already
}

int spawn_child(const std::vector<std::string>& args, const ChildIo& io, pid_t& pid) {
    std::vector<std::string> copy = args;
    std::vector<char*> argv;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    if (io.out_fd >= 0) {
        posix_spawn_file_actions_adddup2(&fa, io.out_fd, STDOUT_FILENO);
        posix_spawn_file_actions_adddup2(&fa, io.out_fd, STDERR_FILENO);
        posix_spawn_file_actions_addclose(&fa, io.out_fd);
    } else {
        posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, io.log.c_str(),
                                         O_WRONLY | O_CREAT | (io.append ? O_APPEND : O_TRUNC), 0644);
        posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
    }
    if (io.close_fd >= 0) posix_spawn_file_actions_addclose(&fa, io.close_fd);
    posix_spawnattr_t at;
    posix_spawnattr_init(&at);
    if (io.new_group) {
        posix_spawnattr_setpgroup(&at, 0);
        posix_spawnattr_setflags(&at, POSIX_SPAWN_SETPGROUP);
    }
    std::vector<std::string> env_copy;
    std::vector<char*> envp;
    if (io.parent_env) {
        for (char** e = environ; *e; ++e)
            if (std::strncmp(*e, "ORODEM_PARENT_PID=", 18) != 0) env_copy.emplace_back(*e);
        env_copy.push_back("ORODEM_PARENT_PID=" + std::to_string(::getpid()));
        for (auto& e : env_copy) envp.push_back(e.data());
        envp.push_back(nullptr);
    }
    pid = -1;
    const int rc = posix_spawnp(&pid, argv[0], &fa, &at, argv.data(), io.parent_env ? envp.data() : environ);
    posix_spawnattr_destroy(&at);
    posix_spawn_file_actions_destroy(&fa);
    return rc;
}

int wait_child(pid_t pid) {
    int st = 0;
    while (::waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

ProgramResult run_program(const std::vector<std::string>& args) {
    ProgramResult r;
    int fds[2];
    if (::pipe(fds) != 0) return r;
    ChildIo io;
    io.out_fd = fds[1];
    io.close_fd = fds[0];
    pid_t pid = -1;
    const int rc = spawn_child(args, io, pid);
    ::close(fds[1]);
    if (rc != 0) {
        ::close(fds[0]);
        return r;
    }
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(fds[0], buf, sizeof buf);
        if (n > 0) r.output.append(buf, static_cast<std::size_t>(n));
        else if (n == 0 || errno != EINTR) break;
    }
    ::close(fds[0]);
    r.status = wait_child(pid);
    return r;
}

}  // namespace orodem
