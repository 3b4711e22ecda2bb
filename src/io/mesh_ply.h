#pragma once
#include <string>

#include "core/mesh_data.h"

namespace snell {

/// Loads a PLY file (ascii, binary_little_endian, binary_big_endian). Reads vertex
/// x y z, optional nx ny nz and texture coordinates (u v, s t, texture_u texture_v or
/// texture_s texture_t), and the face list `vertex_indices` (or `vertex_index`) with any
/// integer count/index types; polygons are triangulated as fans. Other elements and
/// properties are skipped. Throws std::runtime_error naming `path` and the problem.
MeshData load_ply(const std::string& path);

}  // namespace snell
