// Pictures of the particle state (SPEC §3 "Pictures"; render/particle_view):
// the PNG decodes with the requested width and the height that the view's
// aspect ratio implies; disc centres carry their horizon colour (proside band
// A, band B, retroside a darker shade of A); the background is white; SVG
// (with <text>) and PDF are written too; the displacement colours follow the
// fixed scale (or the per-frame quantile for old snapshots); the legend is
// the same whatever the data; a stack of panels shares one width; and
// 30,000 discs render quickly (time printed only). Strain maps: each disc's
// pixel is the log bar's colour of its γ, and the active faults are drawn
// (and returned) as lines, pro-vergent solid blue, retro-vergent dashed green.
#include <gtest/gtest.h>

#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "orodem/render/particle_view.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("orodem-render-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

struct Rgb8 {
    int r, g, b;
};

/// The 8-bit colour Cairo stores for a solid fill of (r, g, b) in [0, 1].
/// Tolerance 1 per channel: Cairo goes through 16-bit colour (d·65535 + 0.5,
/// then >> 8), which can differ by one from rounding d·255.
Rgb8 expect8(double r, double g, double b) {
    return {static_cast<int>(std::lround(r * 255)), static_cast<int>(std::lround(g * 255)),
            static_cast<int>(std::lround(b * 255))};
}

struct Image {
    cairo_surface_t* s = nullptr;
    explicit Image(const std::string& png) : s(cairo_image_surface_create_from_png(png.c_str())) {}
    ~Image() { cairo_surface_destroy(s); }
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
    bool ok() const { return cairo_surface_status(s) == CAIRO_STATUS_SUCCESS; }
    int width() const { return cairo_image_surface_get_width(s); }
    int height() const { return cairo_image_surface_get_height(s); }
    Rgb8 at(int x, int y) const {
        const unsigned char* row = cairo_image_surface_get_data(s) + y * cairo_image_surface_get_stride(s);
        std::uint32_t v;
        std::memcpy(&v, row + 4 * x, 4);  // RGB24 / ARGB32: 0x??RRGGBB native
        return {static_cast<int>((v >> 16) & 0xff), static_cast<int>((v >> 8) & 0xff), static_cast<int>(v & 0xff)};
    }
    /// The pixel where the point c [m] lies in a one-panel picture drawn with o.
    Rgb8 at_point(const ViewOptions& o, Vec2 c) const {
        const PlotArea a = plot_area(o, 1, 0);
        return at(static_cast<int>(std::floor(a.left + (c.x - o.x_min) * a.scale)),
                  static_cast<int>(std::floor(a.top + (o.y_max - c.y) * a.scale)));
    }
};

::testing::AssertionResult close_color(Rgb8 got, Rgb8 want) {
    if (std::abs(got.r - want.r) <= 1 && std::abs(got.g - want.g) <= 1 && std::abs(got.b - want.b) <= 1)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "pixel (" << got.r << "," << got.g << "," << got.b << ") expected ("
                                         << want.r << "," << want.g << "," << want.b << ") ±1";
}

ViewOptions view(int width_px) {
    ViewOptions o;
    o.x_min = -4.0;
    o.x_max = 4.0;
    o.y_min = 0.0;
    o.y_max = 2.0;
    o.h0 = 1.0;
    o.x_s = 0.0;
    o.width_px = width_px;
    o.band = 0.25;
    o.title = "test";
    return o;
}

std::string slurp_text(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// One panel of p at S = 0.
PictureInfo draw(const ParticleStore& p, const std::vector<double>* disp, const ViewOptions& o, const std::string& path) {
    return render_panels({{&p, disp, 0.0}}, o, path);
}

}  // namespace

TEST(Render, PngSizeAndHorizonColours) {
    const fs::path dir = scratch_dir("png");
    // Three large discs (radius 0.3 m = 60 px at this scale): proside band A
    // (depth in [0, band)), proside band B (depth in [band, 2 band)) and
    // retroside band A.
    ParticleStore p;
    const Vec2 c_pro_a{-2.5, 1.0}, c_pro_b{-0.5, 0.7}, c_retro_a{2.0, 1.2};
    const std::size_t a = p.add(c_pro_a, 0.3, 2500.0);
    const std::size_t b = p.add(c_pro_b, 0.3, 2500.0);
    const std::size_t r = p.add(c_retro_a, 0.3, 2500.0);
    p.initial_depth[a] = 0.1;
    p.initial_depth[b] = 0.3;
    p.initial_depth[r] = 0.05;
    p.side[r] = 1;

    const int width = 1690;
    const ViewOptions o = view(width);
    const std::string png = (dir / "h.png").string();
    const PictureInfo info = draw(p, nullptr, o, png);
    ASSERT_TRUE(fs::exists(png));
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
    Image img(png);
    ASSERT_TRUE(img.ok());

    // Width as requested, height as reported; the plot area keeps the view's
    // aspect ratio (same px/m in x and y).
    const PlotArea a0 = plot_area(o, 1, 0);
    EXPECT_EQ(img.width(), width);
    EXPECT_EQ(info.width_px, width);
    EXPECT_EQ(img.height(), info.height_px);
    EXPECT_EQ(picture_size(o, 1).height_px, info.height_px);
    EXPECT_NEAR(a0.height, a0.width * (o.y_max - o.y_min) / (o.x_max - o.x_min), 0.5);
    EXPECT_NEAR(a0.scale, a0.width / (o.x_max - o.x_min), 1e-9);
    // Fonts for print: 1/60 of the width, at least 2% of the height.
    EXPECT_GT(width / 60.0, 0.02 * img.height());

    auto pixel_of = [&](Vec2 x) { return img.at_point(o, x); };
    // Colours of particle_view.cpp: band A (0.93, 0.76, 0.38), band B
    // (0.55, 0.70, 0.85), retroside = 0.55 × the proside colour. A disc's
    // centre pixel lies 58 px inside its edge, so it is fully covered (no
    // antialiasing blend).
    const Rgb8 band_a = expect8(0.93, 0.76, 0.38), band_b = expect8(0.55, 0.70, 0.85);
    const Rgb8 retro_a = expect8(0.55 * 0.93, 0.55 * 0.76, 0.55 * 0.38);
    EXPECT_TRUE(close_color(pixel_of(c_pro_a), band_a));
    EXPECT_TRUE(close_color(pixel_of(c_pro_b), band_b));
    EXPECT_TRUE(close_color(pixel_of(c_retro_a), retro_a));
    // Retroside is darker than proside in every channel.
    const Rgb8 pa = pixel_of(c_pro_a), ra = pixel_of(c_retro_a), pb = pixel_of(c_pro_b);
    std::printf("    %dx%d px; centre pixels: pro band A (%d,%d,%d), pro band B (%d,%d,%d), retro band A (%d,%d,%d)\n",
                img.width(), img.height(), pa.r, pa.g, pa.b, pb.r, pb.g, pb.b, ra.r, ra.g, ra.b);
    EXPECT_LT(ra.r, pa.r);
    EXPECT_LT(ra.g, pa.g);
    EXPECT_LT(ra.b, pa.b);
    // Background: inside the data area, far from every disc.
    EXPECT_TRUE(close_color(pixel_of({1.0, 1.8}), {255, 255, 255}));
    EXPECT_TRUE(close_color(pixel_of({-3.5, 0.2}), {255, 255, 255}));

    // A wider picture: the same frame at a larger scale.
    ViewOptions o2 = o;
    o2.width_px = width + 800;
    const std::string png2 = (dir / "h2.png").string();
    draw(p, nullptr, o2, png2);
    Image img2(png2);
    ASSERT_TRUE(img2.ok());
    EXPECT_EQ(img2.width(), width + 800);
    EXPECT_GT(img2.height(), img.height());
    fs::remove_all(dir);
}

TEST(Render, SvgAndPdfAreWritten) {
    const fs::path dir = scratch_dir("vec");
    ParticleStore p;
    for (int k = 0; k < 20; ++k) p.add({-3.0 + 0.3 * k, 0.5}, 0.15, 2500.0);
    std::vector<double> disp(p.size());
    for (std::size_t s = 0; s < p.size(); ++s) disp[s] = static_cast<double>(s) / 19.0;
    for (const char* ext : {"svg", "pdf"}) {
        for (const ColorBy color_by : {ColorBy::horizons, ColorBy::displacement}) {
            ViewOptions o = view(800);
            o.color_by = color_by;
            const fs::path f = dir / (std::string(name_of(color_by)) + "." + ext);
            draw(p, &disp, o, f.string());
            ASSERT_TRUE(fs::exists(f)) << f;
            EXPECT_GT(fs::file_size(f), 100u) << f;
            for (const auto& e : fs::directory_iterator(dir))
                EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
            const std::string text = slurp_text(f);
            if (std::string(ext) == "pdf") {
                EXPECT_EQ(text.substr(0, 5), "%PDF-") << f;
            } else {
                // Editable text: the labels are <text> elements, not glyph outlines.
                EXPECT_NE(text.find("<svg"), std::string::npos) << f;
                EXPECT_NE(text.find(">S = 0.00</text>"), std::string::npos) << f;
                EXPECT_NE(text.find(">x / h0 (S point at 0)</text>"), std::string::npos) << f;
                EXPECT_NE(text.find(">" + picture_legend(o).title + "</text>"), std::string::npos) << f;
                EXPECT_EQ(text.find("<symbol"), std::string::npos) << f;
                EXPECT_EQ(std::count(text.begin(), text.end(), '\n') > 20, true);
                EXPECT_NE(text.find("<circle"), std::string::npos) << f;
            }
        }
    }
    fs::remove_all(dir);
}

TEST(Render, ThirtyThousandDiscsTiming) {
    // A 300 × 100 lattice of discs (paper size is ~30,000 discs); the time is
    // printed, not asserted (shared machine).
    const fs::path dir = scratch_dir("big");
    ParticleStore p;
    const double r = 0.01;
    for (int j = 0; j < 100; ++j)
        for (int i = 0; i < 300; ++i) {
            const std::size_t s = p.add({-3.0 + r + 2 * r * i + (j % 2) * r, r + j * std::sqrt(3.0) * r}, r, 2500.0);
            p.initial_depth[s] = 2.0 - p.x[s].y;
            p.side[s] = p.x[s].x > 0.0 ? 1 : 0;
        }
    ASSERT_EQ(p.size(), 30000u);
    ViewOptions o = view(1600);
    o.x_min = -3.1;
    o.x_max = 3.1;
    const std::string png = (dir / "big.png").string();
    const auto t0 = std::chrono::steady_clock::now();
    draw(p, nullptr, o, png);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("    render of %zu discs to a %d px wide PNG: %.3f s\n", p.size(), o.width_px, dt);
    Image img(png);
    EXPECT_TRUE(img.ok());
    fs::remove_all(dir);
}

TEST(Render, PositiveQuantileIsTheNearestRankOfThePositiveValues) {
    // 1000 positive values k/1000 (k = 1..1000), shuffled, and 500 zeros:
    // the 0.99 quantile of the positives by nearest rank is the value of rank
    // ceil(0.99 · 1000) = 990, i.e. 0.990; q = 1 gives the maximum; the zeros
    // do not count; no positive value gives 0.
    std::vector<double> v;
    for (int k = 1; k <= 1000; ++k) v.push_back((k * 7919 % 1000 + 1) / 1000.0);  // a permutation of 1..1000
    v.insert(v.begin() + 300, 500, 0.0);
    EXPECT_EQ(positive_quantile(v, 0.99), 990 / 1000.0);
    EXPECT_EQ(positive_quantile(v, 1.0), 1.0);
    EXPECT_EQ(positive_quantile(v, 0.5), 500 / 1000.0);
    EXPECT_EQ(positive_quantile(std::vector<double>(10, 0.0), 0.99), 0.0);
    EXPECT_EQ(positive_quantile({}, 0.99), 0.0);
}

TEST(Render, DisplacementColoursFollowTheFixedScale) {
    // Values per unit convergence: 0 is light grey (0.82, 0.82, 0.82), half
    // the top of the bar (kDisplacementFull = 0.3) sits halfway between the
    // map's second and third stops ((1, 0.85, 0.3) and (0.9, 0.35, 0.1)):
    // (0.95, 0.6, 0.2), the top is dark red (0.45, 0, 0.05), and an outlier
    // ten times the top is clipped to it. The colours do not depend on the
    // other discs' values (no per-frame maximum or quantile).
    const fs::path dir = scratch_dir("disp");
    ParticleStore p;
    std::vector<double> scalar;
    const Vec2 c_zero{-3.0, 1.0}, c_half{-1.5, 1.0}, c_top{0.0, 1.0}, c_outlier{2.0, 1.0};
    for (auto [c, v] : {std::pair{c_zero, 0.0}, {c_half, 0.5 * kDisplacementFull}, {c_top, kDisplacementFull},
                        {c_outlier, 10 * kDisplacementFull}}) {
        p.add(c, 0.3, 2500.0);
        scalar.push_back(v);
    }
    ViewOptions o = view(1690);
    o.color_by = ColorBy::displacement;
    const std::string png = (dir / "d.png").string();
    const PictureInfo info = draw(p, &scalar, o, png);
    Image img(png);
    ASSERT_TRUE(img.ok());
    auto pixel = [&](Vec2 c) { return img.at_point(o, c); };
    EXPECT_TRUE(close_color(pixel(c_zero), expect8(0.82, 0.82, 0.82)));
    EXPECT_TRUE(close_color(pixel(c_half), expect8(0.95, 0.6, 0.2)));
    EXPECT_TRUE(close_color(pixel(c_top), expect8(0.45, 0.0, 0.05)));
    EXPECT_TRUE(close_color(pixel(c_outlier), expect8(0.45, 0.0, 0.05)));
    // The legend: the fixed bar, whatever the values.
    EXPECT_EQ(info.legend.lo, 0.0);
    EXPECT_EQ(info.legend.hi, kDisplacementFull);
    EXPECT_EQ(info.legend.ticks, (std::vector<double>{0.0, 0.1, 0.2, 0.3}));
    for (double& v : scalar) v *= 0.01;
    const PictureInfo again = draw(p, &scalar, o, (dir / "d2.png").string());
    EXPECT_EQ(again.legend.hi, info.legend.hi);
    EXPECT_EQ(again.legend.title, info.legend.title);
    EXPECT_EQ(again.height_px, info.height_px);
    fs::remove_all(dir);
}

TEST(Render, OldSnapshotsAreScaledToTheirQuantileAndSaySo) {
    // A snapshot with only the normalised rel_disp (per_frame_scale): 198
    // discs carry 0.1, one 0.05, one outlier 1.0. The 0.99 quantile of the
    // 200 positives is the value of rank 198, 0.1: a 0.1 disc is at the top
    // colour, the 0.05 disc halfway, the outlier clipped; the legend runs
    // from 0 to 1 and names the per-frame scale.
    const fs::path dir = scratch_dir("old");
    ParticleStore p;
    std::vector<double> scalar;
    const Vec2 c_zone{-2.5, 1.0}, c_half{-0.5, 1.0}, c_outlier{2.0, 1.0};
    for (auto [c, v] : {std::pair{c_zone, 0.1}, {c_half, 0.05}, {c_outlier, 1.0}}) {
        p.add(c, 0.3, 2500.0);
        scalar.push_back(v);
    }
    for (int k = 0; k < 197; ++k) {  // off the picture: they count in the scale only
        p.add({100.0 + k, 1.0}, 0.3, 2500.0);
        scalar.push_back(0.1);
    }
    ViewOptions o = view(1690);
    o.color_by = ColorBy::displacement;
    o.per_frame_scale = true;
    const std::string png = (dir / "d.png").string();
    const PictureInfo info = draw(p, &scalar, o, png);
    Image img(png);
    ASSERT_TRUE(img.ok());
    auto pixel = [&](Vec2 c) { return img.at_point(o, c); };
    EXPECT_TRUE(close_color(pixel(c_zone), expect8(0.45, 0.0, 0.05)));
    EXPECT_TRUE(close_color(pixel(c_half), expect8(0.95, 0.6, 0.2)));
    EXPECT_TRUE(close_color(pixel(c_outlier), expect8(0.45, 0.0, 0.05)));
    EXPECT_EQ(info.legend.hi, 1.0);
    EXPECT_NE(info.legend.title.find("this frame"), std::string::npos) << info.legend.title;
    fs::remove_all(dir);
}

TEST(Render, StackedPanelsShareTheWidthAndTheFrame) {
    // Three panels: the same width, three plot areas of one size one above
    // the other, the picture taller than one panel by two panels and gaps.
    const fs::path dir = scratch_dir("stack");
    ParticleStore p;
    p.add({0.0, 0.5}, 0.3, 2500.0);
    const ViewOptions o = view(1200);
    const PictureInfo one = picture_size(o, 1);
    const PictureInfo three = render_panels({{&p, nullptr, 1.0}, {&p, nullptr, 2.0}, {&p, nullptr, 3.0}}, o,
                                            (dir / "s.png").string());
    Image img((dir / "s.png").string());
    ASSERT_TRUE(img.ok());
    EXPECT_EQ(img.width(), 1200);
    EXPECT_EQ(img.height(), three.height_px);
    const PlotArea a0 = plot_area(o, 3, 0), a1 = plot_area(o, 3, 1), a2 = plot_area(o, 3, 2);
    EXPECT_EQ(a0.left, a2.left);
    EXPECT_EQ(a0.height, a2.height);
    EXPECT_GT(a1.top, a0.top + a0.height);
    EXPECT_NEAR(three.height_px - one.height_px, 2 * (a1.top - a0.top), 1.0);
    // A disc over the top edge is cut off, and the panel says so.
    p.add({1.0, 2.0}, 0.3, 2500.0);
    render_panels({{&p, nullptr, 1.0}}, o, (dir / "cut.svg").string());
    EXPECT_NE(slurp_text(dir / "cut.svg").find(">material above the frame is cut off</text>"), std::string::npos);
    // Horizons legend: the swatches and the band thickness.
    EXPECT_EQ(three.legend.swatches.size(), 4u);
    EXPECT_NE(three.legend.title.find("0.25 h0"), std::string::npos) << three.legend.title;
    fs::remove_all(dir);
}

TEST(Render, RunViewIsTheModelBoxOfTheConfig) {
    // exp1, h0 = 10 m, s_max = 3, pro_margin = 10, retro_length = 8: x from
    // -10.5 h0 to 8.5 h0, y from -0.05 h0 to (1 + sqrt(6/6) + 0.15) h0.
    ConfigBasics b;
    b.experiment = "exp1";
    b.h0 = 10.0;
    b.s_max = 3.0;
    b.pro_margin = 10.0;
    b.retro_length = 8.0;
    const ViewOptions v = run_view(b, 1000);
    EXPECT_DOUBLE_EQ(v.x_min, -105.0);
    EXPECT_DOUBLE_EQ(v.x_max, 85.0);
    EXPECT_DOUBLE_EQ(v.y_min, -0.5);
    EXPECT_NEAR(v.y_max, 21.5, 1e-12);
    EXPECT_EQ(v.width_px, 1000);
    EXPECT_EQ(v.title, "exp1");
    // The critical wedge ends at its backstop.
    b.experiment = "critical-wedge";
    EXPECT_DOUBLE_EQ(run_view(b).x_max, 5.0);
}

TEST(Render, StrainColoursFollowTheFixedLogScale) {
    // Incremental γ on the log bar 1e-3..1: 1e-3 and below (and NaN, an
    // undefined strain) at the bottom colour, light grey; 10^-1.5, halfway
    // along the bar in log, halfway between the map's second and third stops
    // ((1, 0.85, 0.3) and (0.9, 0.35, 0.1)): (0.95, 0.6, 0.2); 1 and above at
    // the top, dark red. Every disc's pixel is bar_colour of its γ.
    const fs::path dir = scratch_dir("strain");
    ParticleStore p;
    std::vector<double> gamma;
    const std::vector<std::pair<Vec2, double>> discs = {
        {{-3.5, 1.0}, 1e-4}, {{-2.5, 1.0}, kStrainLo}, {{-1.5, 1.0}, std::pow(10.0, -1.5)}, {{-0.5, 1.0}, 0.05},
        {{0.5, 1.0}, kStrainHi}, {{1.5, 1.0}, 10.0}, {{2.5, 1.0}, std::nan("")}, {{3.5, 1.0}, 0.0}};
    for (const auto& [c, g] : discs) {
        p.add(c, 0.3, 2500.0);
        gamma.push_back(g);
    }
    ViewOptions o = view(1690);
    o.color_by = ColorBy::strain;
    o.output_ds = 0.25;
    const std::string png = (dir / "s.png").string();
    const PictureInfo info = render_panels({{&p, nullptr, 0.25, &gamma, nullptr}}, o, png);
    Image img(png);
    ASSERT_TRUE(img.ok());
    auto as8 = [](Colour c) { return expect8(c.r, c.g, c.b); };
    for (const auto& [c, g] : discs) EXPECT_TRUE(close_color(img.at_point(o, c), as8(bar_colour(info.legend, g)))) << g;
    const Rgb8 grey = expect8(0.82, 0.82, 0.82), dark = expect8(0.45, 0.0, 0.05);
    EXPECT_TRUE(close_color(img.at_point(o, discs[0].first), grey));
    EXPECT_TRUE(close_color(img.at_point(o, discs[1].first), grey));
    EXPECT_TRUE(close_color(img.at_point(o, discs[2].first), expect8(0.95, 0.6, 0.2)));
    EXPECT_TRUE(close_color(img.at_point(o, discs[4].first), dark));
    EXPECT_TRUE(close_color(img.at_point(o, discs[5].first), dark));
    EXPECT_TRUE(close_color(img.at_point(o, discs[6].first), grey));
    EXPECT_TRUE(close_color(img.at_point(o, discs[7].first), grey));
    // The legend: a fixed log bar labelled in decades, the fault line styles.
    EXPECT_TRUE(info.legend.log_scale);
    EXPECT_EQ(info.legend.lo, kStrainLo);
    EXPECT_EQ(info.legend.hi, kStrainHi);
    ASSERT_EQ(info.legend.ticks.size(), 4u);
    EXPECT_NEAR(info.legend.ticks[2], 0.1, 1e-15);
    EXPECT_NE(info.legend.title.find("ΔS = 0.25"), std::string::npos) << info.legend.title;
    EXPECT_EQ(info.legend.line_keys, (std::vector<std::string>{"pro-vergent fault", "retro-vergent fault"}));
    // The finite strain: its own fixed bar, 1e-2..10.
    o.color_by = ColorBy::strain_total;
    const Legend total = picture_legend(o);
    EXPECT_EQ(total.lo, kStrainTotalLo);
    EXPECT_EQ(total.hi, kStrainTotalHi);
    EXPECT_NE(total.title.find("since S = 0"), std::string::npos) << total.title;
    // SVG: the bar's labels are text.
    o.color_by = ColorBy::strain;
    render_panels({{&p, nullptr, 0.25, &gamma, nullptr}}, o, (dir / "s.svg").string());
    const std::string svg = slurp_text(dir / "s.svg");
    for (const char* s : {">≤ 0.001</text>", ">0.01</text>", ">≥ 1</text>", ">pro-vergent fault</text>"})
        EXPECT_NE(svg.find(s), std::string::npos) << s;
    fs::remove_all(dir);
}

TEST(Render, FaultLinesAreDrawnFromRootToTipInTheirVergenceStyle) {
    // Three faults, one inactive: only the two active ones become lines (in
    // metres: the table's h0 units times h0 = 2), drawn and returned in
    // order; the pro-vergent line is solid blue along its length, the
    // retro-vergent one dashed green (blue and green pixels found along
    // each, and white gaps along the dashed one).
    const fs::path dir = scratch_dir("faults");
    // (The lines are drawn level for the pixel checks; their table dips are
    // 30° and 45°. A fourth, active but dipping 5°, is outside the
    // detector's range, kFaultDipMinDeg: not a line.)
    std::vector<Fault> table(4);
    table[0].id = 7;
    table[0].vergence = 1;
    table[0].dip_deg = 30.0;
    table[0].root = {-1.5, 0.25};
    table[0].tip = {-0.5, 0.25};
    table[1].id = 8;
    table[1].vergence = -1;
    table[1].dip_deg = 45.0;
    table[1].root = {0.5, 0.75};
    table[1].tip = {1.5, 0.75};
    table[2] = table[0];
    table[2].active = false;
    table[3] = table[0];
    table[3].id = 9;
    table[3].dip_deg = 5.0;
    const std::vector<FaultLine> lines = active_fault_lines(table, 2.0);
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], (FaultLine{{-3.0, 0.5}, {-1.0, 0.5}, 1, 7}));
    EXPECT_EQ(lines[1], (FaultLine{{1.0, 1.5}, {3.0, 1.5}, -1, 8}));
    table[3].dip_deg = 80.0;  // too steep too
    EXPECT_EQ(active_fault_lines(table, 2.0).size(), 2u);
    ParticleStore p;
    p.add({0.0, 0.3}, 0.3, 2500.0);
    ViewOptions o = view(1600);
    o.color_by = ColorBy::strain;
    const std::string png = (dir / "f.png").string();
    const PictureInfo info = render_panels({{&p, nullptr, 1.0, nullptr, &lines}}, o, png);
    EXPECT_EQ(info.faults_drawn, lines);
    Image img(png);
    ASSERT_TRUE(img.ok());
    const PlotArea a = plot_area(o, 1, 0);
    auto count_along = [&](const FaultLine& f, auto pred) {  // pixels within ±2 rows of the line's row
        int n = 0;
        const int Y = static_cast<int>(std::floor(a.top + (o.y_max - f.root.y) * a.scale));
        for (double x = f.root.x + 0.05; x < f.tip.x - 0.05; x += 0.01)
            for (int dy = -2; dy <= 2; ++dy)
                n += pred(img.at(static_cast<int>(std::floor(a.left + (x - o.x_min) * a.scale)), Y + dy)) ? 1 : 0;
        return n;
    };
    auto blue = [](Rgb8 c) { return c.b > 200 && c.r < 60; };
    auto green = [](Rgb8 c) { return c.g > 120 && c.r < 40 && c.b < 100; };
    auto white = [](Rgb8 c) { return c.r > 250 && c.g > 250 && c.b > 250; };
    EXPECT_GT(count_along(lines[0], blue), 150);
    EXPECT_EQ(count_along(lines[0], green), 0);
    EXPECT_GT(count_along(lines[1], green), 50);
    EXPECT_EQ(count_along(lines[1], blue), 0);
    // The dashed line's gaps: white (its halo) on the line's own row.
    int gaps = 0;
    for (double x = lines[1].root.x + 0.05; x < lines[1].tip.x - 0.05; x += 0.01)
        gaps += white(img.at_point(o, {x, lines[1].root.y})) ? 1 : 0;
    EXPECT_GT(gaps, 20);
    // Horizons and displacement pictures draw no fault lines.
    o.color_by = ColorBy::horizons;
    EXPECT_TRUE(render_panels({{&p, nullptr, 1.0, nullptr, &lines}}, o, png).faults_drawn.empty());
    fs::remove_all(dir);
}
