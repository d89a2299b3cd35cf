// ParaView output: one VTK UnstructuredGrid (.vtu) per snapshot, one vertex
// cell per disc, with the point data of SPEC §4 (id, radius, velocity,
// initial_depth, side, cluster_id, rel_disp, plus omega and fixed; the
// strain arrays and rel_disp_abs in a run's snapshots), field data S, step
// and time (VtuStamp), and a run.pvd collection carrying S as
// the time value. Data are raw binary
// appended (little-endian, UInt64 headers); files are written atomically.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "orodem/analysis/strain.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// When the snapshot was taken; written as the file's field data (one value
/// each: S [-], step [-], time [s]) so that a snapshot describes itself.
struct VtuStamp {
    double S = 0.0;          // normalised convergence S = v' t / h0 [-]
    std::uint64_t step = 0;  // timestep count
    double time = 0.0;       // simulated time [s]
};

/// A point array given by particle id, written after the others: the
/// particles' paths of a run with [surface] (birth_S, max_burial_depth,
/// erosion_S), absent from every other run's snapshots.
struct VtuByIdArray {
    std::string name;
    const std::vector<double>* values = nullptr;  // by id, the store's size
};

/// rel_disp: per slot (may be empty: written as zeros). stamp: S, step and
/// time as field data (none when null). strain: by particle id, written as
/// shear_strain, vol_strain, rotation and d2min (none when null).
/// rel_disp_abs: per slot, the relative displacement before normalisation
/// [m], written as rel_disp_abs after the others (none when null). by_id:
/// arrays written last, in their order (none when null or empty).
void write_vtu(const std::string& path, const ParticleStore& p, const std::vector<double>& rel_disp,
               const VtuStamp* stamp = nullptr, const StrainField* strain = nullptr,
               const std::vector<double>* rel_disp_abs = nullptr, const std::vector<VtuByIdArray>* by_id = nullptr);

/// run.pvd listing (S, file name relative to the pvd) pairs.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries);

/// Reads back the point data of a VTU written by write_vtu (for tests and
/// `orodem render`): positions and the named scalar arrays, in file order.
struct VtuData {
    std::vector<Vec2> x;
    std::vector<std::pair<std::string, std::vector<double>>> arrays;  // name -> per point (first component)
    const std::vector<double>* find(const std::string& name) const;
    /// The array `name`; IoError "'path': snapshot has no 'name' array" when absent.
    const std::vector<double>& require(const std::string& name, const std::string& path) const;
};
VtuData read_vtu(const std::string& path);
/// The positions of a read snapshot by disc id, from its `id` array (NaN for
/// an id it lacks), and, if `radius` is given, its radii likewise; `path`
/// names the file in errors.
std::vector<Vec2> positions_by_id(const VtuData& d, const std::string& path, std::vector<double>* radius = nullptr);

/// One snapshot listed in a run.pvd.
struct Snapshot {
    double S;
    std::string file;  // relative to the run directory
};
/// The (S, file) entries of run.pvd, one per file (the last S of a repeated
/// file); IoError when it lists none or cannot be read.
std::vector<Snapshot> read_pvd(const std::string& path);

}  // namespace orodem
