#pragma once
#include <string>

#include "core/mesh_data.h"

namespace snell {

/// Loads a Wavefront OBJ file (all objects/groups merged) with tinyobjloader: positions,
/// normals and texture coordinates, polygons triangulated. OBJ indexes each attribute
/// separately; vertices are de-duplicated on the (position, normal, uv) index triple.
/// Normals/uvs are kept only if every face corner has them. Throws std::runtime_error
/// naming `path` when the file is missing or malformed.
MeshData load_obj(const std::string& path);

}  // namespace snell
