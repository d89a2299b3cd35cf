// The S plots (render/plots) and the calibration plots (render/
// calibration_plots) on the drawing canvas: SVG output carries the titles,
// axis labels, tick labels and legend entries as <text> elements (no glyph
// outlines); every font is at least 0.85/60 of the figure's width (the tick
// labels; everything else 1/60 or more), at any width; a PNG has the pixel
// size the plots had before they moved to the canvas (1400 x 976 for one run
// with a title, computed by the old code); PDF starts as a PDF; crowded x
// tick labels are thinned to every 2nd (5th, 10th) tick.
#include <gtest/gtest.h>

#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "orodem/io/series_reader.hpp"
#include "orodem/render/calibration_plots.hpp"
#include "orodem/render/plot_util.hpp"
#include "orodem/render/plots.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("orodem-plots-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A wedge run's series: S = 0 .. 1, NaN angles before a wedge exists, H/h0 over 0.5 (kTaperMinHeight) from S = 0.5.
Series series(double alpha_shift) {
    Series s;
    s.path = "series.csv";
    s.names = kPlotColumns;
    const double nan = std::nan("");
    s.values = {{0.0, 0.25, 0.5, 0.75, 1.0},
                {nan, nan, 12.5 + alpha_shift, 14 + alpha_shift, 15 + alpha_shift},
                {nan, nan, 8.25, 9.3, 10},
                {0.1, 0.3, 0.6, 0.7, 0.8},
                {0.5, 0.1, -0.2, -0.3, -0.4},
                {nan, 20, 35, nan, 50}};
    return s;
}

/// Every <text> element's font size in an SVG.
std::vector<double> font_sizes(const std::string& svg) {
    std::vector<double> out;
    const std::regex re("<text [^>]*font-size=\"([0-9.]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back(std::stod((*it)[1]));
    return out;
}

bool has_text(const std::string& svg, const std::string& s) { return svg.find(">" + s + "</text>") != std::string::npos; }

std::pair<int, int> png_size(const fs::path& p) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(p.c_str());
    std::pair<int, int> wh{-1, -1};
    if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS)
        wh = {cairo_image_surface_get_width(s), cairo_image_surface_get_height(s)};
    cairo_surface_destroy(s);
    return wh;
}

}  // namespace

TEST(Plots, SvgHasEditableTitlesAxisLabelsTicksAndLegend) {
    const fs::path dir = scratch_dir("svg");
    const std::vector<Series> runs = {series(0.0), series(1.0)};
    PlotOptions o;
    o.title = "exp1: 2 runs in sweep";
    plot_series(runs, {"wedge.mu_bp = 0.1", "wedge.mu_bp = 0.2"}, (dir / "p.svg").string(), o);
    const std::string svg = slurp(dir / "p.svg");
    EXPECT_EQ(svg.find("<symbol"), std::string::npos);  // no glyph outlines
    for (const char* s : {"exp1: 2 runs in sweep", "(a) Taper angles α, β (where H ≥ 0.5 h0)", "(b) Wedge height",
                          "(c) Peak deviation from the S point", "(d) Dilation", "S (shortening / h0)",
                          "angle (degrees)", "H / h0", "(x_peak − x_S) / h0", "D (%)", "α (prowedge)",
                          "β (retrowedge)", "wedge.mu_bp = 0.1", "wedge.mu_bp = 0.2", "0.5", "-0.4",
                          // every symbol defined in the figure
                          "α, β: slopes of the pro- and retrowedge surface (line fits), drawn where the wedge height H "
                          "≥ 0.5 h0",
                          "S: shortening / h0; h0: the incoming layer's thickness; H: wedge height above the "
                          "undeformed surface",
                          "x_peak − x_S: where the highest surface column stands, from the S point",
                          "D (%): dilation, the deformed wedge's area against the area of the layer it accreted"})
        EXPECT_TRUE(has_text(svg, s)) << s;
    // Four panels, each with its x label.
    std::size_t n = 0;
    for (auto p = svg.find(">S (shortening / h0)</text>"); p != std::string::npos;
         p = svg.find(">S (shortening / h0)</text>", p + 1))
        ++n;
    EXPECT_EQ(n, 4u);
    // The curves are polylines in the runs' colours, the second angle dashed.
    EXPECT_NE(svg.find("<polyline points=\""), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#1f78b5\""), std::string::npos);  // palette 0 (0.12, 0.47, 0.71)
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
    fs::remove_all(dir);
}

TEST(Plots, FontsScaleWithTheWidth) {
    const fs::path dir = scratch_dir("fonts");
    const std::vector<Series> runs = {series(0.0)};
    for (int width : {800, 1400, 2800}) {
        PlotOptions o;
        o.width_px = width;
        o.title = "exp1: r1";
        const fs::path p = dir / ("w" + std::to_string(width) + ".svg");
        plot_series(runs, {"r1"}, p.string(), o);
        const std::vector<double> sizes = font_sizes(slurp(p));
        ASSERT_GT(sizes.size(), 30u) << width;
        const double lo = *std::min_element(sizes.begin(), sizes.end());
        const double hi = *std::max_element(sizes.begin(), sizes.end());
        EXPECT_GE(lo, 0.85 * width / 60.0 - 0.01) << width;  // tick labels: 0.85 of 1/60 of the width
        EXPECT_LE(hi, 1.15 * width / 60.0 + 0.01) << width;  // the figure's title
    }
    // The calibration plots follow the same rule.
    PlotPanel panel{"Stress ratio", "axial strain ε_a", "σ_1 / σ_3", {}};
    panel.curves.push_back({{0, 0.01, 0.02}, {1, 2, 2.5}, "μ_i = 0.3", 0, false, false});
    panel.curves.push_back({{0, 0.01, 0.02}, {1, 1.5, 1.8}, "μ_i = 0.5", 1, true, false});
    plot_panels({panel, panel}, 2, "Biaxial tests", (dir / "cal.svg").string(), 1400);
    const std::string cal = slurp(dir / "cal.svg");
    for (const char* s : {"Biaxial tests", "Stress ratio", "axial strain ε_a", "σ_1 / σ_3", "μ_i = 0.3", "μ_i = 0.5"})
        EXPECT_TRUE(has_text(cal, s)) << s;
    const std::vector<double> sizes = font_sizes(cal);
    EXPECT_GE(*std::min_element(sizes.begin(), sizes.end()), 0.85 * 1400 / 60.0 - 0.01);
    fs::remove_all(dir);
}

TEST(Plots, PngKeepsTheSizeOfTheRequest) {
    const fs::path dir = scratch_dir("png");
    PlotOptions o;
    o.title = "exp1: r1";
    // The sizes the plots had before the canvas (the old code's output for
    // these requests): one legend row, with and without a title.
    // The four notes that define the symbols add a legend row each (24 px at this width).
    plot_series({series(0.0)}, {"r1"}, (dir / "a.png").string(), o);
    EXPECT_EQ(png_size(dir / "a.png"), std::make_pair(1400, 976 + 4 * 24));
    // Three runs whose legend takes two rows at the new font but took one
    // at the old: the old size all the same.
    plot_series({series(0.0), series(1.0), series(2.0)}, {"wedge.mu_bp = 0.1", "wedge.mu_bp = 0.2", "wedge.mu_bp = 0.3"},
                (dir / "b.png").string(), o);
    EXPECT_EQ(png_size(dir / "b.png"), std::make_pair(1400, 976 + 4 * 24));
    o.title.clear();
    o.width_px = 2000;
    plot_series({series(0.0)}, {"r1"}, (dir / "c.png").string(), o);
    EXPECT_EQ(png_size(dir / "c.png"), std::make_pair(2000, plot::legacy_height(2000, 2, 2, 0.6, false, 1 + 4)));
    EXPECT_EQ(plot::legacy_height(1400, 2, 2, 0.6, true, 1), 976);
    // The calibration bar chart: 1000 px wide, a title and one legend row.
    plot_bars({"discs", "clusters"}, {{"μ_bp = 0.3", {0.3, 0.31}, {0.01, 0.02}}}, "Basal friction", "packing",
              "μ_eff", (dir / "bars.png").string(), 1000);
    EXPECT_EQ(png_size(dir / "bars.png"), std::make_pair(1000, 664));
    // PDF too.
    plot_series({series(0.0)}, {"r1"}, (dir / "d.pdf").string(), o);
    EXPECT_EQ(slurp(dir / "d.pdf").substr(0, 5), "%PDF-");
    fs::remove_all(dir);
}

TEST(Plots, SeedBandIsShadedInThePlotAndTheLegend) {
    const fs::path dir = scratch_dir("band");
    const Series mean = series(0.5), lo = series(0.0), hi = series(1.0);
    plot_series({mean}, {"mean of 2 seeds, band: lowest to highest"}, (dir / "s.svg").string(), {},
                {{&lo, &hi}});
    const std::string svg = slurp(dir / "s.svg");
    EXPECT_TRUE(has_text(svg, "mean of 2 seeds, band: lowest to highest"));
    // Bands under α, β, H and peak (one run of finite rows each) and D (two:
    // S = 0.25-0.5 and 1), and one legend swatch.
    std::size_t n = 0;
    for (auto p = svg.find("fill-opacity=\"0.200\""); p != std::string::npos; p = svg.find("fill-opacity=\"0.200\"", p + 1))
        ++n;
    EXPECT_EQ(n, 6u + 1u);
    fs::remove_all(dir);
}

TEST(Plots, TaperAnglesHaveStandardErrorBandsAndAreMaskedWhileTheWedgeIsLow) {
    const fs::path dir = scratch_dir("se");
    Series s = series(0.0);
    // H/h0 = 0.3 at S = 0.25, where α and β have values: masked (below 0.5).
    s.values[1][1] = 85.0;
    s.values[2][1] = 75.0;
    s.names.insert(s.names.end(), {"alpha_se_deg", "beta_se_deg"});
    s.values.push_back({std::nan(""), 7.0, 1.0, 1.0, 1.0});
    s.values.push_back({std::nan(""), 7.0, 0.5, 0.5, 0.5});
    plot_series({s}, {"r1"}, (dir / "s.svg").string());
    const std::string svg = slurp(dir / "s.svg");
    // One band each under α and β (S = 0.5 to 1), none elsewhere and no swatch.
    std::size_t n = 0;
    for (auto p = svg.find("fill-opacity=\"0.200\""); p != std::string::npos; p = svg.find("fill-opacity=\"0.200\"", p + 1))
        ++n;
    EXPECT_EQ(n, 2u);
    EXPECT_TRUE(has_text(svg, "shaded around α, β: ± 1 standard error of the line fits"));
    // The masked 85° never sets the angle axis (no panel has ticks beyond 50).
    EXPECT_FALSE(has_text(svg, "80"));
    EXPECT_FALSE(has_text(svg, "60"));
    fs::remove_all(dir);
}

TEST(Plots, CrowdedTickLabelsAreThinned) {
    // x from 0 to 0.05 in steps of 0.005 on a half-width panel: labels at
    // 0.01, 0.02, ... only, none overlapping; at full width all of them.
    const fs::path dir = scratch_dir("ticks");
    PlotPanel panel{"Stress ratio", "axial strain ε_a", "σ_1 / σ_3", {}};
    panel.curves.push_back({{0, 0.025, 0.05}, {1, 2, 2.5}, "μ_i = 0.3", 0, false, false});
    plot_panels({panel, panel}, 2, "", (dir / "half.svg").string(), 1400);
    const std::string half = slurp(dir / "half.svg");
    EXPECT_TRUE(has_text(half, "0.01"));
    EXPECT_TRUE(has_text(half, "0.05"));
    EXPECT_FALSE(has_text(half, "0.005"));
    EXPECT_FALSE(has_text(half, "0.045"));
    plot_panels({panel}, 1, "", (dir / "full.svg").string(), 1400);
    EXPECT_TRUE(has_text(slurp(dir / "full.svg"), "0.005"));
    fs::remove_all(dir);
}
