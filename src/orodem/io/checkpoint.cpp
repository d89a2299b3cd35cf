#include "orodem/io/checkpoint.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "orodem/core/bytes.hpp"
#include "orodem/core/hash.hpp"
#include "orodem/io/files.hpp"

namespace orodem {

namespace {

constexpr char kMagic[8] = {'O', 'R', 'O', 'D', 'E', 'M', 'C', 'K'};

std::uint64_t fnv(std::string_view b) {
    Fnv1a h;
    h.add_bytes(b.data(), b.size());
    return h.value();
}

void put_walls(ByteWriter& w, const std::vector<Wall>& walls) {
    w.put(static_cast<std::uint64_t>(walls.size()));
    for (const Wall& x : walls) {
        w.put(x.a); w.put(x.b); w.put(x.velocity); w.put(x.surface_speed);
        w.put(static_cast<std::uint8_t>(x.infinite)); w.put(static_cast<std::uint8_t>(x.rough));
        w.put(x.mu); w.put(static_cast<std::uint8_t>(x.open_ends));
    }
}

std::vector<Wall> get_walls(ByteReader& r) {
    const auto n = r.get<std::uint64_t>();
    if (n > r.remaining()) throw CheckpointError("wall count out of range");
    std::vector<Wall> walls(static_cast<std::size_t>(n));
    for (Wall& x : walls) {
        r.get(x.a); r.get(x.b); r.get(x.velocity); r.get(x.surface_speed);
        x.infinite = r.get<std::uint8_t>() != 0; x.rough = r.get<std::uint8_t>() != 0;
        r.get(x.mu); x.open_ends = r.get<std::uint8_t>() != 0;
    }
    return walls;
}

void put_tag(ByteWriter& w, std::string_view tag) { w.put_string(tag); }
void expect_tag(ByteReader& r, std::string_view tag) {
    const std::string t = r.get_string();
    if (t != tag) throw CheckpointError(fmt::format("section '{}' expected, found '{}'", tag, t));
}

[[noreturn]] void bad(const std::string& why) { throw CheckpointError("inconsistent contents: " + why); }

/// Offsets of a CSR index: n+1 entries, non-decreasing, starting at 0, ending at total.
void check_offsets(const std::vector<std::uint32_t>& b, std::size_t n, std::size_t total, const char* what) {
    if (b.size() != n + 1) bad(fmt::format("{} has {} offsets for {} discs", what, b.size(), n));
    if (b[0] != 0 || b[n] != total) bad(fmt::format("{} does not span its {} entries", what, total));
    for (std::size_t k = 0; k < n; ++k)
        if (b[k] > b[k + 1]) bad(fmt::format("{} decreases at {}", what, k));
}

/// A fault field by field (its struct has padding, whose bytes are not ours to write).
void put_fault(ByteWriter& w, const Fault& f) {
    w.put(f.id);
    w.put(static_cast<std::int32_t>(f.vergence));
    w.put(f.dip_deg);
    w.put(f.root.x), w.put(f.root.y), w.put(f.tip.x), w.put(f.tip.y);
    w.put(f.length), w.put(f.width), w.put(f.slip);
    w.put(f.discs);
    w.put(static_cast<std::uint8_t>(f.active));
    w.put(f.first_S), w.put(f.last_S);
}

Fault get_fault(ByteReader& r) {
    Fault f;
    r.get(f.id);
    f.vergence = r.get<std::int32_t>();
    r.get(f.dip_deg);
    r.get(f.root.x), r.get(f.root.y), r.get(f.tip.x), r.get(f.tip.y);
    r.get(f.length), r.get(f.width), r.get(f.slip);
    r.get(f.discs);
    f.active = r.get<std::uint8_t>() != 0;
    r.get(f.first_S), r.get(f.last_S);
    return f;
}

struct Header {
    CheckpointInfo info;
    std::string_view payload;
};

/// check_hash = false: the file's own integrity only (magic, version, sizes, checksums).
Header read_header(std::string_view bytes, AcceptedHashes expected_hash, bool check_hash = true) {
    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        throw CheckpointError("not an orodem checkpoint (wrong magic bytes)");
    ByteReader r(bytes.substr(sizeof kMagic));
    Header h;
    std::uint64_t size = 0, payload_sum = 0, header_sum = 0;
    try {
        r.get(h.info.version);
        if (h.info.version < kOldestCheckpointVersion || h.info.version > kCheckpointVersion)
            throw CheckpointError(fmt::format("checkpoint format version {}, this orodem ({}) reads versions {}-{}",
                                              h.info.version, ORODEM_VERSION, kOldestCheckpointVersion,
                                              kCheckpointVersion));
        h.info.program_version = r.get_string();
        r.get(h.info.config_hash);
        r.get(h.info.step);
        r.get(size);
        r.get(payload_sum);
        const std::size_t header_end = sizeof kMagic + r.offset();
        r.get(header_sum);
        if (header_sum != fnv(bytes.substr(0, header_end)))
            throw CheckpointError("header checksum mismatch (corrupt file)");
    } catch (const CheckpointError&) {
        throw;
    } catch (const IoError& e) {
        throw CheckpointError(fmt::format("truncated header ({})", e.what()));
    }
    const std::size_t start = sizeof kMagic + r.offset();
    if (bytes.size() - start != size)
        throw CheckpointError(fmt::format("payload is {} bytes, the header says {} (truncated or padded file)",
                                          bytes.size() - start, size));
    h.payload = bytes.substr(start);
    if (fnv(h.payload) != payload_sum) throw CheckpointError("payload checksum mismatch (corrupt file)");
    if (check_hash && !expected_hash.accepts(h.info.config_hash))
        throw ConfigError(fmt::format("the checkpoint was made with another config (hash {:016x}, this config "
                                      "{:016x}); resume with the run's own config.toml and the same --set values",
                                      h.info.config_hash, expected_hash.current));
    return h;
}

}  // namespace

namespace {

/// with_cache_dir: the hash of orodem before kResultNeutralKeys, which hashed packing.cache_dir.
std::uint64_t hash_without_neutral_keys(const Config& c, bool with_cache_dir) {
    Config n = c;
    // Each result-neutral key is set to one fixed value of its type (the
    // values the hash has always used), which to_toml_without_defaults then
    // leaves out where it is the default.
    for (const ResultNeutralKey& k : kResultNeutralKeys) {
        toml::table* section = n.resolved[k.section].as_table();
        if (!section || !section->contains(k.key)) continue;
        if (section->get(k.key)->is_string()) {
            if (!with_cache_dir) section->insert_or_assign(k.key, std::string());
        } else if (std::string_view(k.key) == "threads") {
            section->insert_or_assign(k.key, std::int64_t{0});
        } else {
            section->insert_or_assign(k.key, 0.0);
        }
    }
    // Defaults are left out so that a newer orodem, which adds keys with
    // their defaults, still resumes the checkpoints of an older one.
    return fnv(to_toml_without_defaults(n));
}

}  // namespace

std::uint64_t config_hash(const Config& c) { return hash_without_neutral_keys(c, false); }

AcceptedHashes accepted_config_hashes(const Config& c) {
    return {hash_without_neutral_keys(c, false), hash_without_neutral_keys(c, true)};
}

std::string encode_checkpoint(const Simulation& sim, const RunLoopState& run, std::uint64_t cfg_hash) {
    ByteWriter w;
    const ParticleStore& p = sim.particles;
    put_tag(w, "particles");
    w.put(static_cast<std::uint64_t>(p.size()));
    p.for_each_column([&](const auto& col) { w.put_vector(col); });
    w.put_vector(p.slot_of_id);
    put_tag(w, "contacts");
    const ContactStore& c = sim.contacts;
    w.put_vector(c.i); w.put_vector(c.j); w.put_vector(c.key); w.put_vector(c.xi); w.put_vector(c.shift);
    w.put_vector(c.bonded); w.put_vector(c.f); w.put_vector(c.c); w.put_vector(c.begin);
    w.put_vector(c.in_begin); w.put_vector(c.in_pair);
    put_tag(w, "wall_contacts");
    const WallContactStore& wc = sim.wall_contacts;
    w.put_vector(wc.wall); w.put_vector(wc.key); w.put_vector(wc.xi); w.put_vector(wc.f); w.put_vector(wc.c);
    w.put_vector(wc.begin);
    put_tag(w, "walls");
    put_walls(w, sim.walls);
    put_tag(w, "clock");
    w.put(sim.step_count);
    w.put(sim.time);
    put_tag(w, "internals");
    sim.save_internals(w);
    put_tag(w, "boundaries");
    w.put(static_cast<std::uint64_t>(sim.boundaries.size()));
    for (const auto& b : sim.boundaries) {
        w.put_string(b->name());
        ByteWriter own;
        b->save_state(own);
        w.put_string(own.bytes());
    }
    put_tag(w, "run");
    w.put(run.outputs);
    w.put_vector(run.x_then);
    w.put(static_cast<std::uint64_t>(run.pvd.size()));
    for (const auto& [S, file] : run.pvd) {
        w.put(S);
        w.put_string(file);
    }
    w.put(run.series_bytes);
    w.put(run.log_bytes);
    w.put(run.surface_y_mean);
    put_tag(w, "structures");
    w.put_vector(run.F_total);
    w.put(run.next_fault_id);
    w.put(run.faults_bytes);
    w.put(static_cast<std::uint64_t>(run.faults.size()));
    for (const Fault& f : run.faults) put_fault(w, f);
    w.put(run.stage);
    w.put(run.stage_last_output);
    if (sim.has_materials()) {
        // Only in runs with several materials: a one-material checkpoint keeps its bytes.
        put_tag(w, "materials");
        p.for_each_material_column([&](const auto& col) { w.put_vector(col); });
        sim.save_material_state(w);
    }
    if (run.surface.on) {
        // Only in runs with [surface]: every other checkpoint keeps its bytes.
        const SurfaceState& e = run.surface;
        put_tag(w, "surface");
        w.put(e.last_S);
        w.put_vector(e.remainder);
        w.put_vector(e.max_burial);
        w.put(e.eroded_area);
        w.put(e.requested_area);
        w.put(e.removed);
        w.put(e.eroded_bytes);
        put_tag(w, "surface_paths");
        w.put(e.reserve_begin);
        w.put_vector(e.birth_S);
        w.put_vector(e.erosion_S);
        w.put_vector(e.sed_remainder);
        w.put(e.deposited_area);
        w.put(e.deposit_requested);
        w.put(e.deposited);
        w.put(e.deposited_discs);
    }
    if (run.flexure.on) {
        // Only in runs with [flexure]: every other checkpoint keeps its bytes.
        const FlexureState& e = run.flexure;
        put_tag(w, "flexure");
        w.put(e.solved_step);
        w.put_vector(e.f);
        w.put_vector(e.w);
        w.put(e.profile_bytes);
    }
    put_tag(w, "end");

    const std::string& payload = w.bytes();
    ByteWriter h;
    h.bytes().append(kMagic, sizeof kMagic);
    h.put(kCheckpointVersion);
    h.put_string(ORODEM_VERSION);
    h.put(cfg_hash);
    h.put(sim.step_count);
    h.put(static_cast<std::uint64_t>(payload.size()));
    h.put(fnv(payload));
    h.put(fnv(h.bytes()));
    std::string out = std::move(h.bytes());
    out += payload;
    return out;
}

bool checkpoint_file_intact(const std::string& path) {
    try {
        read_header(read_file(path), 0, false);
        return true;
    } catch (const IoError&) {  // CheckpointError included
        return false;
    }
}

CheckpointInfo verify_checkpoint(std::string_view bytes, AcceptedHashes expected_config_hash) {
    return read_header(bytes, expected_config_hash).info;
}

void decode_checkpoint(std::string_view bytes, AcceptedHashes expected_config_hash, Simulation& sim,
                       RunLoopState& run_out) {
    const Header h = read_header(bytes, expected_config_hash);
    ByteReader r(h.payload);
    ParticleStore p;
    ContactStore c;
    WallContactStore wc;
    std::vector<Wall> walls;
    std::uint64_t step = 0;
    double time = 0.0;
    Simulation::Internals internals;
    Simulation::MaterialState materials;
    std::vector<std::string> boundary_state;
    RunLoopState run;
    try {
        expect_tag(r, "particles");
        const auto n64 = r.get<std::uint64_t>();
        if (n64 > h.payload.size()) bad("particle count out of range");
        const std::size_t n = static_cast<std::size_t>(n64);
        p.for_each_column([&](auto& col) {
            r.get_vector(col);
            if (col.size() != n) bad(fmt::format("a particle column has {} entries for {} discs", col.size(), n));
        });
        r.get_vector(p.slot_of_id);
        if (p.slot_of_id.size() != n) bad("slot_of_id size");
        for (std::size_t s = 0; s < n; ++s)
            if (p.id[s] >= n || p.slot_of_id[p.id[s]] != s) bad(fmt::format("slot_of_id does not invert id at slot {}", s));

        expect_tag(r, "contacts");
        r.get_vector(c.i); r.get_vector(c.j); r.get_vector(c.key); r.get_vector(c.xi); r.get_vector(c.shift);
        r.get_vector(c.bonded); r.get_vector(c.f); r.get_vector(c.c); r.get_vector(c.begin);
        r.get_vector(c.in_begin); r.get_vector(c.in_pair);
        const std::size_t m = c.i.size();
        if (c.j.size() != m || c.key.size() != m || c.xi.size() != m || c.shift.size() != m ||
            c.bonded.size() != m || c.f.size() != m || c.c.size() != m || c.in_pair.size() != m)
            bad("contact arrays differ in length");
        check_offsets(c.begin, n, m, "contacts.begin");
        check_offsets(c.in_begin, n, m, "contacts.in_begin");
        for (std::size_t k = 0; k < m; ++k)
            if (c.i[k] >= n || c.j[k] >= n || c.in_pair[k] >= m) bad(fmt::format("contact {} indexes out of range", k));
        // Cluster ids: -1 (a lone disc) or below n, and as many pairs inside clusters
        // as bonded contacts (the pair list holds every bond), which bounds the
        // bond topology built from them on restore. Found by tests/fuzz/fuzz_checkpoint.
        std::vector<std::uint64_t> members(n, 0);
        for (std::size_t s = 0; s < n; ++s) {
            const std::int32_t cl = p.cluster[s];
            if (cl < -1 || (cl >= 0 && static_cast<std::size_t>(cl) >= n))
                bad(fmt::format("cluster id {} at slot {} (of {} discs)", cl, s, n));
            if (cl >= 0) ++members[static_cast<std::size_t>(cl)];
        }
        std::uint64_t bond_pairs = 0;  // n <= 2^32 (ids are u32), so no overflow
        for (const std::uint64_t k : members)
            if (k > 1) bond_pairs += k * (k - 1) / 2;
        const auto bonded = static_cast<std::uint64_t>(
            std::count_if(c.bonded.begin(), c.bonded.end(), [](std::uint8_t b) { return b != 0; }));
        if (bond_pairs != bonded) bad(fmt::format("{} bonds in the clusters, {} bonded contacts", bond_pairs, bonded));

        expect_tag(r, "wall_contacts");
        r.get_vector(wc.wall); r.get_vector(wc.key); r.get_vector(wc.xi); r.get_vector(wc.f); r.get_vector(wc.c);
        r.get_vector(wc.begin);
        const std::size_t q = wc.wall.size();
        if (wc.key.size() != q || wc.xi.size() != q || wc.f.size() != q || wc.c.size() != q)
            bad("wall contact arrays differ in length");
        check_offsets(wc.begin, n, q, "wall_contacts.begin");

        expect_tag(r, "walls");
        walls = get_walls(r);
        if (walls.size() != sim.walls.size())
            bad(fmt::format("{} walls saved, the experiment has {}", walls.size(), sim.walls.size()));
        for (std::size_t k = 0; k < q; ++k)
            if (wc.wall[k] >= walls.size()) bad(fmt::format("wall contact {} names wall {}", k, wc.wall[k]));

        expect_tag(r, "clock");
        r.get(step);
        r.get(time);
        if (step != h.info.step) bad("step differs from the header's");

        expect_tag(r, "internals");
        internals = Simulation::read_internals(r);
        if (internals.x_ref.size() != n) bad("x_ref size");
        if (internals.wall_shift.size() != walls.size()) bad("wall_shift size");

        expect_tag(r, "boundaries");
        const auto nb = r.get<std::uint64_t>();
        if (nb != sim.boundaries.size())
            bad(fmt::format("{} boundaries saved, the experiment has {}", nb, sim.boundaries.size()));
        for (std::size_t k = 0; k < nb; ++k) {
            const std::string name = r.get_string();
            if (name != sim.boundaries[k]->name())
                bad(fmt::format("boundary {} is '{}', the experiment's is '{}'", k, name, sim.boundaries[k]->name()));
            boundary_state.push_back(r.get_string());
        }

        expect_tag(r, "run");
        r.get(run.outputs);
        r.get_vector(run.x_then);
        if (!run.x_then.empty() && run.x_then.size() != n) bad("x_then size");
        const auto npvd = r.get<std::uint64_t>();
        if (npvd > h.payload.size()) bad("pvd count out of range");
        for (std::uint64_t k = 0; k < npvd; ++k) {
            const double S = r.get<double>();
            run.pvd.emplace_back(S, r.get_string());
        }
        r.get(run.series_bytes);
        r.get(run.log_bytes);
        r.get(run.surface_y_mean);
        if (h.info.version >= 3) {
            expect_tag(r, "structures");
            r.get_vector(run.F_total);
            if (!run.F_total.empty() && run.F_total.size() != n) bad("F_total size");
            r.get(run.next_fault_id);
            r.get(run.faults_bytes);
            const auto nf = r.get<std::uint64_t>();
            if (nf > h.payload.size()) bad("fault count out of range");
            for (std::uint64_t k = 0; k < nf; ++k) run.faults.push_back(get_fault(r));
            if (h.info.version >= 4) {
                r.get(run.stage);
                r.get(run.stage_last_output);
            }
        }
        std::string tag = r.get_string();
        if (tag == "materials") {
            if (!sim.has_materials()) bad("a checkpoint of a run with several materials, for a run with one");
            p.for_each_material_column([&](auto& col) {
                r.get_vector(col);
                if (col.size() != n) bad(fmt::format("a material column has {} entries for {} discs", col.size(), n));
            });
            for (std::size_t s = 0; s < n; ++s)
                if (p.material[s] >= sim.materials.materials.size()) bad(fmt::format("material id {} at slot {}", p.material[s], s));
            materials = Simulation::read_material_state(r);
            if (materials.slip.size() != c.size() || materials.broke.size() != c.size())
                bad("material pair columns differ in length from the pairs");
            tag = r.get_string();
        } else if (sim.has_materials()) {
            bad("a checkpoint of a run with one material, for a run with several");
        }
        if (tag == "surface") {
            SurfaceState& e = run.surface;
            e.on = true;
            r.get(e.last_S);
            r.get_vector(e.remainder);
            r.get_vector(e.max_burial);
            if (e.max_burial.size() != n) bad("surface max_burial size");
            r.get(e.eroded_area);
            r.get(e.requested_area);
            r.get(e.removed);
            r.get(e.eroded_bytes);
            tag = r.get_string();
            if (tag == "surface_paths") {
                r.get(e.reserve_begin);
                r.get_vector(e.birth_S);
                r.get_vector(e.erosion_S);
                if (e.reserve_begin > n || e.birth_S.size() != n || e.erosion_S.size() != n) bad("surface_paths sizes");
                r.get_vector(e.sed_remainder);
                r.get(e.deposited_area);
                r.get(e.deposit_requested);
                r.get(e.deposited);
                r.get(e.deposited_discs);
                tag = r.get_string();
            } else {
                // Written before the paths: the layer only, birth at S = 0, erosion S unknown.
                e.reserve_begin = n;
                e.birth_S.assign(n, 0.0);
                e.erosion_S.assign(n, std::numeric_limits<double>::quiet_NaN());
            }
        }
        if (tag == "flexure") {
            FlexureState& e = run.flexure;
            e.on = true;
            r.get(e.solved_step);
            r.get_vector(e.f);
            r.get_vector(e.w);
            if (e.f.size() != e.w.size()) bad("flexure load and deflection differ in length");
            r.get(e.profile_bytes);
            tag = r.get_string();
        }
        if (tag != "end") throw CheckpointError(fmt::format("section 'end' expected, found '{}'", tag));
        if (r.remaining() != 0) bad(fmt::format("{} bytes left over", r.remaining()));
        if (!(internals.awake_begin <= internals.awake_end && internals.awake_end <= p.size() &&
              internals.pairs_begin <= internals.pairs_end && internals.pairs_end <= c.size() &&
              internals.last_rebuild_step <= step))
            bad("sleeping-zone ranges out of bounds");
    } catch (const CheckpointError&) {
        throw;
    } catch (const IoError& e) {
        throw CheckpointError(e.what());
    }

    // Boundaries first (they can still fail on a short blob): keep their old
    // state to put back, so a refusal leaves sim unchanged.
    std::vector<std::string> old_state;
    for (const auto& b : sim.boundaries) {
        ByteWriter w;
        b->save_state(w);
        old_state.push_back(std::move(w.bytes()));
    }
    std::size_t done = 0;
    try {
        for (; done < sim.boundaries.size(); ++done) {
            ByteReader br(boundary_state[done]);
            sim.boundaries[done]->load_state(br);
            if (br.remaining() != 0) bad(fmt::format("boundary '{}' left {} bytes unread", sim.boundaries[done]->name(), br.remaining()));
        }
    } catch (const std::exception& e) {
        for (std::size_t k = 0; k <= std::min(done, sim.boundaries.size() - 1); ++k) {
            ByteReader br(old_state[k]);
            sim.boundaries[k]->load_state(br);
        }
        throw CheckpointError(e.what());
    }

    sim.particles = std::move(p);
    sim.contacts = std::move(c);
    sim.wall_contacts = std::move(wc);
    sim.walls = std::move(walls);
    sim.step_count = step;
    sim.time = time;
    sim.restore_internals(std::move(internals));
    if (sim.has_materials()) sim.restore_material_state(std::move(materials));
    run_out = std::move(run);
}

std::vector<std::pair<std::uint64_t, std::string>> list_checkpoints(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<std::pair<std::uint64_t, std::string>> out;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        if (name.size() <= 9 || name.rfind("ckpt-", 0) != 0 || name.substr(name.size() - 4) != ".bin") continue;
        std::uint64_t step = 0;
        const char* first = name.data() + 5;
        const char* last = name.data() + name.size() - 4;
        const auto [ptr, err] = std::from_chars(first, last, step);
        if (err != std::errc{} || ptr != last) continue;
        out.emplace_back(step, e.path().string());
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    return out;
}

std::string write_checkpoint(const std::string& dir, std::uint64_t step, std::string_view bytes, int keep) {
    make_dirs(dir);
    const std::string path = fmt::format("{}/ckpt-{:012d}.bin", dir, step);
    write_file_atomic(path, bytes);
    // Read back: a checkpoint is only counted once it is on disk as written.
    if (read_file(path) != bytes)
        throw IoError(fmt::format("{}: the checkpoint read back differs from what was written (disk or file system "
                                  "fault); the older checkpoints are kept",
                                  path));
    // Keep the `keep` newest checkpoints that are intact; older ones go. A
    // damaged file (truncated, altered after it was written) is not counted,
    // so it can never be the reason a good older one is deleted.
    if (keep <= 0) return path;
    int intact = 0;
    for (const auto& [s, file] : list_checkpoints(dir)) {
        if (intact >= keep) {
            std::error_code ec;
            std::filesystem::remove(file, ec);  // a leftover old checkpoint is harmless
        } else if (checkpoint_file_intact(file)) {
            ++intact;
        }
    }
    return path;
}

std::string restore_newest_checkpoint(const std::string& dir, AcceptedHashes expected_config_hash, Simulation& sim,
                                      RunLoopState& run, std::vector<std::string>* notes,
                                      const std::function<std::string(const RunLoopState&)>& fits) {
    const auto all = list_checkpoints(dir);
    std::string reasons;
    for (const auto& [step, path] : all) {
        try {
            const std::string bytes = read_file(path);
            decode_checkpoint(bytes, expected_config_hash, sim, run);
            if (const std::string misfit = fits ? fits(run) : std::string(); !misfit.empty()) throw IoError(misfit);
            return path;
        } catch (const ConfigError& e) {
            throw ConfigError(fmt::format("{}: {}", path, e.what()));
        } catch (const IoError& e) {
            const std::string line = fmt::format("{}: not used: {}", path, e.what());
            if (notes) notes->push_back(line);
            reasons += "; " + line;
        }
    }
    if (all.empty()) throw CheckpointError(fmt::format("no checkpoint (ckpt-<step>.bin) in {}", dir));
    throw CheckpointError(fmt::format("no usable checkpoint in {}{}", dir, reasons));
}

}  // namespace orodem
