#pragma once
// The shape factory sits in loader/, not geometry/: it attaches a BSDF (bsdf/) and skips nested
// emitters (light/), both of which are above geometry in the layer order (scripts/check-layers.sh).
#include <memory>

#include "core/props.h"
#include "geometry/shape.h"

namespace snell {

/// Builds a shape from its `type` (sphere, rectangle, disk, cube, obj, ply). Reads
/// `to_world`, `flip_normals`, `face_normals` (meshes), the file name (resolved relative to
/// the scene file's folder, passed as the string parameter "__base_dir" by the loader), and a
/// nested/referenced BSDF child (default: diffuse 0.5 as in Mitsuba). Emitters are attached by
/// the loader. Unknown types/parameters: SceneError with file:line; missing mesh: names path.
std::shared_ptr<Shape> create_shape(const Props& props);

}  // namespace snell
