#pragma once
// Mitsuba's built-in mesh shapes, as MeshData in world space (already transformed).
#include "core/mesh_data.h"
#include "core/transform.h"

namespace snell {

/// `rectangle`: [-1,1]^2 in the z = 0 plane, normal +z, uv = ((x+1)/2, (y+1)/2); two triangles.
MeshData make_rectangle(const Transform& to_world = Transform());

/// `disk`: unit disk in z = 0, normal +z, as a fan of `segments` triangles (uv as for the
/// rectangle). 256 segments keep the rim within 1 - cos(pi/256) = 7.5e-5 of the circle;
/// area() is the polygon's, so emission and sampling stay mutually consistent.
MeshData make_disk(const Transform& to_world = Transform(), int segments = 256);

/// `cube`: [-1,1]^3, 24 vertices (4 per face, so faces are flat), 12 triangles, outward
/// normals, per-face uvs in [0,1]^2.
MeshData make_cube(const Transform& to_world = Transform());

}  // namespace snell
