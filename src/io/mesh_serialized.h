#pragma once
// Mitsuba's `serialized` mesh format: one or more zlib-compressed triangle meshes in a file, an
// offset table at its end. Each mesh: u16 0x041C, u16 version (3 or 4), then a zlib stream of
// u32 flags, (version 4) a NUL-terminated name, u64 vertex and triangle counts, positions,
// optional normals, texture coordinates and colours (float or double), and the indices (u32,
// u64 when there are more than 2^32 vertices). Little endian throughout.
#include <string>

#include "core/mesh_data.h"

namespace snell {

/// Serialized-file flags (Mitsuba's names).
namespace serialized {
constexpr uint32_t kVertexNormals = 0x0001, kTexcoords = 0x0002, kVertexColors = 0x0008, kFaceNormals = 0x0010,
                   kSinglePrecision = 0x1000, kDoublePrecision = 0x2000;
}

/// The mesh at `shape_index` (0-based) of a serialized file; `face_normals` is set when the file
/// asks for face normals. Throws std::runtime_error naming `path` and the problem.
MeshData load_serialized(const std::string& path, int64_t shape_index, bool* face_normals = nullptr);

}  // namespace snell
