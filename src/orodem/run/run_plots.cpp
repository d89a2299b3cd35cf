#include "orodem/run/run_plots.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "orodem/core/error.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/io/series_reader.hpp"
#include "orodem/render/plots.hpp"
#include "orodem/run/run_dir.hpp"

namespace fs = std::filesystem;
namespace orodem {

namespace {

/// path made absolute and normal, without a trailing separator.
fs::path normal(const std::string& p) {
    fs::path a = fs::absolute(fs::path(p)).lexically_normal();
    if (a.filename().empty() && a.has_parent_path()) a = a.parent_path();
    return a;
}

/// The deepest directory holding all of dirs.
fs::path common_parent(const std::vector<fs::path>& dirs) {
    fs::path common = dirs.front().parent_path();
    for (const fs::path& d : dirs) {
        const fs::path parent = d.parent_path();
        fs::path shared;
        auto a = common.begin(), b = parent.begin();
        for (; a != common.end() && b != parent.end() && *a == *b; ++a, ++b) shared /= *a;
        common = shared;
    }
    return common.empty() ? fs::path("/") : common;
}

}  // namespace

RunPlot plot_runs(const std::vector<std::string>& run_dirs, const std::string& out_arg, bool seeds) {
    RunPlot result;
    if (run_dirs.empty()) throw ConfigError("plot: give at least one run directory");
    std::vector<std::string> texts, names, sources, experiments;
    std::vector<Series> series;
    std::vector<fs::path> absolute;
    for (const std::string& dir : run_dirs) {
        require_run_dir(dir);
        const fs::path a = normal(dir);
        absolute.push_back(a);
        names.push_back(a.filename().string());
        sources.push_back((fs::path(dir) / "config.toml").string());
        texts.push_back(read_file(sources.back()));
        experiments.push_back(experiment_in(texts.back()));
        const fs::path csv = fs::path(dir) / "series.csv";
        if (!fs::exists(csv)) throw IoError(fmt::format("'{}': no such file; the run wrote no series", csv.string()));
        series.push_back(read_series_csv(csv.string()));
    }
    std::vector<std::string> labels = legend_labels(texts, names, sources);
    std::vector<SeriesEnsemble> ensembles;
    std::vector<SeriesBand> bands;
    if (seeds) {  // one curve per group of runs that differ only in their seeds
        const std::vector<std::size_t> group = seed_groups(texts, names, sources);
        const std::size_t n_groups = *std::max_element(group.begin(), group.end()) + 1;
        std::vector<std::string> g_texts, g_names, g_sources;
        std::vector<std::vector<const Series*>> members(n_groups);
        for (std::size_t i = 0; i < group.size(); ++i) {
            if (members[group[i]].empty())
                g_texts.push_back(texts[i]), g_names.push_back(names[i]), g_sources.push_back(sources[i]);
            members[group[i]].push_back(&series[i]);
        }
        const std::vector<std::string> g_labels = legend_labels(g_texts, g_names, g_sources, true);
        ensembles.reserve(n_groups);  // bands point into it
        std::vector<Series> means;
        labels.clear();
        for (std::size_t g = 0; g < n_groups; ++g) {
            ensembles.push_back(seed_ensemble(members[g]));
            means.push_back(ensembles.back().mean);
            bands.push_back({&ensembles.back().lo, &ensembles.back().hi});
            const std::size_t n = members[g].size();
            labels.push_back(n_groups == 1 ? fmt::format("mean of {} seeds, band: lowest to highest", n)
                                           : fmt::format("{} ({} seed{})", g_labels[g], n, n == 1 ? "" : "s"));
            std::string runs;
            for (std::size_t i = 0; i < group.size(); ++i)
                if (group[i] == g) runs += (runs.empty() ? "" : ", ") + names[i];
            result.notes.push_back(fmt::format("{}: {}", labels.back(), runs));
        }
        series = std::move(means);
    }

    std::string out = out_arg;
    if (out.empty())
        out = run_dirs.size() == 1 ? (fs::path(run_dirs.front()) / "figures" / "plots.png").string()
                                   : (common_parent(absolute) / "plots.png").string();
    const fs::path out_path(out);
    std::string ext = out_path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != ".png" && ext != ".svg" && ext != ".pdf")
        throw ConfigError(fmt::format("--out '{}': the file name must end in .png, .svg or .pdf", out));
    if (out_path.has_parent_path()) make_dirs(out_path.parent_path().string());

    PlotOptions o;
    bool same_experiment = true;
    for (const auto& e : experiments) same_experiment = same_experiment && e == experiments.front();
    const std::string what = same_experiment && !experiments.front().empty() ? experiments.front() + ": " : "";
    o.title = run_dirs.size() == 1
                  ? fmt::format("{}{}", what, names.front())
                  : fmt::format("{}{} runs in {}", what, run_dirs.size(), common_parent(absolute).filename().string());
    plot_series(series, labels, out, o, bands);
    result.path = out;
    return result;
}

}  // namespace orodem
