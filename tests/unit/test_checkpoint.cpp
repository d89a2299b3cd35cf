// Checkpoints (SPEC §5, RELIABILITY-CHECKLIST 9-11): a restored wedge steps
// on bit for bit in lockstep with the original, at any thread count; corrupt,
// truncated, other-version and other-config files are refused with a reason
// and never change the Simulation; a failed write keeps the older files.
// Health checks (checklist 1, 2, 5) find the disc at fault.
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

#include <gtest/gtest.h>

#include "orodem/boundary/conveyor_traction.hpp"
#include "orodem/boundary/fixed_retro.hpp"
#include "orodem/engine/health.hpp"
#include "orodem/io/checkpoint.hpp"
#include "orodem/io/config.hpp"
#include "orodem/io/files.hpp"
#include "orodem/setup/packing.hpp"
#include "orodem/setup/scenario.hpp"
#include "orodem/setup/wedge.hpp"

using namespace orodem;
namespace fs = std::filesystem;

namespace {

const char* kWedgeToml =
    "[run]\nexperiment = \"exp1\"\nthreads = 1\n"
    "[wedge]\nv = 0.3\ns_max = 0.5\noutput_ds = 0.1\npro_margin = 3.0\nretro_length = 3.0\n"
    "[packing]\nh0 = 6.0\nr_min = 0.5\nr_max = 1.0\n";

/// A small exp1 wedge from a briefly settled (not fully settled) layer.
struct Fixture {
    Config c = parse_config(kWedgeToml, "ckpt.toml");
    ParticleStore layer;
    Fixture() {
        Simulation s = make_settle_simulation(c);
        s.initialize();
        s.advance(3000);
        cut_layer(s.particles, c.packing.h0);
        layer = std::move(s.particles);
    }
};

const Fixture& fixture() {
    static const Fixture f;
    return f;
}

/// A wedge stepped k steps (many rebuilds, discs fixed on the retro base).
WedgeSetup stepped_wedge(std::uint64_t k) {
    WedgeSetup w = make_wedge(fixture().c, fixture().layer);
    w.sim.initialize();
    w.sim.advance(k);
    return w;
}

RunLoopState some_run_state(const Simulation& sim) {
    RunLoopState r;
    r.outputs = 3;
    for (std::uint32_t id = 0; id < sim.particles.size(); ++id)
        r.x_then.push_back(sim.particles.x[sim.particles.slot_of_id[id]]);
    r.pvd = {{0.0, "snapshots/S00.000.vtu"}, {0.1, "snapshots/S00.100.vtu"}};
    r.series_bytes = 1234;
    r.log_bytes = 567;
    r.surface_y_mean = 4.5;
    return r;
}

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("orodem-ckpt-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

std::string refusal(const std::string& bytes, std::uint64_t hash, Simulation& sim) {
    RunLoopState run;
    try {
        decode_checkpoint(bytes, hash, sim, run);
    } catch (const ConfigError& e) {
        return std::string("config: ") + e.what();
    } catch (const CheckpointError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Checkpoint, RestoredWedgeStepsInLockstepBitForBit) {
    omp_set_num_threads(1);
    const std::uint64_t hash = config_hash(fixture().c);
    WedgeSetup a = stepped_wedge(1500);
    ASSERT_GT(a.sim.rebuild_count(), 2u);
    const RunLoopState run = some_run_state(a.sim);
    const std::string bytes = encode_checkpoint(a.sim, run, hash);

    WedgeSetup b = make_wedge(fixture().c, ParticleStore{});
    RunLoopState back;
    decode_checkpoint(bytes, hash, b.sim, back);
    EXPECT_EQ(back.outputs, run.outputs);
    EXPECT_EQ(back.pvd, run.pvd);
    EXPECT_EQ(back.series_bytes, run.series_bytes);
    EXPECT_EQ(back.log_bytes, run.log_bytes);
    EXPECT_EQ(back.surface_y_mean, run.surface_y_mean);
    ASSERT_EQ(back.x_then.size(), run.x_then.size());
    // Everything saved comes back: the restored state encodes to the same bytes.
    EXPECT_EQ(encode_checkpoint(b.sim, back, hash), bytes);
    EXPECT_EQ(b.sim.state_hash(), a.sim.state_hash());
    EXPECT_EQ(b.sim.rebuild_count(), a.sim.rebuild_count());
    EXPECT_EQ(b.base->total_traction(), a.base->total_traction());
    EXPECT_EQ(b.fixed_retro->fixed_count(), a.fixed_retro->fixed_count());

    // A third copy restored and stepped at another thread count.
    WedgeSetup c3 = make_wedge(fixture().c, ParticleStore{});
    decode_checkpoint(bytes, hash, c3.sim, back);
    for (int k = 0; k < 1500; ++k) {
        omp_set_num_threads(1);
        a.sim.step();
        b.sim.step();
        omp_set_num_threads(3);
        c3.sim.step();
        const std::uint64_t h = a.sim.state_hash();
        ASSERT_EQ(b.sim.state_hash(), h) << "restored copy diverged at step " << a.sim.step_count;
        ASSERT_EQ(c3.sim.state_hash(), h) << "3-thread restored copy diverged at step " << a.sim.step_count;
        ASSERT_EQ(b.base->total_traction(), a.base->total_traction()) << a.sim.step_count;
    }
    EXPECT_EQ(b.sim.rebuild_count(), a.sim.rebuild_count());
    EXPECT_EQ(b.fixed_retro->fixed_count(), a.fixed_retro->fixed_count());
    EXPECT_EQ(b.sim.time, a.sim.time);
    EXPECT_EQ(encode_checkpoint(b.sim, back, hash), encode_checkpoint(a.sim, back, hash));
    omp_set_num_threads(1);
}

TEST(Checkpoint, CorruptTruncatedOtherVersionAndOtherConfigAreRefused) {
    omp_set_num_threads(1);
    const std::uint64_t hash = config_hash(fixture().c);
    WedgeSetup a = stepped_wedge(300);
    const std::string good = encode_checkpoint(a.sim, some_run_state(a.sim), hash);
    WedgeSetup target = stepped_wedge(10);
    const std::uint64_t before = target.sim.state_hash();
    const std::size_t n_before = target.sim.particles.size();

    std::string flipped = good;
    flipped[good.size() / 2] ^= 0x01;
    EXPECT_NE(refusal(flipped, hash, target.sim).find("payload checksum mismatch"), std::string::npos)
        << refusal(flipped, hash, target.sim);

    std::string head_flipped = good;
    head_flipped[20] ^= 0x40;  // inside the program version string
    EXPECT_NE(refusal(head_flipped, hash, target.sim).find("header checksum mismatch"), std::string::npos)
        << refusal(head_flipped, hash, target.sim);

    EXPECT_NE(refusal(good.substr(0, good.size() - 100), hash, target.sim).find("truncated"), std::string::npos);
    EXPECT_NE(refusal(good.substr(0, 30), hash, target.sim).find("truncated"), std::string::npos)
        << refusal(good.substr(0, 30), hash, target.sim);
    EXPECT_NE(refusal("", hash, target.sim).find("not an orodem checkpoint"), std::string::npos);

    std::string other_version = good;
    const std::uint32_t v99 = 99;
    std::memcpy(other_version.data() + 8, &v99, 4);
    EXPECT_NE(refusal(other_version, hash, target.sim).find("format version 99"), std::string::npos)
        << refusal(other_version, hash, target.sim);

    const Config other = parse_config(kWedgeToml, "ckpt.toml", {{"wedge.mu_bp", "0.4"}});
    ASSERT_NE(config_hash(other), hash);
    EXPECT_NE(refusal(good, config_hash(other), target.sim).find("config: the checkpoint was made with another config"),
              std::string::npos);
    // The thread count is not part of the hash: a run may resume at another.
    EXPECT_EQ(config_hash(parse_config(kWedgeToml, "x.toml", {{"run.threads", "4"}})), hash);
    // wedge.sleep_buffer_pro at its default, the value of wedge.sleep_buffer,
    // is left out of the hashed text, as it was before the key existed, so
    // older runs resume; another value changes the hash.
    EXPECT_EQ(config_hash(parse_config(kWedgeToml, "x.toml", {{"wedge.sleep_buffer_pro", "2.0"}})), hash);
    const Config buf1 = parse_config(kWedgeToml, "x.toml", {{"wedge.sleep_buffer", "1.0"}});
    EXPECT_DOUBLE_EQ(buf1.wedge.sleep_buffer_pro, 1.0);
    EXPECT_EQ(to_toml_without_defaults(buf1).find("sleep_buffer_pro"), std::string::npos) << to_toml_without_defaults(buf1);
    EXPECT_NE(to_toml_without_defaults(buf1).find("sleep_buffer = 1.0"), std::string::npos);
    EXPECT_NE(config_hash(parse_config(kWedgeToml, "x.toml", {{"wedge.sleep_buffer_pro", "1.0"}})), hash);

    // None of the refusals touched the target.
    EXPECT_EQ(target.sim.state_hash(), before);
    EXPECT_EQ(target.sim.particles.size(), n_before);
    // A checkpoint of another experiment (no FixedRetroside) does not fit.
    const Config exp3 = parse_config(std::string(kWedgeToml) , "ckpt.toml", {{"run.experiment", "\"exp3\""}});
    WedgeSetup w3 = make_wedge(exp3, ParticleStore{});
    EXPECT_NE(refusal(good, hash, w3.sim).find("boundary 1 is 'fixed-retroside', the experiment's is 'coulomb-base'"),
              std::string::npos)
        << refusal(good, hash, w3.sim);
}

// A damaged newest checkpoint (truncated after it was written) is not one of
// the two kept: writing the next keeps the good older one, so a resume
// always has an intact checkpoint to fall back on.
TEST(Checkpoint, ATruncatedCheckpointIsNotCountedAmongTheTwoKept) {
    omp_set_num_threads(1);
    TempDir tmp;
    const std::string dir = (tmp.path / "checkpoint").string();
    const std::uint64_t hash = config_hash(fixture().c);
    WedgeSetup a = stepped_wedge(100);
    std::vector<std::string> written;
    for (int k = 0; k < 2; ++k) {
        written.push_back(write_checkpoint(dir, a.sim.step_count, encode_checkpoint(a.sim, some_run_state(a.sim), hash)));
        a.sim.advance(50);
    }
    const std::string good_old = written[0];
    std::filesystem::resize_file(written[1], std::filesystem::file_size(written[1]) / 2);  // the newest, truncated
    EXPECT_TRUE(checkpoint_file_intact(good_old));
    EXPECT_FALSE(checkpoint_file_intact(written[1]));
    const std::string third = write_checkpoint(dir, a.sim.step_count, encode_checkpoint(a.sim, some_run_state(a.sim), hash));
    EXPECT_TRUE(std::filesystem::exists(good_old)) << "the good older checkpoint was deleted";
    EXPECT_TRUE(std::filesystem::exists(third));
    // With a fourth, the two newest intact ones are kept and the rest goes.
    a.sim.advance(50);
    const std::string fourth = write_checkpoint(dir, a.sim.step_count, encode_checkpoint(a.sim, some_run_state(a.sim), hash));
    const auto files = list_checkpoints(dir);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0].second, fourth);
    EXPECT_EQ(files[1].second, third);
}

TEST(Checkpoint, KeepsTheLastTwoAndFallsBackFromACorruptNewest) {
    omp_set_num_threads(1);
    TempDir tmp;
    const std::string dir = (tmp.path / "checkpoint").string();
    const std::uint64_t hash = config_hash(fixture().c);
    WedgeSetup a = stepped_wedge(100);
    std::vector<std::uint64_t> hashes;
    for (int k = 0; k < 3; ++k) {
        write_checkpoint(dir, a.sim.step_count, encode_checkpoint(a.sim, some_run_state(a.sim), hash));
        hashes.push_back(a.sim.state_hash());
        a.sim.advance(50);
    }
    auto files = list_checkpoints(dir);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0].first, 200u);
    EXPECT_EQ(files[1].first, 150u);

    // Corrupt the newest: the older one is used and the reason reported.
    std::string bytes = read_file(files[0].second);
    bytes[bytes.size() - 10] ^= 0x20;
    write_file_atomic(files[0].second, bytes);
    WedgeSetup b = make_wedge(fixture().c, ParticleStore{});
    RunLoopState run;
    std::vector<std::string> notes;
    EXPECT_EQ(restore_newest_checkpoint(dir, hash, b.sim, run, &notes), files[1].second);
    EXPECT_EQ(b.sim.state_hash(), hashes[1]);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("checksum mismatch"), std::string::npos) << notes[0];

    // Both bad: refused, naming each file and why.
    write_file_atomic(files[1].second, "garbage");
    try {
        restore_newest_checkpoint(dir, hash, b.sim, run);
        ADD_FAILURE() << "no usable checkpoint was accepted";
    } catch (const CheckpointError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("no usable checkpoint"), std::string::npos) << m;
        EXPECT_NE(m.find("not an orodem checkpoint"), std::string::npos) << m;
    }
    EXPECT_THROW(restore_newest_checkpoint((tmp.path / "none").string(), hash, b.sim, run), CheckpointError);
}

TEST(Checkpoint, AFailedWriteLeavesTheOlderCheckpointsIntactAndNoHalfFile) {
    omp_set_num_threads(1);
    TempDir tmp;
    const std::string dir = (tmp.path / "checkpoint").string();
    const std::uint64_t hash = config_hash(fixture().c);
    WedgeSetup a = stepped_wedge(100);
    write_checkpoint(dir, 100, encode_checkpoint(a.sim, some_run_state(a.sim), hash));
    a.sim.advance(50);
    write_checkpoint(dir, 150, encode_checkpoint(a.sim, some_run_state(a.sim), hash));
    a.sim.advance(50);
    // The final name is taken by a non-empty directory: the rename into place fails (works as root too), and
    // the temporary is removed.
    fs::create_directories(dir + "/ckpt-000000000200.bin/x");
    EXPECT_THROW(write_checkpoint(dir, 200, encode_checkpoint(a.sim, some_run_state(a.sim), hash)), IoError);
    fs::remove_all(dir + "/ckpt-000000000200.bin");
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    const auto files = list_checkpoints(dir);
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0].first, 150u);
    EXPECT_EQ(files[1].first, 100u);
    EXPECT_FALSE(fs::exists(dir + "/ckpt-000000000200.bin"));
    for (const auto& [step, path] : files) EXPECT_NO_THROW(verify_checkpoint(read_file(path), hash)) << path;
}

TEST(Health, FindsNonFiniteOverlapSpeedAndEscapedDiscs) {
    omp_set_num_threads(1);
    WedgeSetup w = stepped_wedge(200);
    Simulation& sim = w.sim;
    HealthLimits lim;
    lim.max_speed = 100.0;
    lim.x_min = -1000.0;
    lim.x_max = 1000.0;
    lim.y_min = -6.0;
    lim.y_max = 200.0;
    ASSERT_FALSE(check_health(sim, lim).has_value());

    const std::uint32_t id = 7;
    const std::size_t s = sim.particles.slot_of_id[id];
    const Vec2 keep_v = sim.particles.v[s], keep_x = sim.particles.x[s];
    sim.particles.v[s].y = std::numeric_limits<double>::quiet_NaN();
    auto p = check_health(sim, lim);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->what, "non-finite velocity");
    EXPECT_EQ(p->id, id);
    EXPECT_NE(p->advice.find("numerics.safety"), std::string::npos);
    sim.particles.v[s] = {0.0, 150.0};
    p = check_health(sim, lim);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->what, "speed");
    EXPECT_EQ(p->id, id);
    sim.particles.v[s] = keep_v;
    sim.particles.x[s] = {keep_x.x, -50.0};
    p = check_health(sim, lim);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->what, "left the domain");
    EXPECT_EQ(p->id, id);
    EXPECT_EQ(p->x.y, -50.0);
    sim.particles.x[s] = keep_x;
    // Put one disc of an unbonded candidate pair onto its partner: an overlap explosion.
    const ContactStore& cs = sim.contacts;
    std::size_t k = 0;
    while (k < cs.size() && cs.bonded[k]) ++k;
    ASSERT_LT(k, cs.size());
    sim.particles.x[cs.i[k]] = sim.particles.x[cs.j[k]] + Vec2{0.01, 0.0};
    p = check_health(sim, lim);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->what, "overlap");
    EXPECT_NE(p->detail.find("run.max_overlap_ratio"), std::string::npos) << p->detail;
}

TEST(Checkpoint, TheConfigHashIgnoresKeysAtTheirDefaultsSoANewerVersionResumes) {
    // A run directory's config.toml written by an older orodem lacks the keys
    // added since; they take their defaults and must not change the hash.
    const Config& c = fixture().c;
    const std::string full = to_toml(c);
    std::string older;
    std::istringstream lines(full);
    int dropped = 0;
    for (std::string line; std::getline(lines, line);) {
        const bool added_later = line.rfind("warn_overlap_ratio =", 0) == 0 || line.rfind("on_domain_exit =", 0) == 0 ||
                                 line.rfind("sleep =", 0) == 0;
        if (added_later) ++dropped; else older += line + "\n";
    }
    ASSERT_EQ(dropped, 3) << full;
    const Config old = parse_config(older, "config.toml");
    EXPECT_NE(older, full);  // the texts differ ...
    EXPECT_EQ(config_hash(old), config_hash(c));  // ... the hashes do not
    // A key set away from its default, even one the older file lacked, counts.
    EXPECT_NE(config_hash(parse_config(older, "config.toml", {{"run.warn_overlap_ratio", "0.05"}})), config_hash(c));
    EXPECT_NE(config_hash(parse_config(older, "config.toml", {{"wedge.sleep", "true"}})), config_hash(c));
    // So does a value written out at a default that is not this version's one.
    EXPECT_NE(config_hash(parse_config(full, "config.toml", {{"material.damping_normal", "0.6"}})), config_hash(c));
}

TEST(Checkpoint, AWedgeRunsResolvedConfigLoadsAgainWithTheSameHash) {
    // `orodem run DIR/config.toml --out DIR --resume` reads the run's own
    // config.toml, which holds the derived packing.length.
    const Config& c = fixture().c;
    const Config again = parse_config(to_toml(c), "config.toml");
    EXPECT_EQ(to_toml(again), to_toml(c));
    EXPECT_EQ(config_hash(again), config_hash(c));
    // Any other packing.length is still refused for a wedge.
    try {
        parse_config(std::string(kWedgeToml) + "length = 40.0\n", "x.toml");
        ADD_FAILURE() << "packing.length = 40 accepted for a wedge";
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("'packing.length'"), std::string::npos) << e.what();
    }
}
