// `orodem plot` and `orodem render` on a run directory built by hand:
// config.toml, series.csv (with NaN rows: no wedge yet), two VTU snapshots
// and run.pvd. Also the legend labels and the series reader directly.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"
#include <stdlib.h>
#include <sys/wait.h>

#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "orodem/core/error.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/io/vtu_writer.hpp"
#include "orodem/state/particles.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

std::string config_text(double mu_bp, int threads = 1) {
    std::ostringstream s;
    s << "# resolved\n\n[packing]\nh0 = 2.0\nkind = 'clusters'\n\n[run]\nexperiment = 'exp1'\nthreads = " << threads
      << "\n\n[wedge]\nmu_bp = " << mu_bp << "\nv = 0.2\n";
    return s.str();
}

const char* kHeader =
    "step,time,S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,kinetic_energy,contacts\n";

/// Decoded PNG size and how many pixels are close to (r, g, b) (0-255).
struct Png {
    int width = 0, height = 0;
    long matching = 0;
    bool ok = false;
};
Png decode_png(const fs::path& p, int r = -1, int g = -1, int b = -1) {
    Png out;
    cairo_surface_t* s = cairo_image_surface_create_from_png(p.c_str());
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
        out.ok = true;
        out.width = cairo_image_surface_get_width(s);
        out.height = cairo_image_surface_get_height(s);
        cairo_surface_flush(s);
        const unsigned char* data = cairo_image_surface_get_data(s);
        const int stride = cairo_image_surface_get_stride(s);
        for (int y = 0; y < out.height && r >= 0; ++y)
            for (int x = 0; x < out.width; ++x) {
                std::uint32_t px;
                std::memcpy(&px, data + y * stride + 4 * x, 4);
                const int pr = (px >> 16) & 255, pg = (px >> 8) & 255, pb = px & 255;
                if (std::abs(pr - r) < 12 && std::abs(pg - g) < 12 && std::abs(pb - b) < 12) ++out.matching;
            }
    }
    cairo_surface_destroy(s);
    return out;
}

class PlotRender : public OrodemTest {
protected:
    /// A run directory as `orodem run` leaves it, small: 12 discs, two snapshots.
    fs::path make_run(const std::string& rel, double mu_bp) {
        const fs::path dir = work_ / rel;
        fs::create_directories(dir / "snapshots");
        fs::create_directories(dir / "figures");
        write(dir / "config.toml", config_text(mu_bp));
        write(dir / "series.csv", std::string(kHeader) +
                                      "0,0,0.000000,0.1,nan,-nan,0.5,nan,0,40\n"
                                      "10,1,0.250000,0.2,nan,nan,0.1,20,3.5,41\n"
                                      "20,2,0.500000,0.3,12.5,8.25,-0.2,35,3.1,42\n"
                                      "30,3,0.750000,0.35,14," + std::to_string(9.0 + mu_bp) + ",-0.3,nan,2.9,43\n"
                                      "40,4,1.000000,0.4,15,10,-0.4,50,2.8,44\n");
        for (int snap = 0; snap < 2; ++snap) {
            orodem::ParticleStore p;
            std::vector<double> rel_disp;
            for (int k = 0; k < 12; ++k) {
                const double x = -6.0 + k + 0.3 * snap * (k > 6), y = 0.5 + (k % 3);
                const std::size_t s = p.add({x, y}, 0.45, 2500.0);
                p.initial_depth[s] = 3.0 - y;
                p.side[s] = k > 6 ? 1 : 0;
                rel_disp.push_back(snap == 0 ? 0.0 : k / 11.0);
            }
            orodem::write_vtu((dir / (snap == 0 ? "snapshots/S00.000.vtu" : "snapshots/S01.000.vtu")).string(), p,
                              rel_disp);
        }
        orodem::write_pvd((dir / "run.pvd").string(),
                          {{0.0, "snapshots/S00.000.vtu"}, {1.0, "snapshots/S01.000.vtu"}});
        return dir;
    }
};

}  // namespace

TEST_F(PlotRender, PlotOfOneRunWritesADecodablePng) {
    const fs::path run = make_run("r1", 0.3);
    const Result r = orodem("plot r1");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const fs::path png = run / "figures" / "plots.png";
    ASSERT_TRUE(fs::exists(png));
    // The first run's colour is (0.12, 0.47, 0.71): its lines are drawn.
    const Png d = decode_png(png, 31, 120, 181);
    ASSERT_TRUE(d.ok);
    EXPECT_EQ(d.width, 1400);
    EXPECT_GT(d.height, 800);
    EXPECT_LT(d.height, 1200);
    EXPECT_GT(d.matching, 500);
    // No temporary files left beside it.
    for (const auto& e : fs::directory_iterator(run / "figures"))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(PlotRender, PlotFormatFollowsTheExtension) {
    make_run("r1", 0.3);
    Result r = orodem("plot r1 --out p.svg");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(slurp(work_ / "p.svg"), "<svg");
    r = orodem("plot r1 --out sub/p.pdf");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "sub" / "p.pdf").substr(0, 5), "%PDF-");
    r = orodem("plot r1 --out p.jpg");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, ".png");
    EXPECT_FALSE(fs::exists(work_ / "p.jpg"));
}

TEST_F(PlotRender, SeveralRunsGoToTheCommonParent) {
    make_run("sweep/wedge.mu_bp=0.1", 0.1);
    make_run("sweep/wedge.mu_bp=0.2", 0.2);
    const Result r = orodem("plot sweep/wedge.mu_bp=0.1 sweep/wedge.mu_bp=0.2/");
    ASSERT_EQ(r.status, 0) << r.err;
    const fs::path png = work_ / "sweep" / "plots.png";
    ASSERT_TRUE(fs::exists(png)) << r.out;
    const Png first = decode_png(png, 31, 120, 181), second = decode_png(png, 227, 26, 28);
    ASSERT_TRUE(first.ok);
    EXPECT_EQ(first.width, 1400);
    EXPECT_GT(first.matching, 100);
    EXPECT_GT(second.matching, 100);  // the second run in its own colour
}

TEST_F(PlotRender, LegendLabelsNameTheDifferingKeys) {
    using orodem::legend_labels;
    // mu_bp differs; threads differ too but do not change the physics.
    auto l = legend_labels({config_text(0.1, 1), config_text(0.2, 4)}, {"a", "b"}, {"a.toml", "b.toml"});
    ASSERT_EQ(l.size(), 2u);
    EXPECT_EQ(l[0], "wedge.mu_bp = 0.1");
    EXPECT_EQ(l[1], "wedge.mu_bp = 0.2");
    // Nothing differs (but the thread count): the directory names.
    l = legend_labels({config_text(0.3, 1), config_text(0.3, 8)}, {"a", "b"}, {"a.toml", "b.toml"});
    EXPECT_EQ(l, (std::vector<std::string>{"a", "b"}));
    // One run: its name.
    EXPECT_EQ(legend_labels({config_text(0.3)}, {"r1"}, {"r1.toml"}), std::vector<std::string>{"r1"});
    // Two keys differ, one present in one run only.
    l = legend_labels({config_text(0.1), config_text(0.2) + "[material]\nmu = 0.5\n"}, {"a", "b"}, {"a", "b"});
    EXPECT_EQ(l[0], "material.mu = (absent), wedge.mu_bp = 0.1");
    EXPECT_EQ(l[1], "material.mu = 0.5, wedge.mu_bp = 0.2");
    // Not TOML: an I/O error naming the source.
    try {
        legend_labels({config_text(0.1), "[wedge\nmu_bp = "}, {"a", "b"}, {"a/config.toml", "b/config.toml"});
        FAIL() << "no error";
    } catch (const orodem::IoError& e) {
        EXPECT_HAS(e.what(), "b/config.toml");
    }
}

TEST_F(PlotRender, SeriesReaderReadsNanAndRejectsBadRows) {
    write(work_ / "s.csv", std::string(kHeader) + "0,0,0,0.1,nan,-nan,0.5,,0,40\n1,1,0.5,0.2,10,5,0.1,20,3.5,41\n2,2");
    const orodem::Series s = orodem::read_series_csv((work_ / "s.csv").string());
    ASSERT_EQ(s.rows(), 2u);  // the unterminated last line is dropped
    ASSERT_NE(s.column("alpha_deg"), nullptr);
    EXPECT_TRUE(std::isnan((*s.column("alpha_deg"))[0]));
    EXPECT_TRUE(std::isnan((*s.column("beta_deg"))[0]));
    EXPECT_TRUE(std::isnan((*s.column("dilation_pct"))[0]));
    EXPECT_DOUBLE_EQ((*s.column("alpha_deg"))[1], 10.0);
    EXPECT_EQ(s.column("no_such"), nullptr);
    write(work_ / "bad.csv", std::string(kHeader) + "0,0,0,0.1,x,1,0.5,1,0,40\n");
    EXPECT_THROW(orodem::read_series_csv((work_ / "bad.csv").string()), orodem::IoError);
    write(work_ / "short.csv", std::string(kHeader) + "0,0,0\n");
    EXPECT_THROW(orodem::read_series_csv((work_ / "short.csv").string()), orodem::IoError);
}

TEST_F(PlotRender, RenderRedrawsTheSnapshots) {
    // Into figures/rendered/ (the run's own figures/ are left alone); the
    // hand-made snapshots have no rel_disp_abs: the per-frame scale.
    const fs::path run = make_run("r1", 0.3);
    Result r = orodem("render r1");
    ASSERT_EQ(r.status, 0) << r.err;
    const fs::path out = run / "figures" / "rendered";
    int height = 0;
    for (const char* f : {"horizons_S00.000.png", "horizons_S01.000.png", "displacement_S01.000.png"}) {
        const Png d = decode_png(out / f);
        EXPECT_TRUE(d.ok) << f;
        EXPECT_EQ(d.width, 1600) << f;
        EXPECT_GT(d.height, 100) << f;
        if (height == 0) height = d.height;
        EXPECT_EQ(d.height, height) << f;  // one frame for the run
    }
    EXPECT_FALSE(fs::exists(run / "figures" / "horizons_S00.000.png"));
    // The first snapshot has nothing to be displaced from.
    EXPECT_FALSE(fs::exists(out / "displacement_S00.000.png"));
    // --at picks the nearest snapshot; --format, --width and --dir apply.
    r = orodem("render r1 --at 0.8 --format svg --width 800");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(slurp(out / "horizons_S01.000.svg"), "<svg");
    EXPECT_HAS(slurp(out / "displacement_S01.000.svg"), "(old snapshot)</text>");
    EXPECT_FALSE(fs::exists(out / "horizons_S00.000.svg"));
    r = orodem("render r1 --at 0.1,0.2 --width 640 --dir small");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(decode_png(work_ / "small" / "horizons_S00.000.png").width, 640);
    EXPECT_EQ(orodem("render r1 --format gif").status, 2);
    EXPECT_EQ(orodem("render r1 --at one").status, 2);
    // An S beyond the run's snapshots (S = 0 and 1 here) is refused with the range, not drawn as the last one.
    r = orodem("render r1 --at 7 --dir beyond");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "--at 7: the run's outputs are at S = 0.00 to 1.00");
    EXPECT_FALSE(fs::exists(work_ / "beyond"));
    EXPECT_EQ(orodem("render r1 --at 1.1 --dir near").status, 0);  // within half a spacing of the last: the last
    // Snapshots without strain arrays (an orodem before strain maps): no
    // strain map, said; a strain figure or movie stops with one line, exit
    // 2, nothing written.
    EXPECT_FALSE(fs::exists(out / "strain_S01.000.png"));
    r = orodem("render r1 --at 1 --dir old --force");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "1 without strain arrays");
    EXPECT_FALSE(fs::exists(work_ / "old" / "strain_S01.000.png"));
    for (const char* cmd : {"render r1 --color-by strain --out s.png", "render r1 --color-by strain_total --out s.png",
                            "movie r1 --color-by strain --out s.mp4"}) {
        r = orodem(cmd);
        EXPECT_EQ(r.status, 2) << cmd;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_HAS(r.err, "snapshots/S0");
        EXPECT_HAS(r.err, "shear_strain");
    }
    EXPECT_FALSE(fs::exists(work_ / "s.png"));
    EXPECT_FALSE(fs::exists(work_ / "s.mp4"));
}

TEST_F(PlotRender, MeasureTakesTheRunsMeasuresAgainFromItsSnapshots) {
    // A real (tiny) run: `orodem measure` re-reads each snapshot and measures
    // it with y_mean taken from the S = 0 one, as the run did from its layer;
    // every measure it shares with series.csv must come out the same (the
    // positions are stored exactly). Dilation divides by S h0 instead of
    // v t, which agree to the 6 decimals of S: relative 1e-5; so does the
    // belt's decoupling point (the belt's displacement from the S of two
    // snapshots).
    write_tiny_exp1(work_);
    ASSERT_EQ(orodem("run tiny.toml --out r --threads 1").status, 0);
    const Result r = orodem("measure r");
    ASSERT_EQ(r.status, 0) << r.err;
    write(work_ / "measured.csv", r.out);
    const orodem::Series again = orodem::read_series_csv((work_ / "measured.csv").string());
    const orodem::Series series = orodem::read_series_csv((work_ / "r" / "series.csv").string());
    ASSERT_EQ(again.rows(), series.rows());
    ASSERT_EQ(again.rows(), 3u);
    for (const char* name : {"S", "H_over_h0", "alpha_deg", "beta_deg", "peak_dx_over_h0", "toe_pro_x_over_h0",
                             "toe_retro_x_over_h0", "beta_inner_deg", "beta_outer_deg", "retro_break_x_over_h0",
                             "dilation_pct", "decoupling_x_over_h0"}) {
        const auto* a = again.column(name);
        const auto* b = series.column(name);
        ASSERT_TRUE(a && b) << name;
        for (std::size_t k = 0; k < again.rows(); ++k) {
            if (std::isnan((*b)[k])) {
                EXPECT_TRUE(std::isnan((*a)[k])) << name << " row " << k;
            } else if (std::string(name) == "dilation_pct" || std::string(name) == "decoupling_x_over_h0") {
                EXPECT_NEAR((*a)[k], (*b)[k], 1e-5 * std::fabs((*b)[k])) << name << " row " << k;
            } else {
                EXPECT_EQ((*a)[k], (*b)[k]) << name << " row " << k;
            }
        }
    }
    EXPECT_GT((*again.column("H_over_h0"))[2], 0.0);
    // Not a wedge run, or not a run: one line, exit 2.
    fs::create_directories(work_ / "s");
    write(work_ / "s" / "config.toml", "[run]\nexperiment = 'settle'\n[packing]\nh0 = 6.0\n");
    write(work_ / "s" / "series.csv", "step,time,kinetic_energy\n");
    Result bad = orodem("measure s");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(count_lines(bad.err), 1) << bad.err;
    EXPECT_HAS(bad.err, "settle");
    bad = orodem("measure nope");
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(count_lines(bad.err), 1) << bad.err;
}

TEST_F(PlotRender, MissingOrBrokenRunDirectoriesExitWithOneLine) {
    for (const char* cmd : {"plot nope", "render nope", "plot nope --out x.png"}) {
        const Result r = orodem(cmd);
        EXPECT_TRUE(r.status == 2 || r.status == 4) << cmd << ": " << r.status;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_HAS(r.err, "nope");
    }
    fs::create_directories(work_ / "empty");
    Result r = orodem("plot empty");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "not a run directory");
    // A run without its series: an I/O error naming the file.
    const fs::path run = make_run("r1", 0.3);
    fs::remove(run / "series.csv");
    r = orodem("plot r1");
    EXPECT_EQ(r.status, 4);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "series.csv");
    // A snapshot gone: render names it.
    fs::remove(run / "snapshots" / "S01.000.vtu");
    r = orodem("render r1");
    EXPECT_EQ(r.status, 4);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "S01.000.vtu");
    // A settle run's series has no S: not a wedge run.
    write(run / "series.csv", "step,time,kinetic_energy\n0,0,1\n");
    r = orodem("plot r1");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "'S'");
    EXPECT_EQ(orodem("plot").status, 2);
}

TEST_F(PlotRender, PlateVelocityScriptBinsTheProsideDiscsOfASnapshot) {
    // scripts/plate-velocity on a snapshot with known velocities: h0 = 2 m,
    // v' = 0.2 m/s (config_text), bins of 1 h0 from the S point.
    const fs::path dir = work_ / "plate";
    fs::create_directories(dir / "snapshots");
    write(dir / "config.toml", config_text(0.3));
    orodem::ParticleStore p;
    auto add = [&](double x, double y, double vx) { p.v[p.add({x, y}, 0.45, 2500.0)] = {vx, 0.0}; };
    add(-0.5, 0.45, 0.1);   // bin 0, on the base: 0.5 v'
    add(-1.0, 2.0, 0.2);    // bin 0, above it: 1.0 v'
    add(-3.0, 0.46, -0.1);  // bin 1, on the base (bottom 1 cm up): -0.5 v'
    add(1.0, 0.45, 0.5);    // retroside: left out
    orodem::write_vtu((dir / "snapshots/S00.500.vtu").string(), p, std::vector<double>(p.size(), 0.0));
    std::string out;
    ASSERT_EQ(run("python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/plate-velocity") + " " +
                      quote(dir.string()) + " 0.5 1.0",
                  &out),
              0)
        << out;
    std::istringstream lines(out);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream f(line);
        std::vector<double> row;
        for (double x; f >> x;) row.push_back(x);
        if (row.size() == 4 && f.eof()) rows.push_back(row);
    }
    ASSERT_EQ(rows.size(), 2u) << out;
    EXPECT_EQ(rows[0], (std::vector<double>{-0.5, 0.75, 0.5, 2.0})) << out;
    EXPECT_EQ(rows[1], (std::vector<double>{-1.5, -0.5, -0.5, 1.0})) << out;
}

TEST_F(PlotRender, ValidateFindingsScriptMeasuresRunsAndTheSpreadOverSeeds) {
    // scripts/validate-findings on hand-made series with known answers:
    // S = 0.25 ... 6 (last third: S >= 4), H = 0.4 S^0.5 (b = 0.5 exactly),
    // alpha = 10 deg before S = 3 and c after, beta = b0 throughout.
    // The peak lies at 0.1 h0 ± swing, + at odd rows and - at even ones.
    auto make = [&](const std::string& name, double c, double b0, double wall_from, double swing = 0.0) {
        const fs::path dir = work_ / "findings" / name;
        fs::create_directories(dir);
        write(dir / "config.toml", "[wedge]\ns_max = 6.0\npro_margin = 10.0\n");
        std::ostringstream s;
        s << "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0\n";
        s << "0,0,nan,nan,nan,nan,-15.5,nan\n";  // S = 0: a roughness bump by the wall is no wedge
        for (int k = 1; k <= 24; ++k) {
            const double S = 0.25 * k;
            const double toe = S >= wall_from ? -(16.0 - S) + 0.5 : -5.0;  // trailing wall at -(16 - S) h0
            s << S << ',' << 0.4 * std::sqrt(S) << ',' << (S < 3.0 ? 10.0 : c) << ',' << b0 << ','
              << 0.1 + (k % 2 ? swing : -swing) << ",90," << toe << ",2.5\n";
        }
        write(dir / "series.csv", s.str());
        return dir.string();
    };
    const std::string a1 = make("a1", 5.0, 20.0, 99.0), a2 = make("a2", 6.0, 21.0, 5.0),
                      a3 = make("a3", 7.0, 22.0, 99.0), b1 = make("b1", 9.0, 25.0, 99.0, 1.0);
    const std::string script = "python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/validate-findings");
    std::string out;
    ASSERT_EQ(run(script + " " + quote(a1) + " " + quote(a2), &out), 0) << out;
    EXPECT_HAS(out, "| a1 | 10.0 ± 0.0 | 5.0 ± 0.0 | 20.0 ± 0.0 | 0.50; 0.50 | 0.98 | 90 | +0.10 (+0.10 … +0.10) | +2.50 | never |");
    EXPECT_HAS(out, "| a2 | 10.0 ± 0.0 | 6.0 ± 0.0 | 21.0 ± 0.0 | 0.50; 0.50 | 0.98 | 90 | +0.10 (+0.10 … +0.10) | +2.50 | 5.00 |");
    EXPECT_HAS(out, "| a1 | 1 | 0 | none |");  // a still peak never switches
    // Seeds a1-a3: stage-2 alpha 6 ± 1 deg; b1 alone borrows that sd:
    // (9 - 6) / sqrt(1/3 + 1/1) = 2.6 standard errors.
    ASSERT_EQ(run(script + " --spread A=" + quote(a1) + "," + quote(a2) + "," + quote(a3) + " B=" + quote(b1), &out), 0)
        << out;
    // b1's peak over the last third (S >= 4: rows 16-24, five at -0.9, four at
    // +1.1): mean 0.1 - 1/9 = -0.01 h0, range 2 h0.
    EXPECT_HAS(out, "| A | 3 | 10.00 ± 0.00 | 6.00 ± 1.00 | 6.00 ± 1.00 | 21.00 ± 1.00 | 0.500 ± 0.000 | 0.980 ± 0.000 | "
                    "90.0 ± 0.0 | 2.50 ± 0.00 | 0.10 ± 0.00 | 0.00 ± 0.00 |");
    EXPECT_HAS(out, "| B | 1 | 10.00 | 9.00 | 9.00 | 25.00 | 0.500 | 0.980 | 90.0 | 2.50 | -0.01 | 2.00 |");
    EXPECT_HAS(out, "alpha (S >= 3): B - A = +3.00 deg, +2.6 seed standard errors");
    // beta: (25 - 21) / sqrt(1/3 + 1/1) = 3.5 standard errors.
    EXPECT_HAS(out, "beta (last third): B - A = +4.00 deg, +3.5 seed standard errors");
    // b1's peak falls from +1.1 to -0.9 h0 (2 h0 >= 0.5) into every even row;
    // only outputs from S = 1 (row 4) count, so the fall into row 4 (from
    // S = 0.75) does not: rows 6, 8, ..., 24, ten switches.
    EXPECT_HAS(out, "| B | 1 | 10 | 1.50 (+1.10 -> -0.90); 2.00 (+1.10 -> -0.90); ");
    EXPECT_HAS(out, "; 6.00 (+1.10 -> -0.90) |");
    EXPECT_HAS(out, "| A | 3 | 0 | none |");
    EXPECT_NE(run(script + " --spread A" + " 2>&1", &out), 0);
    EXPECT_HAS(out, "LABEL=RUN_DIR");
}

TEST_F(PlotRender, ValidateFindingsScriptAveragesTheRetrosideTwoSlopes) {
    // series.csv with the two-slope columns: S = 0.25 ... 6, last third S >= 4
    // (rows 16-24). beta inner = bi, beta outer = bo + (+d at odd rows, -d at
    // even ones: five -d and four +d over the last third), break 3 h0.
    auto make = [&](const std::string& name, double bi, double bo, double d) {
        const fs::path dir = work_ / "slopes" / name;
        fs::create_directories(dir);
        write(dir / "config.toml", "[wedge]\ns_max = 6.0\npro_margin = 10.0\n");
        std::ostringstream s;
        s << "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0,"
             "beta_inner_deg,beta_outer_deg,retro_break_x_over_h0\n";
        for (int k = 1; k <= 24; ++k)
            s << 0.25 * k << ",0.5,5,10,0,90,-5,2.5," << (k < 8 ? std::string("nan") : std::to_string(bi)) << ','
              << bo + (k % 2 ? d : -d) << ",3\n";
        write(dir / "series.csv", s.str());
        return dir.string();
    };
    const std::string a1 = make("a1", 12.0, 4.0, 0.0), a2 = make("a2", 14.0, 2.0, 0.0),
                      b1 = make("b1", 7.0, 16.0, 0.9);
    const std::string script = "python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/validate-findings");
    std::string out;
    ASSERT_EQ(run(script + " " + quote(b1), &out), 0) << out;
    // b1's outer slope over the last third: 16 + (4 x 0.9 - 5 x 0.9) / 9 = 15.9.
    EXPECT_HAS(out, "| b1 | 1 | 7.00 | 15.90 | 3.00 |");
    ASSERT_EQ(run(script + " --spread A=" + quote(a1) + "," + quote(a2) + " B=" + quote(b1), &out), 0) << out;
    EXPECT_HAS(out, "| A | 2 | 13.00 ± 1.41 | 3.00 ± 1.41 | 3.00 ± 0.00 |");
    // (15.9 - 3) / sqrt(2/2 + 2/1) = 7.4 standard errors (B borrows A's sd).
    EXPECT_HAS(out, "beta outer (last third): B - A = +12.90 deg, +7.4 seed standard errors");
    // A run whose series predates the columns and has no snapshots: n/a.
    const fs::path old = work_ / "slopes" / "old";
    fs::create_directories(old);
    write(old / "config.toml", "[wedge]\ns_max = 6.0\n");
    write(old / "series.csv", "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,"
                              "toe_retro_x_over_h0\n1,0.5,5,10,0,90,-5,2.5\n2,0.6,5,10,0,90,-5,2.5\n");
    ASSERT_EQ(run(script + " " + quote(old.string()), &out), 0) << out;
    EXPECT_HAS(out, "| old | 1 | n/a | n/a | n/a |");
}

// A finished exp1 run for scripts/validate-findings (h0 = 10 m; the trailing
// wall at -(s_max + pro_margin) h0): config.toml, log.txt and a first
// snapshot whose plate window (1 h0 from the wall to 2 h0 before S) holds ten
// discs of 104 m² (one more disc sits outside it). With s_max + pro_margin =
// 16 the window is 1300 m² of layer: area fraction 0.8. The caller writes
// series.csv, starting with kFindingsSeriesHeader.
namespace {
const char* const kFindingsSeriesHeader =
    "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0,section_push\n";
void write_findings_run(const fs::path& dir, double s_max, double pro_margin) {
    fs::create_directories(dir / "snapshots");
    write(dir / "config.toml", "[wedge]\ns_max = " + std::to_string(s_max) + "\npro_margin = " + std::to_string(pro_margin) +
                                   "\n[packing]\nh0 = 10.0\n");
    write(dir / "log.txt", "finished: S = " + std::to_string(s_max) + "\n");
    orodem::ParticleStore p;
    for (int k = 0; k < 10; ++k) p.add({-140.0 + 12.0 * k, 5.0}, std::sqrt(104.0 / M_PI), 2500.0);
    p.add({0.0, 5.0}, 3.0, 2500.0);
    orodem::write_vtu((dir / "snapshots" / "S0.vtu").string(), p, {});
    orodem::write_pvd((dir / "run.pvd").string(), {{0.0, "snapshots/S0.vtu"}});
}
}  // namespace

TEST_F(PlotRender, ValidateFindingsVerdictsFollowTheirRules) {
    // A manifest of three exp1 groups (mu_bp 0.1, 0.3, 0.5), two seeds each,
    // hand-made series S = 0.25 ... 6: alpha = 5 ± 0.1 (the seeds) for S < 3
    // in every group, then a ± 0.5 with a = 2, 6, 10; beta 20 ± 0.5 in every
    // group. Per group the seed s.e. is sd/sqrt(2) = 0.5 (0.1 for stage 1).
    //
    // The plate's push ahead of the toe (section_push) over 1 <= S < 3 is
    // (a / 4) ± 0.1 rho g h0^2 (rho = 2500, g = 9.81, h0 = 10 m), so 0.5, 1.5
    // and 2.5. The first snapshot holds ten discs of area 104 m² in the
    // plate's window (x from -150 to -20 m: 1300 m² of layer, area fraction
    // eta = 0.8) and one outside it; with phi_peak = 30° (K_p = 3) the
    // passive strength is 1/2 K_p eta = 1.2 rho g h0^2.
    const fs::path root = work_ / "verdicts";
    auto make = [&](const std::string& group, int seed, double a, double s1 = 5.0) {
        const fs::path dir = root / "runs" / "mid" / group / ("seed" + std::to_string(seed));
        write_findings_run(dir, 6.0, 10.0);
        const double off = seed == 1 ? -1.0 : 1.0;
        std::ostringstream s;
        s << kFindingsSeriesHeader;
        for (int k = 1; k <= 24; ++k) {
            const double S = 0.25 * k;
            s << S << ',' << 0.4 * std::sqrt(S) << ',' << (S < 3.0 ? s1 + 0.1 * off : a + 0.5 * off) << ','
              << 20.0 + 0.5 * off << ",0,95,-5,2.5," << (a / 4.0 + 0.1 * off) * 2500.0 * 9.81 * 100.0 << "\n";
        }
        write(dir / "series.csv", s.str());
    };
    for (int seed : {1, 2}) {
        make("exp1_mubp0.1", seed, 2.0);
        make("exp1_mubp0.3", seed, 6.0);
        make("exp1_mubp0.5", seed, 10.0);
        // The same seeds on the traction base: stage-1 alpha 2, 5 and 8 ± 0.1 (not alike).
        make("exp1_mubp0.1_traction", seed, 2.0, 2.0);
        make("exp1_mubp0.3_traction", seed, 6.0, 5.0);
        make("exp1_mubp0.5_traction", seed, 10.0, 8.0);
    }
    std::string groups;
    for (const char* g : {"exp1_mubp0.1", "exp1_mubp0.3", "exp1_mubp0.5"})
        groups += std::string("[mid.\"") + g + "\"]\nconfig = \"configs/mid/exp1.toml\"\nseeds = [1, 2]\nphi_peak_deg = 30\n" +
                  "phi_cs_deg = 26\nmu_b = 0.3\n" +
                  "[mid.\"" + g + "_traction\"]\nconfig = \"configs/mid/exp1.toml\"\nseeds = [1, 2]\n";
    // The critical wedge's packings: the frontal thrust roots 3 h0 ahead of
    // the toe in the hexagonal packing (one run: no seed changes a lattice),
    // 1 ± 0.1 and 0.5 ± 0.1 h0 in the random ones (two seeds each).
    auto make_cw = [&](const std::string& group, int seed, double ahead) {
        const fs::path dir = root / "runs" / "mid" / group / ("seed" + std::to_string(seed));
        fs::create_directories(dir);
        write(dir / "config.toml", "[wedge]\ns_max = 6.0\n");
        write(dir / "log.txt", "finished: S = 6.000\n");
        std::ostringstream s;
        s << "S,H_over_h0,alpha_deg,beta_deg,peak_dx_over_h0,dilation_pct,toe_pro_x_over_h0,toe_retro_x_over_h0,"
             "front_thrust_x_over_h0\n";
        for (int k = 1; k <= 24; ++k)
            s << 0.25 * k << ",0.5,8,nan,0,95,-4,nan," << (k == 8 ? std::string("nan") : std::to_string(-4.0 - ahead))
              << "\n";
        write(dir / "series.csv", s.str());
    };
    make_cw("critical_hexagonal", 1, 3.0);
    for (int seed : {1, 2}) {
        make_cw("critical_discs", seed, seed == 1 ? 0.9 : 1.1);
        make_cw("critical_clusters", seed, seed == 1 ? 0.4 : 0.6);
    }
    groups += "[mid.critical_hexagonal]\nconfig = \"c.toml\"\nseeds = [1]\ndeterministic = true\n"
              "[mid.critical_discs]\nconfig = \"c.toml\"\nseeds = [1, 2]\n"
              "[mid.critical_clusters]\nconfig = \"c.toml\"\nseeds = [1, 2]\n";
    write(root / "m.toml", "root = \"runs\"\n" + groups);
    const std::string script = "ORODEM=/nonexistent /usr/bin/python3 " +
                               quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/validate-findings");
    std::string out;
    ASSERT_EQ(run(script + " --verdicts " + quote((root / "m.toml").string()), &out), 0) << out;
    // Stage 1: every difference 0 ± 0.14, inside ±2 deg: alike.
    EXPECT_HAS(out, "mu_bp 0.1: 5.00 ± 0.10 (2 runs); mu_bp 0.3: 5.00 ± 0.10 (2 runs); mu_bp 0.5: 5.00 ± 0.10 (2 runs) | reproduced |");
    // On the traction base 2, 5, 8 ± 0.1: differences of 3 and 6 deg, 21 and 42 se: not alike.
    EXPECT_HAS(out, "traction base (the same seeds, to S = 3) | alpha, 1 <= S < 3: mu_bp 0.1: 2.00 ± 0.10 (2 runs); "
                    "mu_bp 0.3: 5.00 ± 0.10 (2 runs); mu_bp 0.5: 8.00 ± 0.10 (2 runs) | not reproduced |");
    // Ordered: +4 deg, se sqrt(0.5² + 0.5²) = 0.707 with Welch's 2 degrees of freedom (t 4.303): the 95%
    // interval 4 ± 3.04 lies above 0 in both steps; p = 0.03; detectable (4.303 + 1.061) 0.707 = 3.79.
    EXPECT_HAS(out, "0.3 - 0.1 +4.00 [+0.96, +7.04], p = 0.03, detectable 3.79, 0.5 - 0.3 +4.00 [+0.96, +7.04], "
                    "p = 0.03, detectable 3.79 | reproduced |");
    // H = 0.4 S^0.5 exactly: b = 0.5 with no spread; D = 95%.
    EXPECT_HAS(out, "mu_bp 0.5: 0.500 ± 0.000 (2 runs) | reproduced |");
    EXPECT_HAS(out, "mu_bp 0.5: 95.0 ± 0.0 (2 runs) | reproduced |");
    // No orodem: no fault table, so the two rows of the retro thrust's root have no runs to judge.
    EXPECT_HAS(out, "h0 of it: mu_bp 0.1: no runs; mu_bp 0.3: no runs; mu_bp 0.5: no runs | no runs |");
    EXPECT_HAS(out, "h0 of the output's decoupling point: mu_bp 0.1: no runs; mu_bp 0.3: no runs; mu_bp 0.5: no "
                    "runs | no runs |");
    // Beta alike (20 ± 0.35 in each) and steeper than alpha in every group.
    EXPECT_HAS(out, "beta - alpha: 0.1 +18.00");
    // Hexagonal 3 h0 ahead (deterministic, s.e. 0): 2.0 and 2.5 h0 beyond the random packings, s.e. 0.1 with
    // one degree of freedom (t 12.71): intervals 2.0 ± 1.27 and 2.5 ± 1.27, above 0; an output with no thrust is
    // left out.
    EXPECT_HAS(out, "hexagonal 3.00 ± 0.00 (1 run); discs 1.00 ± 0.10 (2 runs); clusters 0.50 ± 0.10 (2 runs); "
                    "hexagonal - discs +2.00 [+0.73, +3.27], p = 0.032, detectable 1.41, hexagonal - clusters "
                    "+2.50 [+1.23, +3.77], p = 0.025, detectable 1.41");
    EXPECT_HAS(out, "clusters 8.00 ± 0.00 (2 runs) | reproduced |");
    // The push table: 0.50 ± 0.10 against 1.2 (ratio 0.42), 2.50 against 1.2 (2.08).
    EXPECT_HAS(out, "| exp1_mubp0.1 | 0.50 ± 0.10 (2 runs) | 0.800 | 1.20 | 0.42 |");
    // A traction group takes phi_peak from its Coulomb twin.
    EXPECT_HAS(out, "| exp1_mubp0.1_traction | 0.50 ± 0.10 (2 runs) | 0.800 | 1.20 | 0.42 |");
    EXPECT_HAS(out, "| exp1_mubp0.5 | 2.50 ± 0.10 (2 runs) | 0.800 | 1.20 | 2.08 |");
    {
        // With an orodem, --verdicts takes the snapshot columns from `orodem measure` and keeps the
        // run's own others (section_push). A stand-in measure gives alpha 7 at S = 1.5 and 2.5: each
        // run's stage-1 mean becomes (6 (5 ± 0.1) + 2 * 7) / 8 = 5.5 ± 0.075 (s.e. 0.075, printed 0.07),
        // and the push rows stay.
        // Its `taper` gives Dahlen's critical alpha 4.25 deg (compressive) and 21.5 deg
        // (extensional) for every group: the critical-taper table with the stable field
        // between them, and with --taper-plot its picture (matplotlib).
        write(root / "fake-orodem",
              "#!/bin/sh\nif [ \"$1\" = measure ]; then printf 'S,alpha_deg\\n1.5,7\\n2.5,7\\n'; exit 0; fi\n"
              "if [ \"$1\" = taper ]; then printf 'critical taper (compressive branch): alpha = 4.25 deg\\n"
              "critical taper (extensional branch): alpha = 21.5 deg\\n'; exit 0; fi\n"
              "exit 1\n");
        fs::permissions(root / "fake-orodem", fs::perms::owner_all);
        std::string again;
        const fs::path plot = root / "taper-SIZE.png";
        ASSERT_EQ(run("ORODEM=" + quote((root / "fake-orodem").string()) + " /usr/bin/python3 " +
                          quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/validate-findings") + " --verdicts " +
                          quote((root / "m.toml").string()) + " --taper-plot " + quote(plot.string()),
                      &again),
                  0)
            << again;
        EXPECT_HAS(again, "mu_bp 0.1: 5.50 ± 0.07 (2 runs); mu_bp 0.3: 5.50 ± 0.07 (2 runs)");
        EXPECT_HAS(again, "| exp1_mubp0.1 | 0.50 ± 0.10 (2 runs) | 0.800 | 1.20 | 0.42 |");
        EXPECT_HAS(again, "| exp1_mubp0.1 | 0.3 | 30 / 26 deg |");
        EXPECT_HAS(again, "| 4.25 (stable to 21.50) | 4.25 (stable to 21.50) |");
        EXPECT_HAS(again, "![measured prowedge taper against critical taper, intermediate size](" +
                              (root / "taper-mid.png").string() + ")");
        EXPECT_GT(fs::file_size(root / "taper-mid.png"), 1000u);
    }
    // One group 3 deg above the others at stage 1 (seeds 0.1 apart): outside
    // the ±2 deg of "alike" and beyond 2 s.e., so the finding is refuted. (1 deg
    // at 7 s.e. would still count as alike: sameness is judged by the margin.)
    for (int seed : {1, 2}) make("exp1_mubp0.5", seed, 10.0);
    {
        const fs::path s = root / "runs" / "mid" / "exp1_mubp0.5" / "seed1" / "series.csv";
        std::string t = slurp(s);
        for (std::size_t at = t.find(",4.9,"); at != std::string::npos; at = t.find(",4.9,", at)) t.replace(at, 5, ",7.9,");
        write(s, t);
        const fs::path s2 = root / "runs" / "mid" / "exp1_mubp0.5" / "seed2" / "series.csv";
        t = slurp(s2);
        for (std::size_t at = t.find(",5.1,"); at != std::string::npos; at = t.find(",5.1,", at)) t.replace(at, 5, ",8.1,");
        write(s2, t);
    }
    ASSERT_EQ(run(script + " --verdicts " + quote((root / "m.toml").string()), &out), 0) << out;
    EXPECT_HAS(out, "mu_bp 0.5: 8.00 ± 0.10 (2 runs) | not reproduced |");
}

TEST_F(PlotRender, ValidateFindingsArchivesRunsAsRecordsThatTheVerdictsRead) {
    // Two seeds of one exp1 group: stage-1 alpha 5 ± 0.1, the plate's push
    // 0.5 ± 0.1 rho g h0^2, a first snapshot with layer area fraction 0.8 (as
    // in the verdicts test above). A stand-in orodem measures alpha 7 at
    // S = 1.5 and 2.5 and prints a fault table with an active retro fault
    // rooted 0.1 h0 from S at S = 1 and 2 and 2 h0 from it at S = 3. `--archive`
    // writes each run's record: its series as measured (stage 1 becomes
    // 5.50 ± 0.07), its fault table and eta. With the run directories gone
    // and no orodem, `--verdicts` reads the records and gives the same numbers:
    // the push row (0.42 of the passive strength needs eta from the record)
    // and a retro fault at S in 2 of the 9 outputs from S = 1 (0.22 ± 0.00).
    const fs::path root = work_ / "archive";
    for (int seed : {1, 2}) {
        const fs::path dir = root / "runs" / "mid" / "exp1_mubp0.1" / ("seed" + std::to_string(seed));
        write_findings_run(dir, 3.0, 13.0);
        const double off = seed == 1 ? -1.0 : 1.0;
        std::ostringstream s;
        s << kFindingsSeriesHeader;
        for (int k = 1; k <= 12; ++k)
            s << 0.25 * k << ",0.4," << 5.0 + 0.1 * off << ",20,0,95,-5,2.5," << (0.5 + 0.1 * off) * 2500.0 * 9.81 * 100.0
              << "\n";
        write(dir / "series.csv", s.str());
    }
    write(root / "m.toml", "root = \"runs\"\nrecords = \"records\"\n[mid.\"exp1_mubp0.1\"]\nconfig = \"c.toml\"\n"
                           "seeds = [1, 2]\nphi_peak_deg = 30\n");
    write(root / "fake-orodem",
          "#!/bin/sh\ncase \"$1\" in\n--version) echo 9.9; exit 0;;\nmeasure) printf 'S,alpha_deg\\n1.5,7\\n2.5,7\\n'; exit 0;;\n"
          "faults) printf 'S,id,vergence,dip_deg,root_x_over_h0,tip_x_over_h0,width_over_h0,slip_over_h0,active\\n"
          "1,0,retro,30,0.1,1,0.1,0.1,1\\n2,0,retro,30,-0.1,1,0.1,0.1,1\\n3,0,retro,30,2,3,0.1,0.1,1\\n'; exit 0;;\nesac\nexit 1\n");
    fs::permissions(root / "fake-orodem", fs::perms::owner_all);
    const std::string script = "/usr/bin/python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/validate-findings");
    std::string out;
    ASSERT_EQ(run("ORODEM=" + quote((root / "fake-orodem").string()) + " " + script + " --archive " +
                      quote((root / "m.toml").string()),
                  &out),
              0)
        << out;
    const fs::path rec = root / "records" / "mid" / "exp1_mubp0.1" / "seed1";
    for (const char* f : {"series.csv", "faults.csv", "config.toml", "log.txt", "record.toml"})
        EXPECT_TRUE(fs::exists(rec / f)) << f;
    EXPECT_FALSE(fs::exists(rec / "run.pvd"));
    {
        const std::string r = slurp(rec / "record.toml");
        const std::size_t at = r.find("eta = ");
        ASSERT_NE(at, std::string::npos) << r;
        EXPECT_NEAR(std::stod(r.substr(at + 6)), 0.8, 1e-12) << r;
    }
    EXPECT_HAS(slurp(rec / "record.toml"), "orodem 9.9");
    fs::remove_all(root / "runs");
    ASSERT_EQ(run("ORODEM=/nonexistent " + script + " --verdicts " + quote((root / "m.toml").string()) + " --size mid",
                  &out),
              0)
        << out;
    EXPECT_HAS(out, "mu_bp 0.1: 5.50 ± 0.07 (2 runs)");
    EXPECT_HAS(out, "| exp1_mubp0.1 | 0.50 ± 0.10 (2 runs) | 0.800 | 1.20 | 0.42 |");
    EXPECT_HAS(out, "h0 of it: mu_bp 0.1: 0.22 ± 0.00 (2 runs)");
    // On a fresh clone (the run directories gone, the records there), `--make`
    // makes nothing again: the stand-in orodem fails any `run`, so a run started
    // would print "exit 1" and leave its directory.
    ASSERT_EQ(run("ORODEM=" + quote((root / "fake-orodem").string()) + " " + script + " --make " +
                      quote((root / "m.toml").string()) + " --size mid",
                  &out),
              0)
        << out;
    EXPECT_HAS(out, "mid/exp1_mubp0.1/seed2: archived in");
    EXPECT_EQ(out.find("exit 1"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(root / "runs" / "mid")) << out;
}

TEST_F(PlotRender, CheckTaperFitsTheSnapshotsSurfaceAndJudgesTheSeriesAlpha) {
    // One snapshot whose surface is a wedge of known tapers: one disc (R = 0.5 m)
    // per 1 m column, its top on a plate at 10 m, rising at 10 deg from x = -60 m
    // to the peak at x = 0 and falling at 20 deg to the retroside plate. Its S
    // falls short of the nominal 2 (1.999996, as the outputs of a run do), and
    // --from 2 must still take it. The fit gives 10 and 20 deg to round-off, so
    // a series alpha of 11.5 is 1.50 deg off (within 2) and 12.5 is 2.50
    // (exceeds: exit 1); beta is printed, not judged.
    const fs::path dir = work_ / "taper-run";
    fs::create_directories(dir / "snapshots");
    write(dir / "config.toml", "[packing]\nh0 = 10.0\nr_max = 0.5\n");
    orodem::ParticleStore p;
    const double ta = std::tan(10.0 * M_PI / 180.0), tb = std::tan(20.0 * M_PI / 180.0);
    for (int k = 0; k <= 160; ++k) {
        const double x = -100.0 + k;
        const double top = x < -60.0 ? 10.0 : x <= 0.0 ? 10.0 + (x + 60.0) * ta : std::max(10.0, 10.0 + 60.0 * ta - x * tb);
        p.add({x, top - 0.5}, 0.5, 2500.0);
    }
    orodem::write_vtu((dir / "snapshots" / "S02.000.vtu").string(), p, {});
    orodem::write_pvd((dir / "run.pvd").string(), {{1.999996, "snapshots/S02.000.vtu"}});
    const std::string script =
        "/usr/bin/python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/check-taper") + " " + quote(dir.string()) +
        " --from 2";
    std::string out;
    write(dir / "series.csv", "S,alpha_deg,beta_deg\n1.999996,11.5,19\n");
    ASSERT_EQ(run(script, &out), 0) << out;
    EXPECT_HAS(out, " 2.000        11.50        10.00        19.00        20.00");
    EXPECT_HAS(out, "median |alpha(series) - alpha(fit)| = 1.50 deg over 1 outputs: within the tolerance of 2 deg");
    write(dir / "series.csv", "S,alpha_deg,beta_deg\n1.999996,12.5,19\n");
    EXPECT_EQ(run(script, &out), 1) << out;
    EXPECT_HAS(out, "= 2.50 deg over 1 outputs: EXCEEDS the tolerance of 2 deg");

    // A stepped prowedge: a frontal imbricate rising at 5 deg from x = -80 m to
    // -40 m (10 to 13.50 m), one low column at -40 m (down to the plate), then
    // the main front at 15 deg to the peak at 0 (24.22 m). The toe walk on the
    // three-column mean (default) passes the low column (mean 12.4 m, above
    // the level + 1 m) and ends at the imbricate's foot; its fit takes the
    // columns between 20% and 80% of the 14.22 m relief on both steps
    // (x = -47 ... -41 and -39 ... -11), whose least-squares slope this test
    // computes. The first-dip walk ends at the low column and fits the front
    // alone: 15 deg.
    const fs::path step = work_ / "taper-step";
    fs::create_directories(step / "snapshots");
    write(step / "config.toml", "[packing]\nh0 = 10.0\nr_max = 0.5\n");
    const double t5 = std::tan(5.0 * M_PI / 180.0), t15 = std::tan(15.0 * M_PI / 180.0);
    auto top = [&](double x) {
        if (x < -80.0) return 10.0;
        if (x < -40.0) return 10.0 + (x + 80.0) * t5;
        if (x == -40.0) return 10.0;
        if (x <= 0.0) return 10.0 + 40.0 * t5 + (x + 40.0) * t15;
        return std::max(10.0, 10.0 + 40.0 * t5 + 40.0 * t15 - x * tb);
    };
    orodem::ParticleStore q;
    std::vector<double> fx, fy;
    const double relief = top(0.0) - 10.0;
    for (int k = 0; k <= 160; ++k) {
        const double x = -100.0 + k;
        q.add({x, top(x) - 0.5}, 0.5, 2500.0);
        const double r = (top(x) - 10.0) / relief;
        if (x >= -80.0 && x <= 0.0 && r >= 0.2 && r <= 0.8) fx.push_back(x), fy.push_back(top(x));
    }
    double mx = 0, my = 0;
    const double n = static_cast<double>(fx.size());
    for (std::size_t k = 0; k < fx.size(); ++k) mx += fx[k] / n, my += fy[k] / n;
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < fx.size(); ++k) sxy += (fx[k] - mx) * (fy[k] - my), sxx += (fx[k] - mx) * (fx[k] - mx);
    const double both = std::atan(sxy / sxx) * 180.0 / M_PI;
    ASSERT_EQ(fx.size(), 36u);  // 7 imbricate columns, 29 of the front
    orodem::write_vtu((step / "snapshots" / "S02.000.vtu").string(), q, {});
    orodem::write_pvd((step / "run.pvd").string(), {{2.0, "snapshots/S02.000.vtu"}});
    write(step / "series.csv", "S,alpha_deg,beta_deg\n2,15,20\n");
    const std::string check =
        "/usr/bin/python3 " + quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/check-taper") + " " + quote(step.string());
    ASSERT_EQ(run(check + " --toe first-dip", &out), 0) << out;
    EXPECT_HAS(out, " 2.000        15.00        15.00");
    EXPECT_EQ(run(check + " --tolerance 1", &out), 1) << out;  // 15 against the fit over both steps, 13.92
    EXPECT_HAS(out, fmt::format(" 2.000        15.00   {:10.2f}", both));
    EXPECT_GT(15.0 - both, 1.0);
}

/// A stand-in orodem for scripts/quasi-static-check in `root`: `check`
/// prints a config's derived values, `measure RUN` prints RUN/measured.csv.
static void write_quasi_static_orodem(const fs::path& root) {
    write(root / "fake-orodem",
          "#!/bin/sh\n"
          "if [ \"$1\" = check ]; then printf 'v = 0.05\\nsafety = 0.1\\ndt = 0.0003\\ninertial number I = "
          "0.0004\\n'; exit 0; fi\n"
          "if [ \"$1\" = measure ]; then cat \"$2/measured.csv\"; exit 0; fi\nexit 1\n");
    fs::permissions(root / "fake-orodem", fs::perms::owner_all);
}

TEST_F(PlotRender, QuasiStaticCheckPairsEachArmWithItsReferenceSeedBySeed) {
    // Arms v and v-nosleep (the sleeping zones off), measured by a stand-in
    // orodem: alpha of v is 5, 7, 9 for seeds 1-3 and 20 for a seed 4 that the
    // other arm lacks, of v-nosleep 6, 7.5, 10. Unpaired: 7.83 ± 1.17 against
    // 10.25 ± 3.35 (sd 6.70 / 2), a difference of -2.42 with s.e.
    // hypot(1.167, 3.351) = 3.55, and "no" for the missing seed. Paired over
    // the common seeds 1-3: differences 1, 0.5, 1, mean 0.83, sd 0.289, s.e.
    // 0.17: the shift, with its sign, at 5 s.e. Beta and H are equal: 0 ± 0.
    const fs::path root = work_ / "qsc";
    fs::create_directories(root);
    write_quasi_static_orodem(root);
    auto make = [&](const std::string& arm, int seed, double alpha) {
        const fs::path dir = root / "out" / arm / ("seed" + std::to_string(seed));
        fs::create_directories(dir);
        write(dir / "log.txt", "finished: S = 3.000\n");
        write(dir / "series.csv", "S,trailing_wall_push\n3,1e6\n");
        std::ostringstream m;
        m << "S,alpha_deg,beta_deg,H_over_h0\n0.5,30,30,0.2\n1," << alpha << ",8,0.7\n3," << alpha << ",8,0.7\n";
        write(dir / "measured.csv", m.str());
    };
    make("v", 1, 5.0);
    make("v", 2, 7.0);
    make("v", 3, 9.0);
    make("v", 4, 20.0);
    make("v-nosleep", 1, 6.0);
    make("v-nosleep", 2, 7.5);
    make("v-nosleep", 3, 10.0);
    std::string out;
    ASSERT_EQ(run("ORODEM=" + quote((root / "fake-orodem").string()) + " /usr/bin/python3 " +
                      quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/quasi-static-check") + " --config c.toml" +
                      " --out " + quote((root / "out").string()) + " --arms v,v-nosleep --seeds 1,2,3,4 --from 1" +
                      " --report-only",
                  &out),
              0)
        << out;
    EXPECT_HAS(out, "| v-nosleep | 0.05 | 0.0003 | 0.0004 | 3 | 7.83 ± 1.17 (Δ -2.42, s.e. 3.55) |");
    EXPECT_HAS(out, "paired difference v-nosleep - v (seeds 1,2,3): alpha +0.83 ± 0.17 deg, beta +0.00 ± 0.00 deg, "
                    "H/h0 +0.000 ± 0.000");

    // The equivalence rule (--margins 2,2,0.1). v-nosleep: alpha |Δ| 2.42
    // with 2 s.e. 7.10 is neither within the margin nor beyond it
    // (undecided, and no seed count settles a |Δ| above the margin); beta
    // and H are equal with no spread (accepted). A 2v arm at alpha 30, 30.5,
    // 31 (sd 0.5) lies 20.25 from v, 13.5 beyond 2 s.e. = 2 hypot(0.289,
    // 3.351) = 6.73: refuted. The one-s.e. rule says "no" for both.
    make("2v", 1, 30.0);
    make("2v", 2, 30.5);
    make("2v", 3, 31.0);
    const std::string base = "ORODEM=" + quote((root / "fake-orodem").string()) + " /usr/bin/python3 " +
                             quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/quasi-static-check") +
                             " --config c.toml --out " + quote((root / "out").string()) +
                             " --arms v,2v,v-nosleep --seeds 1,2,3,4 --from 1 --report-only";
    ASSERT_EQ(run(base + " --margins 2,2,0.1", &out), 0) << out;
    EXPECT_HAS(out, "equivalence v-nosleep - v: undecided: alpha undecided (|Δ| 2.42, 2 s.e. 7.10, margin 2 deg; "
                    "seeds per arm to settle: none), beta accepted (|Δ| 0.00, 2 s.e. 0.00, margin 2 deg; seeds per "
                    "arm to settle: 2), H/h0 accepted (|Δ| 0.000, 2 s.e. 0.000, margin 0.1; seeds per arm to settle: 2)");
    EXPECT_HAS(out, "equivalence 2v - v: refuted: alpha refuted (|Δ| 20.25, 2 s.e. 6.73, margin 2 deg;");
    // Paired over seeds 1-3: v-nosleep - v differs by 1, 0.5, 1 (mean 0.83,
    // s.e. 0.17): 0.83 + 0.33 <= 2, accepted; 4 sd² / (2 - 0.83)² = 0.24 -> 2
    // seeds. 2v - v: 25, 23.5, 22 (s.e. 0.87), 23.5 - 1.73 > 2: refuted.
    EXPECT_HAS(out, "paired equivalence v-nosleep - v (seeds 1,2,3): accepted: alpha accepted (Δ 0.83, 2 s.e. 0.33, "
                    "margin 2 deg; seeds to settle: 2), beta accepted (Δ 0.00, 2 s.e. 0.00, margin 2 deg;");
    EXPECT_HAS(out, "paired equivalence 2v - v (seeds 1,2,3): refuted: alpha refuted (Δ 23.50, 2 s.e. 1.73, margin 2 "
                    "deg; seeds to settle: none)");
    // With a margin beyond the difference: the seeds that would settle it.
    // 2v against v with margin 25: pooled sd sqrt((0.25 + 44.92) / 2) =
    // 4.752 (v's four seeds: sd 6.70), 8 sd² / (25 - 20.25)² = 8.0 -> 9.
    ASSERT_EQ(run(base + " --margins 25,2,0.1", &out), 0) << out;
    EXPECT_HAS(out, "alpha undecided (|Δ| 20.25, 2 s.e. 6.73, margin 25 deg; seeds per arm to settle: 9)");
    // Student's t for few pairs (--quantile t): three pairs, 2 degrees of
    // freedom, t = 4.303. 2v - v with margin 27: 23.5 + 2 x 0.866 = 25.23
    // accepts with 2, 23.5 + 4.303 x 0.866 = 27.23 does not (and 23.5 -
    // 3.73 is inside 27: undecided); the pairs to settle at sd 1.5 and room
    // 3.5: 2 pairs 12.706 x 1.5 / sqrt(2) = 13.5, 3 pairs 3.73, 4 pairs
    // 3.182 x 1.5 / 2 = 2.39 <= 3.5: 4 (with 2: 4 x 2.25 / 12.25 -> 2).
    ASSERT_EQ(run(base + " --margins 27,2,0.1", &out), 0) << out;
    EXPECT_HAS(out, "paired equivalence 2v - v (seeds 1,2,3): accepted: alpha accepted (Δ 23.50, 2 s.e. 1.73, margin "
                    "27 deg; seeds to settle: 2)");
    ASSERT_EQ(run(base + " --margins 27,2,0.1 --quantile t", &out), 0) << out;
    EXPECT_HAS(out, "paired equivalence 2v - v (seeds 1,2,3, t quantile): undecided: alpha undecided (Δ 23.50, 4.303 "
                    "s.e. 3.73, margin 27 deg; seeds to settle: 4)");
    EXPECT_NE(run(base + " --margins 2,0,0.1", &out), 0);
    EXPECT_HAS(out, "--margins: '2,0,0.1' is not three positive numbers");
}

TEST_F(PlotRender, QuasiStaticCheckTakesAFindingsRecordFromItsSeries) {
    // A findings record (record.toml, series.csv, no snapshots) stands in
    // for a run of the v arm: its measures come from its own series.csv
    // (alpha over S >= 1: mean of 4 and 6), not from orodem measure, which
    // the stand-in orodem fails; a run with snapshots is still measured.
    const fs::path root = work_ / "qsc-record";
    fs::create_directories(root);
    write_quasi_static_orodem(root);
    const fs::path rec = root / "out" / "v" / "seed1";
    fs::create_directories(rec);
    write(rec / "log.txt", "finished: S = 3.000\n");
    write(rec / "record.toml", "# archived\n");
    write(rec / "series.csv", "S,alpha_deg,beta_deg,H_over_h0,trailing_wall_push\n0.5,30,30,0.2,1\n1,4,8,0.7,1\n"
                              "3,6,10,0.9,2e6\n");
    const fs::path run2 = root / "out" / "v" / "seed2";
    fs::create_directories(run2 / "snapshots");
    write(run2 / "log.txt", "finished: S = 3.000\n");
    write(run2 / "series.csv", "S,trailing_wall_push\n3,1e6\n");
    write(run2 / "measured.csv", "S,alpha_deg,beta_deg,H_over_h0\n1,7,8,0.7\n3,9,8,0.8\n");
    std::string out;
    ASSERT_EQ(run("ORODEM=" + quote((root / "fake-orodem").string()) + " /usr/bin/python3 " +
                      quote(std::string(ORODEM_SOURCE_DIR) + "/scripts/quasi-static-check") + " --config c.toml" +
                      " --out " + quote((root / "out").string()) + " --arms v --seeds 1,2 --from 1 --report-only",
                  &out),
              0)
        << out;
    EXPECT_HAS(out, "v/seed1: alpha 5.00 deg, beta 9.00 deg (1 <= S <= 3), H/h0 0.900, trailing-wall push 2e+06 N");
    EXPECT_HAS(out, "v/seed2: alpha 8.00 deg, beta 8.00 deg (1 <= S <= 3), H/h0 0.800");
}

TEST_F(PlotRender, SeedGroupsJoinTheRunsThatDifferOnlyInTheirSeeds) {
    const std::string a = config_text(0.3), b = config_text(0.5);
    auto seeded = [](std::string t, int seed) {
        return t.replace(t.find("kind = 'clusters'\n"), 18, "kind = 'clusters'\nseed = " + std::to_string(seed) + "\n");
    };
    // Seeds, and the thread count (not physics), do not split a group; mu_bp does.
    const std::vector<std::string> texts = {seeded(a, 1), seeded(b, 1), seeded(a, 2), config_text(0.3, 8),
                                            seeded(b, 7) + "[numerics]\ndt = 1e-4\n"};
    EXPECT_EQ(orodem::seed_groups(texts, {"a", "b", "c", "d", "e"}, {}), (std::vector<std::size_t>{0, 1, 0, 0, 2}));
    EXPECT_THROW(orodem::seed_groups({a, "[run\n"}, {"a", "b"}, {}), orodem::IoError);
}

TEST_F(PlotRender, SeedEnsembleIsTheMeanAndRangeOfTheRunsAtEachS) {
    // Three runs: the third one row shorter, the second with a NaN; rows
    // matched by S (the first run's S carries round-off below 1e-6).
    auto series = [](std::vector<double> S, std::vector<double> a) {
        orodem::Series s;
        s.path = "x";
        s.names = {"S", "alpha_deg"};
        s.values = {std::move(S), std::move(a)};
        return s;
    };
    const double nan = std::nan("");
    const orodem::Series r1 = series({0.25 + 1e-9, 0.5, 0.75}, {1.0, 2.0, 3.0});
    const orodem::Series r2 = series({0.25, 0.5, 0.75}, {4.0, nan, 6.0});
    const orodem::Series r3 = series({0.25, 0.5}, {7.0, 11.0});
    const orodem::SeriesEnsemble e = orodem::seed_ensemble({&r1, &r2, &r3});
    ASSERT_EQ(e.mean.rows(), 3u);
    EXPECT_EQ(e.mean.values[0], (std::vector<double>{0.25 + 1e-9, 0.5, 0.75}));
    EXPECT_EQ(e.mean.values[1], (std::vector<double>{4.0, 6.5, 4.5}));
    EXPECT_EQ(e.lo.values[1], (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_EQ(e.hi.values[1], (std::vector<double>{7.0, 11.0, 6.0}));
    EXPECT_EQ(e.count[1], (std::vector<int>{3, 2, 2}));
    EXPECT_EQ(e.count[0], (std::vector<int>{3, 3, 2}));
    const orodem::Series no_alpha = series({0.25}, {1.0});
    orodem::Series renamed = no_alpha;
    renamed.names[1] = "beta_deg";
    EXPECT_THROW(orodem::seed_ensemble({&r1, &renamed}), orodem::ConfigError);
}

TEST_F(PlotRender, PlotSeedsDrawsOneMeanCurveOverAShadedBand) {
    // Three runs of one config with different packing seeds and their own
    // alpha: with --seeds one curve in the first colour over a band of that
    // colour at 20% on white (210, 228, 240); without it, three colours and
    // no band.
    for (int k = 1; k <= 3; ++k) {
        const fs::path dir = make_run("seeds/s" + std::to_string(k), 0.3);
        std::string t = config_text(0.3);
        write(dir / "config.toml",
              t.replace(t.find("kind = 'clusters'\n"), 18, "kind = 'clusters'\nseed = " + std::to_string(k) + "\n"));
        // H/h0 0.6 and 0.8: α and β drawn (masked below 0.5, render/plots.hpp kTaperMinHeight).
        write(dir / "series.csv", std::string(kHeader) + "0,0,0.25,0.6," + std::to_string(4 * k) +
                                      ",20,0.1,50,1,40\n10,1,1.0,0.8," + std::to_string(6 * k) + ",22,0.2,60,1,41\n");
    }
    Result r = orodem("plot seeds/s1 seeds/s2 seeds/s3 --out band.png --seeds");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "plot: mean of 3 seeds, band: lowest to highest: s1, s2, s3");
    const Png band = decode_png(work_ / "band.png", 210, 228, 240), second = decode_png(work_ / "band.png", 227, 26, 28);
    ASSERT_TRUE(band.ok);
    EXPECT_GT(band.matching, 5000) << band.matching;
    EXPECT_EQ(second.matching, 0);
    r = orodem("plot seeds/s1 seeds/s2 seeds/s3 --out lines.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_LT(decode_png(work_ / "lines.png", 210, 228, 240).matching, band.matching / 20);  // only antialiased line edges
    EXPECT_GT(decode_png(work_ / "lines.png", 227, 26, 28).matching, 100);
    // Two configs: one curve and band each, labelled by what differs.
    const fs::path other = make_run("seeds/m5", 0.5);
    r = orodem("plot seeds/s1 seeds/m5 seeds/s2 --out two.png --seeds");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "plot: wedge.mu_bp = 0.3 (2 seeds): s1, s2");
    EXPECT_HAS(r.out, "plot: wedge.mu_bp = 0.5 (1 seed): m5");
}
