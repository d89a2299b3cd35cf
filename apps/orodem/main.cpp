// orodem command line: parses arguments with CLI11, hands typed values to the
// subcommands (commands.hpp) and maps errors to exit statuses (0 ok,
// 1 internal, 2 bad config or arguments, 3 unstable, 4 I/O, 6 a missing program
// (ffmpeg, sbatch), 7 the scheduler refused a job; an interrupted
// run returns 130 for SIGINT, 143 for SIGTERM after writing a checkpoint).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <cstdio>

#include "commands.hpp"
#include "orodem/core/error.hpp"
#include "orodem/engine/pair_kernel.hpp"

using namespace orodem;

namespace {

/// --scheduler and the Slurm options of sweep and resume; `cpus` describes --cpus-per-task.
/// Refuses NaN and infinities, which CLI11's ranges let through (NaN compares false with both ends).
const CLI::Validator kFinite(
    [](const std::string& s) {
        try {
            if (!std::isfinite(std::stod(s))) return std::string("must be a finite number, not ") + s;
        } catch (const std::exception&) {  // not a number at all: the option's own parse refuses it
        }
        return std::string();
    },
    "FINITE");

/// A --color-by option: one of kColorBys's names, parsed once into `out`.
CLI::Option* add_color_by(CLI::App* cmd, orodem::ColorBy& out, const std::string& help) {
    std::vector<std::string> names;
    for (const auto& n : orodem::kColorBys) names.emplace_back(n.name);
    return cmd->add_option_function<std::string>(
                  "--color-by", [&out](const std::string& v) { orodem::value_in(orodem::kColorBys, v, out); }, help)
        ->check(CLI::IsMember(names))
        ->default_str(orodem::name_of(out));
}

void add_scheduler_options(CLI::App* cmd, SchedulerArgs& s, const std::string& cpus) {
    cmd->add_option("--scheduler", s.scheduler, "Where a sweep's runs go: local (this machine) or slurm (one Slurm "
                                                "job array, scripts in DIR/slurm/)")
        ->check(CLI::IsMember({"local", "slurm"}))
        ->capture_default_str();
    auto given = [&s](const auto&) { s.slurm_given = true; };
    cmd->add_option("--partition", s.slurm.partition, "Slurm partition (default: the cluster's)")->each(given);
    cmd->add_option("--time", s.slurm.time, "Wall-time limit of each array task, HH:MM:SS or D-HH:MM:SS (default: "
                                            "the partition's); a member stopped by it continues with orodem resume "
                                            "DIR --scheduler slurm")
        ->each(given);
    cmd->add_option("--cpus-per-task", s.slurm.cpus_per_task, "Slurm: " + cpus)
        ->check(CLI::Range(1, 1024))
        ->each(given);
    cmd->add_option("--sbatch-arg", s.slurm.sbatch_args, "A further sbatch option, e.g. --sbatch-arg=--account=geo "
                                                         "(repeatable)")
        ->allow_extra_args(false)
        ->each(given);
}

}  // namespace

int main(int argc, char** argv) {
    // Whole lines as they are printed, also into a file or a pipe (a run
    // started with nohup shows "resuming ..." at once, not at its end).
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    // The step kernels' instruction-set version, once for the process: the
    // best the CPU runs, or the one ORODEM_ISA names (engine/pair_kernel.hpp).
    KernelIsa isa = KernelIsa::sse2;
    try {
        isa = select_kernel_isa(std::getenv("ORODEM_ISA"));
    } catch (const ConfigError& e) {
        fmt::print(stderr, "orodem: error: {}\n", e.what());
        return static_cast<int>(ExitCode::config);
    }
    CLI::App app{"orodem: discrete element model of doubly vergent orogenic wedges (Naylor et al. 2005)"};
    app.require_subcommand(1);
    app.set_version_flag("--version", fmt::format("{} (step kernels: {})", ORODEM_VERSION, isa_name(isa)));

    CommonArgs run_args, check_args;
    std::string out;
    auto* run = app.add_subcommand("run", "Run the experiment of CONFIG into a new run directory");
    run->add_option("config", run_args.config, "TOML config file")->required();
    run->add_option("--out", out, "Output directory (new or empty); default runs/<config name>");
    run->add_option("--set", run_args.sets, "Override a config value, e.g. --set material.mu=0.5")->take_all();
    run->add_option("--threads", run_args.threads, "OpenMP threads (0 = all cores)")->check(CLI::Range(0, 1024));
    run->add_flag("--force", run_args.force, "Start a run estimated to take more than a week (refused otherwise)");
    bool resume = false;
    run->add_flag("--resume", resume, "Continue the run in --out DIR from its newest usable checkpoint (same config; "
                                      "the outputs end up as those of an uninterrupted run)");

    CommonArgs resume_args;
    std::string resume_dir;
    auto* resume_cmd = app.add_subcommand("resume", "Continue the run in RUN_DIR from its newest usable checkpoint "
                                                    "(same as: run RUN_DIR/config.toml --out RUN_DIR --resume), or "
                                                    "the sweep in a sweep's folder: its finished runs kept, the "
                                                    "interrupted one continued, the rest started");
    resume_cmd->add_option("run_dir", resume_dir, "Run directory, or a sweep's folder")->required();
    resume_cmd->add_option("--threads", resume_args.threads, "OpenMP threads (0 = all cores)")->check(CLI::Range(0, 1024));
    int resume_jobs = 1;
    resume_cmd->add_option("--jobs", resume_jobs, "A sweep's runs at once, each in its own process with the cores "
                                                  "shared among them unless --threads is given")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    double resume_s_max = std::nan("");
    auto* resume_s_max_opt =
        resume_cmd->add_option("--s-max", resume_s_max, "Extend a run (finished or not) to this S on the same incoming "
                                                        "plate: wedge.s_max = S, wedge.pro_margin shortened by as "
                                                        "much; refused (nothing changed) when the plate is too short")
            ->check(CLI::Range(0.0, 100.0))
            ->check(kFinite);
    SchedulerArgs resume_sched;
    resume_sched.slurm.cpus_per_task = 0;  // as in DIR/slurm/array.sh
    add_scheduler_options(resume_cmd, resume_sched, "the CPUs of each array task (default: as in DIR/slurm/array.sh)");

    std::string member_dir;
    int member_threads = -1;
    auto* member = app.add_subcommand("sweep-member", "One run of a parallel sweep (started by orodem sweep --jobs)");
    member->group("");  // internal: not listed in --help
    member->add_option("run_dir", member_dir, "The member's folder")->required();
    member->add_option("--threads", member_threads, "OpenMP threads");

    std::string status_dir;
    auto* status = app.add_subcommand("status", "Where the wedge run in RUN_DIR (or each run of a sweep's folder) stands: "
                                                "S reached, how its last piece ended, newest checkpoint, time left, how "
                                                "to continue it; writes nothing");
    status->add_option("run_dir", status_dir, "Run directory")->required();
    auto* check = app.add_subcommand("check", "Validate CONFIG and print the resolved config, particle count and dt; writes nothing");
    check->add_option("config", check_args.config, "TOML config file")->required();
    check->add_option("--set", check_args.sets, "Override a config value")->take_all();

    CommonArgs sweep_args;
    std::vector<std::string> sweep_vary;
    std::string sweep_out;
    auto* sweep = app.add_subcommand("sweep", "One run per value of a config key, into DIR/<key>=<value>/, then the "
                                              "overlay plots; an interrupted sweep continues with orodem resume DIR");
    sweep->add_option("config", sweep_args.config, "TOML config file")->required();
    sweep->add_option("--vary", sweep_vary, "key=v1,v2,..., e.g. wedge.mu_bp=0.1,0.2,0.3; given again for another "
                                            "key, the runs are every combination (run.seed=1,2,3 as one of them: "
                                            "each group's mean over its seeds in the plots)")
        ->required()
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    sweep->add_option("--out", sweep_out, "Output directory (new or empty); default runs/<config name>-sweep");
    sweep->add_option("--set", sweep_args.sets, "Override a config value")->take_all();
    sweep->add_option("--threads", sweep_args.threads, "OpenMP threads (0 = all cores)")->check(CLI::Range(0, 1024));
    sweep->add_flag("--force", sweep_args.force, "Start runs estimated to take more than a week (refused otherwise)");
    int sweep_jobs = 1;
    sweep->add_option("--jobs", sweep_jobs, "Runs at once, each in its own process with the cores shared among "
                                            "them unless --threads is given")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    SchedulerArgs sweep_sched;
    add_scheduler_options(sweep, sweep_sched, "the CPUs of each array task, and its member's --threads");

    std::string settle_dir;
    int settle_threads = -1;
    auto* settle = app.add_subcommand("sweep-settle", "The packings a sweep's members share, settled once (the Slurm "
                                                      "job its array waits for)");
    settle->group("");  // internal: not listed in --help
    settle->add_option("sweep_dir", settle_dir, "The sweep's folder")->required();
    settle->add_option("--threads", settle_threads, "OpenMP threads");

    std::vector<std::string> plot_dirs;
    std::string plot_out;
    bool plot_seeds = false;
    auto* plot = app.add_subcommand("plot", "Plot alpha, beta, H/h0, peak deviation and dilation against S for one or "
                                            "more runs, overlaid and labelled by what differs between their configs");
    plot->add_option("run_dirs", plot_dirs, "Run directories (each with config.toml and series.csv)")->required();
    plot->add_option("--out", plot_out, "Output file, .png, .svg or .pdf; default RUN_DIR/figures/plots.png for "
                                        "one run, <common parent>/plots.png for several");
    plot->add_flag("--seeds", plot_seeds, "Draw the runs that differ only in their seeds (run.seed, packing.seed) as "
                                          "one curve each: the mean over the seeds, over a band shaded from the "
                                          "lowest to the highest value");

    RenderArgs ra;
    auto* render = app.add_subcommand("render", "Pictures of a run's saved snapshots (run.pvd) in the run's frame and "
                                                "colour scales: with --out FILE one figure stacking the snapshots "
                                                "nearest --at (as the paper's Figures 9 and 13), else the horizon, "
                                                "displacement and strain picture of each snapshot into --dir");
    render->add_option("run_dir", ra.run_dir, "Run directory")->required();
    render->add_option("--at", ra.at, "Shortenings S, e.g. --at 1,2.5: the snapshots nearest them (default: with "
                                      "--out four evenly spread up to the last, else all)")
        ->delimiter(',');
    auto* render_out = render->add_option("--out", ra.out, "One stacked figure, .png, .svg (text as <text>) or .pdf");
    add_color_by(render, ra.color_by, "The stacked figure's colouring (strain: γ of the output interval, "
                                      "strain_total: since S = 0; both with the active faults)")
        ->needs(render_out);
    render->add_option("--dir", ra.dir, "Folder of the per-snapshot pictures (default RUN_DIR/figures/rendered)")
        ->excludes(render_out);
    render->add_option("--format", ra.format, "Format of the per-snapshot pictures")
        ->check(CLI::IsMember({"png", "svg", "pdf"}))
        ->excludes(render_out)
        ->capture_default_str();
    render->add_option("--width", ra.width, "Picture width in pixels")
        ->check(CLI::Range(200, 20000))
        ->capture_default_str();
    render->add_option("--xlim", ra.xlim, "Crop the frame to x from A to B h0 from the S point, e.g. --xlim -6,3 "
                                          "(the deformed zone; default the run's whole frame)")
        ->delimiter(',')
        ->check(kFinite);
    render->add_option("--title", ra.title, "The pictures' title (default the experiment's name)");
    render->add_flag("--force", ra.force, "Replace files that exist already (never done otherwise)");

    MovieArgs ma;
    auto* movie = app.add_subcommand("movie", "An animation of a run's saved snapshots, --seconds long at --fps, each "
                                              "snapshot shown for an equal time (held, or cross-faded with --blend), "
                                              "in the run's frame and colour scales (needs ffmpeg: exit status 6 "
                                              "without it)");
    movie->add_option("run_dir", ma.run_dir, "Run directory")->required();
    movie->add_option("--out", ma.out, "Output file, .mp4 or .gif")->required();
    add_color_by(movie, ma.color_by, "Colouring");
    movie->add_option("--fps", ma.fps, "The file's frame rate, frames per second")->check(CLI::Range(1.0, 60.0))->check(kFinite)->capture_default_str();
    movie->add_option("--seconds", ma.seconds, "The movie's length in seconds; each snapshot is shown for "
                                               "seconds / snapshots")
        ->check(CLI::Range(0.5, 3600.0))
        ->check(kFinite)
        ->capture_default_str();
    movie->add_flag("--blend", ma.blend, "Cross-fade from each snapshot to the next (ffmpeg's framerate filter: "
                                         "a blend of two pictures, not a simulated state) instead of holding each");
    movie->add_option("--xlim", ma.xlim, "Crop the frame to x from A to B h0 from the S point")
        ->delimiter(',')
        ->check(kFinite);
    movie->add_option("--title", ma.title, "The frames' title (default the experiment's name)");
    movie->add_option("--width", ma.width, "Frame width in pixels")->check(CLI::Range(200, 8000))->capture_default_str();
    movie->add_flag("--force", ma.force, "Replace the file if it exists already");

    std::string measure_dir;
    auto* measure = app.add_subcommand("measure", "The wedge measures (H, alpha, beta, the retroside in two "
                                                  "slopes, peak, toes, dilation) of each saved snapshot of a wedge "
                                                  "run, taken again, as CSV on standard output; writes nothing");
    measure->add_option("run_dir", measure_dir, "Run directory")->required();

    std::string faults_dir;
    double faults_at_S = std::nan("");
    bool faults_csv = false, faults_recompute = false;
    auto* faults = app.add_subcommand("faults", "The faults of a wedge run at one output (the last, or the one "
                                                "nearest --at): stage, active pro- and retro-vergent faults, frontal "
                                                "thrust, and each fault's dip, root, tip, width and slip; writes nothing");
    faults->add_option("run_dir", faults_dir, "Run directory")->required();
    faults->add_option("--at", faults_at_S, "Normalised convergence S of the output (the nearest one)")
        ->check(CLI::Range(0.0, 1e9));
    faults->add_flag("--csv", faults_csv, "Every output, in the format of faults.csv");
    faults->add_flag("--recompute", faults_recompute,
                     "Compute the table from the snapshots even where the run has a faults.csv");

    double taper_phi = 0.0, taper_phib = std::nan(""), taper_mu_b = std::nan(""), taper_beta = 0.0;
    auto* taper = app.add_subcommand("taper", "Critical surface slopes of a dry noncohesive Coulomb wedge "
                                              "(exact solution of Dahlen 1984, both branches)");
    taper->add_option("--phi", taper_phi, "Internal friction angle phi, degrees, in (0, 90)")->required()->check(kFinite);
    auto* taper_phib_opt = taper->add_option("--phib", taper_phib, "Basal friction angle phi_b, degrees, in [0, phi)")->check(kFinite);
    taper->add_option("--mu-b", taper_mu_b, "Basal friction coefficient mu_b = tan(phi_b), instead of --phib")
        ->check(kFinite)
        ->excludes(taper_phib_opt);
    taper->add_option("--beta", taper_beta, "Basal dip beta, degrees, positive toward the hinterland")
        ->capture_default_str();

    CommonArgs calib_args;
    std::string calib_out;
    auto* calib = app.add_subcommand("calibrate", "Run the calibration experiment of CONFIG (biaxial, basal-friction, "
                                                  "repose) into a new run directory with report.md");
    calib->add_option("config", calib_args.config, "TOML config file")->required();
    calib->add_option("--out", calib_out, "Output directory (new or empty); default runs/<config name>");
    calib->add_option("--set", calib_args.sets, "Override a config value")->take_all();
    calib->add_option("--threads", calib_args.threads, "OpenMP threads (0 = all cores)")->check(CLI::Range(0, 1024));

    auto* bench = app.add_subcommand("bench", "Performance benchmarks");
    bench->require_subcommand(1);
    auto* pile = bench->add_subcommand("pile", "The canonical 30,000-disc pile of ../shared/bench (checks the LAMMPS reference)");
    std::string pile_file = "../shared/bench/settled.txt";
    std::uint64_t pile_steps = 20000;
    int pile_threads = 0;
    pile->add_option("--pile", pile_file, "Start state, 'id x y r' per line")->capture_default_str();
    pile->add_option("--steps", pile_steps, "Timesteps to run")->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000000}))->capture_default_str();
    pile->add_option("--threads", pile_threads, "OpenMP threads (0 = all cores)")->check(CLI::Range(0, 1024));

    // A first word that is neither an option nor a command: say so (CLI11
    // would only say that a subcommand is required).
    if (argc > 1 && argv[1][0] != '-') {
        std::string names;
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands([](const CLI::App* a) { return !a->get_group().empty(); })) {
            known = known || sub->get_name() == argv[1];
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known && std::string(argv[1]) != "sweep-member" && std::string(argv[1]) != "sweep-settle") {
            fmt::print(stderr, "orodem: error: unknown command '{}'; the commands are {} (orodem --help)\n", argv[1],
                       names);
            return static_cast<int>(ExitCode::config);
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : static_cast<int>(ExitCode::config);
    }
    try {
        if (*run) return cmd_run(run_args, out, resume);
        if (*resume_cmd && resume_s_max_opt->count() > 0) {
            if (resume_jobs != 1 || resume_sched.scheduler != "local" || resume_sched.slurm_given)
                throw ConfigError("--s-max extends one run on this machine; --jobs and the Slurm options are for "
                                  "a sweep's folder");
            return cmd_extend(resume_dir, resume_s_max, resume_args.threads);
        }
        if (*resume_cmd) return cmd_resume(resume_dir, resume_args.threads, resume_jobs, resume_sched);
        if (*settle) return cmd_sweep_settle(settle_dir, settle_threads);
        if (*member) return cmd_sweep_member(member_dir, member_threads);
        if (*status) return cmd_status(status_dir);
        if (*check) return cmd_check(check_args);
        if (*sweep) return cmd_sweep(sweep_args, sweep_vary, sweep_out, sweep_jobs, sweep_sched);
        if (*calib) return cmd_calibrate(calib_args, calib_out);
        if (*plot) return cmd_plot(plot_dirs, plot_out, plot_seeds);
        if (*render) return cmd_render(ra);
        if (*movie) return cmd_movie(ma);
        if (*measure) return cmd_measure(measure_dir);
        if (*faults) return cmd_faults(faults_dir, faults_at_S, faults_csv, faults_recompute);
        if (*taper) return cmd_taper(taper_phi, taper_phib, taper_mu_b, taper_beta);
        if (*pile) return cmd_bench_pile(pile_file, pile_steps, pile_threads);
    } catch (const ConfigError& e) {
        fmt::print(stderr, "orodem: error: {}\n", e.what());
        return static_cast<int>(ExitCode::config);
    } catch (const IoError& e) {
        fmt::print(stderr, "orodem: I/O error: {}\n", e.what());
        return static_cast<int>(ExitCode::io);
    } catch (const InterruptedError& e) {
        fmt::print(stderr, "\norodem: interrupted: {}\n", e.what());
        return 128 + e.signal;
    } catch (const MissingToolError& e) {
        fmt::print(stderr, "orodem: error: {}\n", e.what());
        return static_cast<int>(ExitCode::missing_tool);
    } catch (const SchedulerError& e) {
        fmt::print(stderr, "orodem: scheduler error: {}\n", e.what());
        return static_cast<int>(ExitCode::scheduler);
    } catch (const InstabilityError& e) {
        fmt::print(stderr, "orodem: unstable: {}\n", e.what());
        return static_cast<int>(ExitCode::unstable);
    } catch (const std::exception& e) {
        fmt::print(stderr, "orodem: internal error: {}\n", e.what());
        return static_cast<int>(ExitCode::internal);
    }
    return 0;
}
