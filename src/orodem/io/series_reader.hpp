// Reading back what a run directory holds, for `orodem plot` and
// `orodem render`: series.csv as named numeric columns, legend labels for
// several runs from the differences between their resolved config.toml, and
// the runs that differ only in their seeds, gathered into one ensemble.
#pragma once

#include <string>
#include <vector>

namespace orodem {

/// series.csv: the header's column names and one vector of values per column.
/// "nan", "-nan" and empty fields read as NaN.
struct Series {
    std::string path;                         // the file it was read from
    std::vector<std::string> names;           // header columns
    std::vector<std::vector<double>> values;  // values[c][row]
    std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
    /// The column called name, or nullptr.
    const std::vector<double>* column(const std::string& name) const;
};

/// Reads a CSV with a header row. Throws IoError naming the path when the file
/// cannot be read or a row is malformed (a last line without its newline, as
/// a run stopped mid-write leaves it, is skipped).
Series read_series_csv(const std::string& path);

/// The number of columns of `file_header` (the first line of the CSV file
/// `path`) when they are the leading columns of `header`, i.e. the file was
/// started by an orodem that wrote fewer columns; throws ConfigError naming
/// both headers otherwise.
std::size_t csv_leading_columns(const std::string& file_header, const std::string& header, const std::string& path);

/// The first n comma-separated fields of a CSV line (all of it when it has fewer).
std::string csv_first_fields(const std::string& line, std::size_t n);

/// Legend labels for runs whose resolved configs are `config_texts` (TOML):
/// the keys whose values differ among the runs, "key = value" joined by ", "
/// (at most three, then "+N more"). Keys that do not change the physics
/// (run.threads, packing.cache_dir) are ignored. Where nothing differs, or the
/// labels would not tell the runs apart, names[i] is used. `sources` name the
/// texts in errors (a TOML syntax error throws IoError naming the source).
/// With ignore_seeds, run.seed and packing.seed are ignored too (labels for
/// the seed groups of seed_groups).
std::vector<std::string> legend_labels(const std::vector<std::string>& config_texts,
                                       const std::vector<std::string>& names,
                                       const std::vector<std::string>& sources, bool ignore_seeds = false);

/// Whether `key` (e.g. "run.seed") changes only the random packing: run.seed
/// or packing.seed, the keys seed_groups ignores.
bool is_seed_key(const std::string& key);

/// Groups of runs that differ only in their seeds: group[i] is the index of
/// run i's group, groups numbered in order of first appearance. Two runs are
/// in one group when their resolved configs agree on every key except
/// run.seed, packing.seed and the keys legend_labels ignores. Errors as
/// legend_labels.
std::vector<std::size_t> seed_groups(const std::vector<std::string>& config_texts,
                                     const std::vector<std::string>& names,
                                     const std::vector<std::string>& sources);

/// Several runs of one config with different seeds, row by row: rows are
/// matched by their S (to 1e-6), over the union of the members' S values in
/// increasing order; each other column holds the mean (`mean`), the lowest
/// (`lo`) and the highest (`hi`) of the members' finite values at that S, or
/// NaN where none is finite. `count` has the number of finite values per
/// column and row.
struct SeriesEnsemble {
    Series mean, lo, hi;
    std::vector<std::vector<int>> count;  // count[c][row]
};
/// Throws ConfigError when a member lacks the column "S" or a column of the
/// first member.
SeriesEnsemble seed_ensemble(const std::vector<const Series*>& members);

}  // namespace orodem
