// Layered wedges: the material table of a config with [materials.NAME] and
// [[layers]], and the assignment of each particle of the cut layer to its
// layer and material (docs/physics.md "Materials, layers and weakening").
#pragma once

#include "orodem/io/config.hpp"
#include "orodem/physics/materials.hpp"
#include "orodem/state/particles.hpp"

namespace orodem {

/// The materials of c.materials (ids in their order) and the law of every
/// pair of them (mix_materials, or c.friction_pairs where named). Healing
/// per unit S becomes a rate per second at the belt speed: healing v / h0.
MaterialTable material_table(const Config& c);

/// Gives each particle of the layer its layer and material: a particle (a
/// cluster's discs together, by their mean height) belongs to the layer of
/// c.layers (proside, x ≤ 0 by the mean x) or c.retro_layers (x > 0) whose
/// band of heights above the base holds it, the bands stacked from the base
/// in h0, everything above the top band in the top layer. Sets the masses
/// from each material's density (inverse masses of free discs as
/// set_free_inertia without a floor) and zero damage. Layer ids: from 0 at
/// the base on each side (its stack's index; `side` tells the two apart).
/// `unit`: the thickness unit of the layers [m]; 0 = packing.h0 (the
/// basal-friction block's layers are fractions of calibrate.block_height).
void assign_layers(const Config& c, ParticleStore& p, double unit = 0.0);

/// The id of material `name` in c.materials (its index; the loader refuses
/// unknown names).
std::uint8_t material_id(const Config& c, const std::string& name);

/// Every particle of p in material `name` of c.materials (layer 0): the
/// biaxial test of calibrate.material. Masses as assign_layers.
void assign_material(const Config& c, ParticleStore& p, const std::string& name);

/// The table with every law's damping replaced by the damping ratio ζ
/// (with_damping_ratio): the biaxial compaction's.
MaterialTable with_damping_ratio(MaterialTable t, double zeta);

}  // namespace orodem
