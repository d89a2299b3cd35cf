// Figures and movies of a run (render/particle_view, render/run_figures;
// `orodem render`, `orodem movie`) on a real tiny exp1 (three snapshots):
// every picture of the run has one size and one legend (the numbers of its
// colour bar compared, not pixels), render draws the run's frames at the
// run's size, stacks snapshots into one PNG, SVG (text as <text>) or PDF,
// never replaces a file without --force, and the movie is made by ffmpeg
// (skipped with a message where ffmpeg is not installed) or refused with
// exit status 6 when ffmpeg is missing. Strain maps: a third picture per
// output with the run's active faults (the lines drawn are those of its
// fault table), one fixed log scale, stacked by render, animated by movie.
#include <gtest/gtest.h>

#include "cli/cli_util.hpp"

#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "orodem/render/particle_view.hpp"
#include "orodem/io/process.hpp"
#include "orodem/render/run_figures.hpp"
#include "orodem/io/fault_table.hpp"
#include "orodem/run/run_faults.hpp"

namespace fs = std::filesystem;
using namespace cli;

namespace {

struct PngSize {
    int width = 0, height = 0;
};
PngSize png_size(const fs::path& p) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(p.c_str());
    PngSize out;
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS)
        out = {cairo_image_surface_get_width(s), cairo_image_surface_get_height(s)};
    cairo_surface_destroy(s);
    return out;
}

class Figures : public OrodemTest {
protected:
    /// The tiny exp1 in work_/r: snapshots at S = 0, 0.25, 0.5.
    fs::path make_run() {
        write_tiny_exp1(work_);
        const Result r = orodem("run tiny.toml --out r --threads 1");
        EXPECT_EQ(r.status, 0) << r.err;
        return work_ / "r";
    }
};

}  // namespace

TEST_F(Figures, FramesOfARunShareSizeAndColourScale) {
    const fs::path run = make_run();
    // The run's own pictures: one size for all.
    const PngSize first = png_size(run / "figures" / "horizons_S00.000.png");
    ASSERT_GT(first.width, 0);
    for (const char* f : {"horizons_S00.250.png", "horizons_S00.500.png", "displacement_S00.250.png",
                          "displacement_S00.500.png"}) {
        const PngSize s = png_size(run / "figures" / f);
        EXPECT_EQ(s.width, first.width) << f;
        EXPECT_EQ(s.height, first.height) << f;
    }
    // Two frames drawn again from the snapshots: the run's size, and the same
    // colour bar (values, ticks, title) in both.
    const orodem::SavedRun saved = orodem::open_saved_run(run.string());
    ASSERT_EQ(saved.snaps.size(), 3u);
    std::vector<std::vector<orodem::PictureInfo>> infos;
    for (std::size_t k : {1u, 2u}) {
        const orodem::Frame f = orodem::read_frame(saved, k);
        EXPECT_FALSE(f.per_frame_scale);  // the snapshot has rel_disp_abs
        ASSERT_EQ(f.displacement.size(), f.p.size());
        for (double v : f.displacement) EXPECT_TRUE(std::isfinite(v) && v >= 0.0);
        const fs::path dir = work_ / ("again" + std::to_string(k));
        fs::create_directories(dir);
        infos.push_back(orodem::render_output_pictures({&f.p, &f.displacement, f.S}, orodem::run_view(saved.config),
                                                       dir.string(), "x"));
        ASSERT_EQ(infos.back().size(), 2u);
        EXPECT_EQ(png_size(dir / "displacement_x.png").width, first.width);
        EXPECT_EQ(png_size(dir / "displacement_x.png").height, first.height);
    }
    const orodem::PictureInfo &a = infos[0][1], &b = infos[1][1];
    EXPECT_EQ(a.width_px, b.width_px);
    EXPECT_EQ(a.height_px, b.height_px);
    EXPECT_EQ(a.width_px, first.width);
    EXPECT_EQ(a.height_px, first.height);
    EXPECT_EQ(a.legend.lo, 0.0);
    EXPECT_EQ(a.legend.hi, orodem::kDisplacementFull);
    EXPECT_EQ(a.legend.lo, b.legend.lo);
    EXPECT_EQ(a.legend.hi, b.legend.hi);
    EXPECT_EQ(a.legend.ticks, b.legend.ticks);
    EXPECT_EQ(a.legend.title, b.legend.title);
    EXPECT_HAS(a.legend.title, "ΔS h0");
    // The horizon pictures: one legend too.
    EXPECT_EQ(infos[0][0].legend.title, infos[1][0].legend.title);
    EXPECT_EQ(infos[0][0].legend.swatches.size(), 4u);
}

TEST_F(Figures, RenderStacksSnapshotsIntoOneFigure) {
    const fs::path run = make_run();
    const orodem::ViewOptions view = orodem::run_view(orodem::open_saved_run(run.string()).config);
    Result r = orodem("render r --at 0.25,0.5 --out fig.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "2 panels (S = 0.25, 0.50)");
    const PngSize png = png_size(work_ / "fig.png");
    EXPECT_EQ(png.width, 1600);
    EXPECT_EQ(png.height, orodem::picture_size(view, 2).height_px);
    // SVG: the labels are editable text.
    r = orodem("render r --at 0,0.25,0.5 --out out/fig.svg --color-by displacement");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string svg = slurp(work_ / "out" / "fig.svg");
    for (const char* s : {"<svg", ">S = 0.00</text>", ">S = 0.25</text>", ">S = 0.50</text>",
                          ">x / h0 (S point at 0)</text>", ">exp1</text>", "h0)</text>"})
        EXPECT_HAS(svg, s);
    // PDF.
    r = orodem("render r --at 0.5,0.6 --out fig.pdf");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "fig.pdf").substr(0, 5), "%PDF-");
    EXPECT_HAS(r.out, "1 panels (S = 0.50)");  // both nearest the last snapshot
    // Beyond the run (its last output S = 0.5): refused with the range, nothing written.
    r = orodem("render r --at 1,2,3 --out beyond.pdf");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "outputs are at S = 0.00 to 0.50");
    EXPECT_FALSE(fs::exists(work_ / "beyond.pdf"));
    // No --at: four evenly spread up to the last (here the nearest of 0.125,
    // 0.25, 0.375, 0.5: three distinct snapshots).
    r = orodem("render r --out four.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(work_ / "four.png").height, orodem::picture_size(view, 3).height_px);
}

TEST_F(Figures, RenderNeverReplacesFilesUnlessForced) {
    const fs::path run = make_run();
    const std::string own = slurp(run / "figures" / "horizons_S00.500.png");
    ASSERT_EQ(orodem("render r --at 0.5 --out fig.png").status, 0);
    write(work_ / "fig.png", "mine");
    Result r = orodem("render r --at 0.5 --out fig.png");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "fig.png");
    EXPECT_HAS(r.err, "--force");
    EXPECT_EQ(slurp(work_ / "fig.png"), "mine");
    r = orodem("render r --at 0.5 --out fig.png --force");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(slurp(work_ / "fig.png"), "mine");
    // Per-snapshot pictures go to figures/rendered/, not over the run's own.
    r = orodem("render r");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "7 pictures of 3 snapshots");  // horizons 3, displacement and strain 2 each
    EXPECT_TRUE(fs::exists(run / "figures" / "rendered" / "displacement_S00.500.png"));
    EXPECT_EQ(png_size(run / "figures" / "rendered" / "horizons_S00.500.png").height,
              png_size(run / "figures" / "horizons_S00.500.png").height);
    EXPECT_EQ(slurp(run / "figures" / "horizons_S00.500.png"), own);
    // Again: they exist now.
    r = orodem("render r --at 0.25");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "horizons_S00.250.png");
    EXPECT_HAS(r.err, "2 more");  // its displacement and strain maps
    EXPECT_EQ(orodem("render r --at 0.25 --force").status, 0);
    // Bad requests: exit 2, one line, nothing written.
    r = orodem("render r --out fig.jpg");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, ".svg");
    EXPECT_FALSE(fs::exists(work_ / "fig.jpg"));
    EXPECT_EQ(orodem("render r --color-by displacement").status, 2);  // only with --out
    EXPECT_EQ(orodem("render r --out a.png --format svg").status, 2);
    EXPECT_EQ(orodem("render r --out a.png --color-by strains").status, 2);
    EXPECT_EQ(orodem("render r --color-by strain").status, 2);  // only with --out
    // --xlim crops the frame to x from A to B h0 from the S point, --title replaces the experiment's name.
    r = orodem("render r --at 0.5 --out crop.svg --xlim -3,2 --title 'mu_bp = 0.3, seed 1'");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string crop = slurp(work_ / "crop.svg");
    EXPECT_HAS(crop, ">mu_bp = 0.3, seed 1</text>");
    EXPECT_HAS(crop, ">-3</text>");
    EXPECT_HAS(crop, ">2</text>");
    EXPECT_EQ(crop.find(">-4</text>"), std::string::npos);
    EXPECT_EQ(crop.find(">exp1</text>"), std::string::npos);
    r = orodem("render r --at 0.5 --dir cropped --xlim -3,2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(work_ / "cropped" / "horizons_S00.500.png").width, 1600);  // a narrower x range, drawn larger
    EXPECT_GT(png_size(work_ / "cropped" / "horizons_S00.500.png").height,
              png_size(run / "figures" / "horizons_S00.500.png").height);
    for (const char* bad : {"--xlim 2,-3", "--xlim 1", "--xlim 1,2,3"}) {
        r = orodem(std::string("render r --out bad.png ") + bad);
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_FALSE(fs::exists(work_ / "bad.png")) << bad;
    }
}

TEST_F(Figures, MovieNeedsFfmpegAndMakesTheAnimation) {
    make_run();
    // Without ffmpeg on PATH: one line naming it, exit 6, nothing written.
    Result r = [&] {
        const std::string cmd = "cd " + quote(work_.string()) + " && PATH=/nonexistent " + quote(ORODEM_EXE) +
                                " movie r --out none.mp4 2>" + quote((capture_ / "e").string());
        const int raw = std::system(cmd.c_str());
        Result x;
        x.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
        x.err = slurp(capture_ / "e");
        return x;
    }();
    EXPECT_EQ(r.status, 6);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_HAS(r.err, "ffmpeg");
    EXPECT_FALSE(fs::exists(work_ / "none.mp4"));
    // Bad extension: exit 2.
    r = orodem("movie r --out run.avi");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, ".mp4");
    if (orodem::find_on_path("ffmpeg").empty())
        GTEST_SKIP() << "ffmpeg is not installed here (scripts/install-deps installs it): the movie itself is not tested";
    r = orodem("movie r --out run.mp4");
    ASSERT_EQ(r.status, 0) << r.err;
    // The defaults: 10 s at 25 frames per second, each of the 3 snapshots held for a third of it.
    EXPECT_HAS(r.out, "movie: 3 snapshots, each shown 3.33 s (repeated frames), 10 s at 25 frames per second (250 "
                      "frames) in run.mp4");
    const std::string mp4 = slurp(work_ / "run.mp4");
    ASSERT_GT(mp4.size(), 100u);
    EXPECT_EQ(mp4.substr(4, 4), "ftyp");
    r = orodem("movie r --out strain.mp4 --color-by strain");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "strain.mp4").substr(4, 4), "ftyp");
    r = orodem("movie r --out sub/run.gif --color-by displacement --fps 2 --width 640");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "sub" / "run.gif").substr(0, 4), "GIF8");
    // A '%' in the folder's name is not an ffmpeg pattern.
    r = orodem("movie r --out '100%d_s/run.mp4' --seconds 1 --fps 3");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "100%d_s" / "run.mp4").substr(4, 4), "ftyp");
    // A fixed rate and length whatever the number of snapshots; cross-faded with --blend.
    r = orodem("movie r --out blend.mp4 --blend --seconds 3 --fps 10 --xlim -4,2 --title 'exp1, mu_bp = 0.3'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "each shown 1 s (cross-faded into the next), 3 s at 10 frames per second (30 frames)");
    if (!orodem::find_on_path("ffprobe").empty()) {
        std::string probe;
        ASSERT_EQ(run("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                      "stream=nb_read_frames,r_frame_rate,duration -of csv=p=0 " +
                          quote((work_ / "blend.mp4").string()),
                      &probe),
                  0);
        EXPECT_EQ(probe, "10/1,3.000000,30\n");
        ASSERT_EQ(run("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of "
                      "csv=p=0 " + quote((work_ / "run.mp4").string()),
                      &probe),
                  0);
        EXPECT_EQ(probe, "250\n");
    }
    // Fewer frames than snapshots: refused, nothing written.
    r = orodem("movie r --out short.mp4 --seconds 1 --fps 2");
    EXPECT_EQ(r.status, 2);
    EXPECT_HAS(r.err, "--seconds 1 at --fps 2 is 2 frames for 3 snapshots");
    EXPECT_FALSE(fs::exists(work_ / "short.mp4"));
    // No temporary folder left beside them.
    for (const auto& e : fs::directory_iterator(work_))
        EXPECT_EQ(e.path().filename().string().find(".orodem-movie"), std::string::npos) << e.path();
    // An existing movie is kept unless --force.
    r = orodem("movie r --out run.mp4");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(slurp(work_ / "run.mp4"), mp4);
    EXPECT_EQ(orodem("movie r --out run.mp4 --force").status, 0);
}

TEST_F(Figures, StrainMapsCarryTheFaultsOfTheTableOnOneScale) {
    const fs::path run = make_run();
    // The run's own strain maps: every output but the first, the run's size.
    const PngSize h = png_size(run / "figures" / "horizons_S00.250.png");
    EXPECT_FALSE(fs::exists(run / "figures" / "strain_S00.000.png"));
    for (const char* f : {"strain_S00.250.png", "strain_S00.500.png"}) {
        const PngSize s = png_size(run / "figures" / f);
        EXPECT_EQ(s.width, h.width) << f;
        EXPECT_EQ(s.height, h.height) << f;
    }
    // The tiny run finds no fault: a table planted in its place with two
    // active faults at its last output (S = 0.5) (one pro-, one retro-vergent), an inactive
    // one and an active one dipping 3° (outside the detector's stated range,
    // kFaultDipMinDeg: in the table, not drawn). Drawn again from the snapshots with the table's lines:
    // the lines drawn are the table's active faults at that S within the range, in metres, with their ids; one legend.
    const orodem::SavedRun saved = orodem::open_saved_run(run.string());
    const double h0 = saved.config.h0;
    std::vector<orodem::Fault> planted(4);
    planted[0].id = 1, planted[0].vergence = 1, planted[0].root = {-1.0 * h0, 0.0}, planted[0].tip = {-1.5 * h0, 0.8 * h0};
    planted[0].dip_deg = 58.0;
    planted[1].id = 2, planted[1].vergence = -1, planted[1].root = {0.2 * h0, 0.0}, planted[1].tip = {0.9 * h0, 0.7 * h0};
    planted[1].dip_deg = 45.0;
    planted[2] = planted[0];
    planted[2].id = 3, planted[2].active = false;
    planted[3] = planted[0];
    planted[3].id = 4, planted[3].dip_deg = 3.0, planted[3].tip = {-3.0 * h0, 0.1 * h0};
    std::string csv = orodem::faults_header() + "\n";
    for (const auto& f : planted) csv += orodem::faults_line(saved.snaps[2].S, f, h0) + "\n";
    write(run / "faults.csv", csv);
    const orodem::RunFaults table = orodem::run_faults(run.string());
    ASSERT_EQ(table.rows.size(), 4u);
    const orodem::RunFaultLines lines = orodem::run_fault_lines(table, saved.snaps, saved.config.h0);
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_TRUE(lines[0].empty());  // S = 0: no interval, no fault
    std::vector<orodem::PictureInfo> maps;
    for (std::size_t k : {1u, 2u}) {
        std::size_t active = 0;
        for (const orodem::FaultRow& row : table.rows) {
            if (std::fabs(row.S - saved.snaps[k].S) > 1e-6 || !row.fault.active || row.fault.dip_deg < 10.0) continue;
            ASSERT_LT(active, lines[k].size());
            EXPECT_NEAR(lines[k][active].root.x, row.fault.root.x * saved.config.h0, 1e-9);
            EXPECT_NEAR(lines[k][active].tip.y, row.fault.tip.y * saved.config.h0, 1e-9);
            EXPECT_EQ(lines[k][active].vergence, row.fault.vergence);
            EXPECT_EQ(lines[k][active].id, row.fault.id);
            ++active;
        }
        EXPECT_EQ(active, lines[k].size());
        EXPECT_EQ(lines[k].size(), k == 2 ? 2u : 0u);
        const orodem::Frame f = orodem::read_frame(saved, k);
        ASSERT_EQ(f.strain.size(), f.p.size());
        ASSERT_EQ(f.strain_total.size(), f.p.size());
        const fs::path dir = work_ / ("strain" + std::to_string(k));
        fs::create_directories(dir);
        const auto infos = orodem::render_output_pictures(orodem::frame_panel(f, orodem::ColorBy::strain, &lines[k]),
                                                          orodem::run_view(saved.config), dir.string(), "x");
        ASSERT_EQ(infos.size(), 3u);
        EXPECT_EQ(infos[2].faults_drawn, lines[k]);
        EXPECT_EQ(png_size(dir / "strain_x.png").height, h.height);
        maps.push_back(infos[2]);
        std::printf("    S = %.2f: %zu active faults drawn\n", f.S, lines[k].size());
    }
    EXPECT_EQ(maps[0].width_px, maps[1].width_px);
    EXPECT_EQ(maps[0].height_px, maps[1].height_px);
    EXPECT_EQ(maps[0].legend.lo, orodem::kStrainLo);
    EXPECT_EQ(maps[0].legend.hi, orodem::kStrainHi);
    EXPECT_EQ(maps[0].legend.lo, maps[1].legend.lo);
    EXPECT_EQ(maps[0].legend.hi, maps[1].legend.hi);
    EXPECT_EQ(maps[0].legend.ticks, maps[1].legend.ticks);
    EXPECT_EQ(maps[0].legend.title, maps[1].legend.title);
    EXPECT_EQ(maps[0].legend.line_keys, maps[1].legend.line_keys);
    // Stacked by render, incremental and finite, in PDF and PNG.
    Result r = orodem("render r --color-by strain --at 0.25,0.5 --out fig.pdf");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(slurp(work_ / "fig.pdf").substr(0, 5), "%PDF-");
    r = orodem("render r --color-by strain_total --at 0,0.25,0.5 --out total.png");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_size(work_ / "total.png").height,
              orodem::picture_size(orodem::run_view(saved.config), 3).height_px);
    r = orodem("render r --color-by strain --at 0.5 --out fig.svg");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_HAS(r.out, "2 active faults drawn");
    const std::string svg = slurp(work_ / "fig.svg");
    EXPECT_HAS(svg, ">retro-vergent fault</text>");
    EXPECT_HAS(svg, ">active faults dipping 10-75°, numbered by their id:</text>");
    // The ids at the tips, bold in the fault's colour: 1 and 2; not 4 (3°) nor 3 (inactive).
    std::vector<std::string> ids;
    const std::regex id_text("font-weight=\"bold\" text-anchor=\"middle\" fill=\"#[0-9a-f]+\">([0-9]+)</text>");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), id_text); it != std::sregex_iterator(); ++it)
        ids.push_back((*it)[1]);
    EXPECT_EQ(ids, (std::vector<std::string>{"1", "2"}));
}

