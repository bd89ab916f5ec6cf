#pragma once
// Private to the io module: the `shape` key of the rigid bodies (planar and spatial), read into a
// model::BodyShape (model/body_shape.hpp) by types/body_shape.cpp.
#include "common.hpp"

namespace alphaflex::scene_detail {

/// The `shape` key of a body type's schema.
Key shape_key();
/// The schema of a `shape` map (docs table `bodies.shape`).
const Schema& shape_schema();
/// Reads the item's `shape`, if given, and adds it to the model as the shape of `node`.
void read_body_shape(const Item& it, int node);

}  // namespace alphaflex::scene_detail
