// Pictures of the particle state (SPEC §3 "Pictures"; render/particle_view):
// the PNG decodes with the requested width and the height that the view's
// aspect ratio implies; disc centres carry their horizon colour (proside band
// A, band B, retroside a darker shade of A); the background is white; SVG and
// PDF are written too; and 30,000 discs render quickly (time printed only).
#include <gtest/gtest.h>

#include <cairo.h>
#include <unistd.h>

#include <chrono>
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

// Plot frame of particle_view.cpp: margins in pixels (left, right, top,
// bottom) around the data area, whose scale is the same in x and y.
constexpr double kMarginL = 70, kMarginR = 20, kMarginT = 40, kMarginB = 50;

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
    o.label = "test";
    return o;
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

    const int width = 1690;  // data area 1600 px over 8 m: 200 px/m
    const ViewOptions o = view(width);
    const std::string png = (dir / "h.png").string();
    render_particles(p, nullptr, o, png);
    ASSERT_TRUE(fs::exists(png));
    EXPECT_FALSE(fs::exists(png + ".tmp"));
    Image img(png);
    ASSERT_TRUE(img.ok());

    // Width as requested; height: the data area keeps the view's aspect
    // ratio (same px/m in x and y) inside the fixed pixel margins.
    const double scale = (width - kMarginL - kMarginR) / (o.x_max - o.x_min);
    const int height = static_cast<int>(std::ceil((o.y_max - o.y_min) * scale + kMarginT + kMarginB));
    EXPECT_EQ(img.width(), width);
    EXPECT_EQ(img.height(), height);  // 2 m · 200 px/m + 90 = 490

    auto pixel_of = [&](Vec2 x) {
        return img.at(static_cast<int>(std::floor(kMarginL + (x.x - o.x_min) * scale)),
                      static_cast<int>(std::floor(kMarginT + (o.y_max - x.y) * scale)));
    };
    // Colours of particle_view.cpp: band A (0.93, 0.76, 0.38), band B
    // (0.55, 0.70, 0.85), retroside = 0.55 × the proside colour. A disc's
    // centre pixel lies 60 px inside its edge, so it is fully covered (no
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

    // Margin-independent aspect check: doubling the data-area width doubles
    // its height, so the picture grows by (Δwidth) · (y range / x range),
    // ±1 px for the ceil.
    ViewOptions o2 = o;
    o2.width_px = width + 800;
    const std::string png2 = (dir / "h2.png").string();
    render_particles(p, nullptr, o2, png2);
    Image img2(png2);
    ASSERT_TRUE(img2.ok());
    EXPECT_EQ(img2.width(), width + 800);
    EXPECT_NEAR(img2.height() - img.height(), 800.0 * (o.y_max - o.y_min) / (o.x_max - o.x_min), 1.0);
    fs::remove_all(dir);
}

TEST(Render, SvgAndPdfAreWritten) {
    const fs::path dir = scratch_dir("vec");
    ParticleStore p;
    for (int k = 0; k < 20; ++k) p.add({-3.0 + 0.3 * k, 0.5}, 0.15, 2500.0);
    std::vector<double> disp(p.size());
    for (std::size_t s = 0; s < p.size(); ++s) disp[s] = static_cast<double>(s) / 19.0;
    for (const char* ext : {"svg", "pdf"}) {
        for (const char* color_by : {"horizons", "displacement"}) {
            ViewOptions o = view(800);
            o.color_by = color_by;
            const fs::path f = dir / (std::string(color_by) + "." + ext);
            render_particles(p, &disp, o, f.string());
            ASSERT_TRUE(fs::exists(f)) << f;
            EXPECT_GT(fs::file_size(f), 100u) << f;
            EXPECT_FALSE(fs::exists(f.string() + ".tmp"));
            std::ifstream in(f, std::ios::binary);
            std::string head(256, '\0');
            in.read(head.data(), static_cast<std::streamsize>(head.size()));
            if (std::string(ext) == "pdf") EXPECT_EQ(head.substr(0, 5), "%PDF-") << f;
            else EXPECT_NE(head.find("<svg"), std::string::npos) << f;
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
    render_particles(p, nullptr, o, png);
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

TEST(Render, DisplacementColourIsScaledToTheQuantileNotTheMaximum) {
    // 200 discs: 198 carry 0.1 (a shear zone), one 0.05, one outlier 1.0 (a
    // disc rolling down a slope). The 0.99 quantile of the 200 positives is
    // the value of rank 198: 0.1. So a 0.1 disc is full dark red (scaled
    // value 1: (0.65, 0.1, 0.1)), the 0.05 disc mid orange (scaled 0.5:
    // (1, 0.75, 0.1)), and the outlier clipped to full red. Scaled to the
    // maximum instead, the 0.1 disc would be near white (1, 0.95, 0.82).
    const fs::path dir = scratch_dir("disp");
    ParticleStore p;
    std::vector<double> scalar;
    const Vec2 c_zone{-2.5, 1.0}, c_half{-0.5, 1.0}, c_outlier{2.0, 1.0};
    p.add(c_zone, 0.3, 2500.0);
    scalar.push_back(0.1);
    p.add(c_half, 0.3, 2500.0);
    scalar.push_back(0.05);
    p.add(c_outlier, 0.3, 2500.0);
    scalar.push_back(1.0);
    for (int k = 0; k < 197; ++k) {  // off the picture: they count in the scale only
        p.add({100.0 + k, 1.0}, 0.3, 2500.0);
        scalar.push_back(0.1);
    }
    ViewOptions o = view(1690);
    o.color_by = "displacement";
    const std::string png = (dir / "d.png").string();
    render_particles(p, &scalar, o, png);
    Image img(png);
    ASSERT_TRUE(img.ok());
    const double scale = (1690 - kMarginL - kMarginR) / (o.x_max - o.x_min);
    auto pixel = [&](Vec2 c) {
        return img.at(static_cast<int>(kMarginL + (c.x - o.x_min) * scale),
                      static_cast<int>(kMarginT + (o.y_max - c.y) * scale));
    };
    EXPECT_TRUE(close_color(pixel(c_zone), expect8(0.65, 0.1, 0.1)));
    EXPECT_TRUE(close_color(pixel(c_half), expect8(1.0, 0.75, 0.1)));
    EXPECT_TRUE(close_color(pixel(c_outlier), expect8(0.65, 0.1, 0.1)));
    fs::remove_all(dir);
}
