// Helpers shared by the CLI tests (they run the real orodem binary):
// reading and writing files, shell quoting, running a command, starting one
// in the background, and comparing two run directories byte for byte.
#pragma once

#include <gtest/gtest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

/// EXPECT that text contains needle, showing the text when it does not.
#define EXPECT_HAS(text, needle) \
    EXPECT_NE(std::string(text).find(needle), std::string::npos) << "missing \"" << (needle) << "\" in:\n" << (text)

namespace cli {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline void write(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << p;
}

/// Single-quoted for /bin/sh.
inline std::string quote(const std::string& s) {
    std::string q = "'";
    for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

inline int count_lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

/// Runs a shell command; its stdout and stderr go to *out. Exit status, -1 if it did not exit.
inline int run(const std::string& cmd, std::string* out = nullptr) {
    FILE* f = popen((cmd + " 2>&1").c_str(), "r");
    if (!f) return -1;
    char buf[4096];
    std::string text;
    while (std::fgets(buf, sizeof buf, f)) text += buf;
    const int st = pclose(f);
    if (out) *out = text;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/// A background orodem process with its stdout/stderr files.
struct Proc {
    pid_t pid = -1;
    fs::path out, err;
};

/// Starts orodem with args, stdout/stderr into files beside `log_stem`.
inline Proc start(const std::vector<std::string>& args, const fs::path& log_stem) {
    Proc p;
    p.out = log_stem.string() + ".out";
    p.err = log_stem.string() + ".err";
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, p.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, p.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all = {ORODEM_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = posix_spawn(&p.pid, ORODEM_EXE, &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) p.pid = -1;
    return p;
}

/// Exit status, or 128 + signal when killed by one.
inline int wait_for(const Proc& p) {
    int st = 0;
    if (p.pid < 0 || waitpid(p.pid, &st, 0) != p.pid) return -1;
    if (WIFEXITED(st)) return WEXITSTATUS(st);
    if (WIFSIGNALED(st)) return 128 + WTERMSIG(st);
    return -1;
}

inline std::vector<std::string> names_in(const fs::path& dir) {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
}

/// series.csv, run.pvd, every snapshot and every snapshot picture byte for byte.
inline void expect_same_outputs(const fs::path& a, const fs::path& b) {
    EXPECT_EQ(slurp(b / "series.csv"), slurp(a / "series.csv")) << b;
    EXPECT_EQ(slurp(b / "faults.csv"), slurp(a / "faults.csv")) << b;
    EXPECT_EQ(slurp(b / "run.pvd"), slurp(a / "run.pvd")) << b;
    ASSERT_EQ(names_in(b / "snapshots"), names_in(a / "snapshots")) << b;
    for (const auto& n : names_in(a / "snapshots"))
        EXPECT_TRUE(slurp(b / "snapshots" / n) == slurp(a / "snapshots" / n)) << b / "snapshots" / n;
    int pictures = 0;
    for (const auto& n : names_in(a / "figures")) {
        if (n.rfind("horizons_", 0) != 0 && n.rfind("displacement_", 0) != 0) continue;
        ++pictures;
        EXPECT_TRUE(slurp(b / "figures" / n) == slurp(a / "figures" / n)) << b / "figures" / n;
    }
    EXPECT_GT(pictures, 5);
}

/// What a run of the orodem binary printed and returned.
struct Result {
    int status = -1;  // exit status, or -1 when the process did not exit normally
    std::string out, err;
};

/// A fixture with a fresh temporary folder per test (removed afterwards):
/// work_, where orodem runs, and capture_, where its output is kept.
class OrodemTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string tmpl = (fs::temp_directory_path() / "orodem-test-XXXXXX").string();
        ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
        root_ = tmpl;
        work_ = root_ / "work";
        capture_ = root_ / "capture";
        fs::create_directories(work_);
        fs::create_directories(capture_);
    }
    void TearDown() override {
        std::error_code ec;
        if (!root_.empty()) fs::remove_all(root_, ec);
    }

    /// Runs `orodem ARGS` in work_ (ARGS already shell-quoted where needed),
    /// with the environment assignments `env` (e.g. "ORODEM_ISA=sse2") before
    /// it; stdout and stderr go to files outside work_.
    Result orodem(const std::string& args, const std::string& env = "") {
        const fs::path out = capture_ / "stdout", err = capture_ / "stderr";
        const std::string cmd = "cd " + quote(work_.string()) + " && " + env + (env.empty() ? "" : " ") +
                                quote(ORODEM_EXE) + " " + args + " >" +
                                quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
        const int raw = std::system(cmd.c_str());
        Result r;
        r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
        r.out = slurp(out);
        r.err = slurp(err);
        return r;
    }

    fs::path root_, work_, capture_;
};

/// The rows of a CSV text (no quoting), each split at its commas.
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> f;
        std::istringstream l(line);
        for (std::string x; std::getline(l, x, ',');) f.push_back(x);
        rows.push_back(f);
    }
    return rows;
}

/// The index of column `name` in a CSV header (a test failure, and 0, when it has none).
inline std::size_t csv_column(const std::vector<std::string>& header, const std::string& name) {
    for (std::size_t k = 0; k < header.size(); ++k)
        if (header[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return 0;
}

/// A tiny exp1 (h0 = 6 m, S = 0.5, three outputs) whose packing cache lies in dir.
inline void write_tiny_exp1(const fs::path& dir, const std::string& name = "tiny.toml") {
    write(dir / name, "[run]\nexperiment = \"exp1\"\n"
                      "[wedge]\nv = 0.2\ns_max = 0.5\noutput_ds = 0.25\npro_margin = 3.0\nretro_length = 3.0\n"
                      "[packing]\nh0 = 6.0\ncache_dir = \"" + (dir / "cache").string() + "\"\n");
}

/// write_tiny_exp1 plus `extra` TOML appended; returns the file's path.
inline fs::path write_tiny_exp1_with(const fs::path& dir, const std::string& name, const std::string& extra) {
    write_tiny_exp1(dir, name);
    const fs::path p = dir / name;
    write(p, slurp(p) + extra);
    return p;
}

}  // namespace cli
