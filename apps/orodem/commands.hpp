// The subcommands of the orodem executable, one function each, called by
// main.cpp after CLI11 has parsed the arguments. Each returns the exit status
// and lets library errors propagate (main maps them to exit statuses).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace orodem {

struct CommonArgs {
    std::string config;
    std::vector<std::string> sets;
    int threads = -1;  // -1: from the config
};

int cmd_check(const CommonArgs& a);
int cmd_run(const CommonArgs& a, const std::string& out_arg);
int cmd_sweep(const CommonArgs& a, const std::string& vary, const std::string& out_arg);
int cmd_bench_pile(const std::string& pile, std::uint64_t steps, int threads);

}  // namespace orodem
