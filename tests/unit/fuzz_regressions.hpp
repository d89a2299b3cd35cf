// The saved fuzz inputs (tests/fuzz/regressions/<kind>/) that the regression
// tests replay: every regular file, in name order, with its bytes.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace orodem::test {

/// (file name, contents) of each saved input of one fuzzer; empty when the
/// folder is missing.
inline std::vector<std::pair<std::string, std::string>> fuzz_regressions(const std::string& kind) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(ORODEM_SOURCE_DIR) / "tests/fuzz/regressions" / kind;
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& f : files) {
        std::ifstream in(f, std::ios::binary);
        std::ostringstream ss;
        ss << in.rdbuf();
        out.emplace_back(f.filename().string(), ss.str());
    }
    return out;
}

}  // namespace orodem::test
