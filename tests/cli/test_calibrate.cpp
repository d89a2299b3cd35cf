// orodem calibrate: a tiny run of each calibration experiment into a temp
// directory (config written here, small sizes) exits 0 and writes report.md,
// the summary and per-test CSVs and the plots; the run-directory contract of
// orodem run holds (a non-empty --out is refused with exit 2); orodem run
// and orodem sweep refuse a calibration config, orodem calibrate any other; orodem check
// prints a calibration's setup.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

/// Runs orodem with args (stdout and stderr into *out); the exit status.
int orodem(const std::string& args, std::string* out = nullptr) { return cli::run(std::string(ORODEM_EXE) + " " + args, out); }

std::string read_all(const fs::path& p) { return cli::slurp(p); }
void write_text(const fs::path& p, const std::string& text) { cli::write(p, text); }
int lines(const std::string& s) { return cli::count_lines(s); }

class Calibrate : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("orodem_calibrate_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_);
    }
    fs::path dir_;
};

const char* kMaterial = "[material]\nk_n = 1.5e8\n[packing]\nr_min = 0.5\nr_max = 1.0\n";

}  // namespace

TEST_F(Calibrate, BiaxialWritesReportCsvsAndPlots) {
    const fs::path cfg = dir_ / "biax.toml";
    write_text(cfg, std::string("[run]\nexperiment = \"biaxial\"\nthreads = 1\n[calibrate]\n"
                                "kinds = [\"discs\", \"clusters\"]\nmu_values = [0.0, 0.5]\nwidth = 10.0\n"
                                "height = 20.0\nmax_strain = 0.02\ncritical_from = 0.01\noutput_strain = 0.0025\n") +
                        kMaterial);
    const fs::path out = dir_ / "run";
    std::string text;
    ASSERT_EQ(orodem("calibrate " + cfg.string() + " --out " + out.string(), &text), 0) << text;
    for (const char* f : {"config.toml", "log.txt", "report.md", "biaxial.csv", "biaxial.png", "biaxial-angles.png",
                          "biaxial-discs-mu0.csv", "biaxial-discs-mu0.5.csv", "biaxial-clusters-mu0.csv",
                          "biaxial-clusters-mu0.5.csv"})
        EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
    const std::string summary = read_all(out / "biaxial.csv");
    EXPECT_EQ(lines(summary), 5);  // header + 2 kinds x 2 values
    EXPECT_EQ(summary.rfind("kind,mu,phi_peak_deg,", 0), 0u);
    EXPECT_EQ(lines(read_all(out / "biaxial-discs-mu0.5.csv")), 1 + 8);  // 0.02 / 0.0025 rows
    const std::string md = read_all(out / "report.md");
    for (const char* s : {"# orodem calibration: biaxial", "| discs | 0.5 |", "| clusters | 0 |", "](biaxial.png)",
                          "inertial number", "orodem calibrate "})
        EXPECT_NE(md.find(s), std::string::npos) << s;
    EXPECT_EQ(read_all(out / "biaxial.png").substr(1, 3), "PNG");
    // The resolved config reads back (orodem check) and the directory is never overwritten.
    EXPECT_EQ(orodem("check " + (out / "config.toml").string(), &text), 0) << text;
    EXPECT_EQ(orodem("calibrate " + cfg.string() + " --out " + out.string(), &text), 2) << text;
    EXPECT_NE(text.find("not empty"), std::string::npos) << text;
}

TEST_F(Calibrate, BasalFrictionAndReposeRun) {
    const fs::path basal = dir_ / "basal.toml", repose = dir_ / "repose.toml";
    write_text(basal, std::string("[run]\nexperiment = \"basal-friction\"\nthreads = 1\n[calibrate]\n"
                                  "kinds = [\"discs\"]\nmu_bp_values = [0.1, 0.3]\nblock_length = 10.0\n"
                                  "block_height = 5.0\nbelt_speed = 0.15\nduration = 3.0\n") +
                          kMaterial);
    write_text(repose, std::string("[run]\nexperiment = \"repose\"\nthreads = 1\n[calibrate]\n"
                                   "kinds = [\"clusters\"]\nmu_values = [0.5]\ncolumn_width = 6.0\n"
                                   "column_height = 12.0\nlift_speed = 4.0\n") +
                           kMaterial);
    std::string text;
    ASSERT_EQ(orodem("calibrate " + basal.string() + " --out " + (dir_ / "b").string(), &text), 0) << text;
    for (const char* f : {"report.md", "basal-friction.csv", "basal-friction.png", "basal-friction-series.png",
                          "basal-friction-discs-mu_bp0.1.csv",
                          "basal-friction-discs-mu_bp0.3.csv"})
        EXPECT_TRUE(fs::is_regular_file(dir_ / "b" / f)) << f;
    EXPECT_EQ(lines(read_all(dir_ / "b" / "basal-friction.csv")), 3);
    EXPECT_NE(read_all(dir_ / "b" / "report.md").find("| discs | 0.3 | 16.7 | 0."), std::string::npos)
        << read_all(dir_ / "b" / "report.md");  // μ_bp, atan μ_bp, measured μ_eff
    ASSERT_EQ(orodem("calibrate " + repose.string() + " --out " + (dir_ / "r").string(), &text), 0) << text;
    for (const char* f : {"report.md", "repose.csv", "repose.png", "repose-clusters-mu0.5.csv"})
        EXPECT_TRUE(fs::is_regular_file(dir_ / "r" / f)) << f;
    EXPECT_NE(read_all(dir_ / "r" / "report.md").find("| clusters | 0.5 |"), std::string::npos);
}

TEST_F(Calibrate, WrongCommandForTheExperimentIsRefused) {
    const fs::path calib = dir_ / "calib.toml", settle = dir_ / "settle.toml";
    write_text(calib, "[run]\nexperiment = \"repose\"\n");
    write_text(settle, "[run]\nexperiment = \"settle\"\n");
    std::string text;
    EXPECT_EQ(orodem("run " + calib.string() + " --out " + (dir_ / "a").string(), &text), 2) << text;
    EXPECT_NE(text.find("orodem calibrate"), std::string::npos) << text;
    EXPECT_FALSE(fs::exists(dir_ / "a"));
    EXPECT_EQ(orodem("sweep " + calib.string() + " --vary material.mu=0.1,0.2 --out " + (dir_ / "s").string(), &text),
              2)
        << text;
    EXPECT_FALSE(fs::exists(dir_ / "s"));
    EXPECT_EQ(orodem("calibrate " + settle.string() + " --out " + (dir_ / "b").string(), &text), 2) << text;
    EXPECT_NE(text.find("not a calibration experiment"), std::string::npos) << text;
    EXPECT_FALSE(fs::exists(dir_ / "b"));
    // A bad value is refused before anything is written.
    EXPECT_EQ(orodem("calibrate " + calib.string() + " --set calibrate.fit_to=2.0 --out " + (dir_ / "c").string(),
                     &text),
              2)
        << text;
    EXPECT_FALSE(fs::exists(dir_ / "c"));
}

TEST_F(Calibrate, CheckPrintsTheSetup) {
    std::string text;
    ASSERT_EQ(orodem(std::string("check ") + ORODEM_SOURCE_DIR + "/configs/calibrate/biaxial.toml", &text), 0)
        << text;
    for (const char* s : {"[calibrate]", "tests                  = 10", "inertial number I = 0.001", "strain_rate = "})
        EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
    for (const char* cfg : {"basal-friction.toml", "repose.toml"})
        EXPECT_EQ(orodem(std::string("check ") + ORODEM_SOURCE_DIR + "/configs/calibrate/" + cfg, &text), 0)
            << cfg << "\n" << text;
    EXPECT_NE(text.find("repose"), std::string::npos);
}
