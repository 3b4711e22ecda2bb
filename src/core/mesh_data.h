#pragma once
// Plain triangle-mesh arrays, as produced by the OBJ/PLY readers and the shape builders and
// consumed by TriangleMesh. Kept separate from TriangleMesh so the readers need no Embree, and
// in core/ because both io/ (the readers) and geometry/ (the builders, TriangleMesh) use it.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/transform.h"
#include "core/vector.h"

namespace snell {

/// A named per-vertex or per-face value of 1 or 3 channels (Mitsuba's mesh attributes, read
/// from PLY files: "vertex_color", "face_weight", ...).
struct MeshAttribute {
    std::string name;  ///< with its "vertex_" or "face_" prefix, as Mitsuba names it
    bool per_face = false;
    int channels = 1;           ///< 1 or 3
    std::vector<float> values;  ///< channels per vertex, or per triangle
};

/// Indexed triangle list. `normals` and `uvs` are either empty or one per position.
/// Winding: counter-clockwise seen from the outside (the side the face normal points to).
struct MeshData {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  ///< per-vertex shading normals (need not be unit length)
    std::vector<Vec2> uvs;      ///< per-vertex texture coordinates
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<MeshAttribute> attributes;  ///< per-face ones have one entry per triangle
};

/// Applies `xf` to positions (point) and normals (inverse transpose). A transform that flips
/// handedness (det < 0) also reverses the winding, so that the winding-derived face normal
/// stays on the side it was on before (pbrt and Mitsuba keep orientation the same way).
void transform_mesh(MeshData& mesh, const Transform& xf);

/// Checks index ranges, attribute counts and finiteness; throws std::runtime_error
/// "<what>: <problem>" (what = file name or builder name).
void validate_mesh(const MeshData& mesh, const std::string& what);

}  // namespace snell
