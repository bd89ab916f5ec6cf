#pragma once
// Private to src/io/types: the full mesh of a reduced beam block (model/mesh_reconstruction.hpp)
// built from the reduction (types/reduced_beams_3d.cpp), and the sensors that read it — points
// inside the block and the section forces of its elements (types/point_sensors_3d.cpp,
// types/element_output_3d.cpp).
#include <map>
#include <memory>

#include "alphaflex/modal/superelement.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {

/// The mesh of a block reduced on `scratch` (its elements `elements`, its nodes the scratch nodes
/// 0 … n−1 in the order of `rb`'s points; `in_block` mesh node → scratch node, for the names of
/// its named points). `whole`: results recovered as S(ξ), not the odd part (a basis with modal
/// derivatives; MeshReconstruction::Recovery).
std::shared_ptr<const MeshReconstruction> reduced_block_mesh(const Item& it, const Model& scratch, const std::vector<int>& elements,
                                                             const ReducedBlock& rb, const std::map<int, int>& in_block, bool whole = false);

/// A point sensor whose `body` names a point inside a reduced block: an element output of the
/// block's reduced body (its point's position or displacement). False if `body` names no such
/// point; fails with a clear message for what cannot be read there (velocities, accelerations,
/// an offset `point`, `relative_to`).
bool read_reduced_point_sensor(const Item& it, Sensor& sn);

/// A `beam_output` sensor of an element of a reduced block: the section force or strain recovered
/// from the modes. False if `beam` names no reduced block.
bool read_reduced_element_output(const Item& it, Sensor& sn, const std::string& block, int element);

}  // namespace alphaflex::scene_detail
