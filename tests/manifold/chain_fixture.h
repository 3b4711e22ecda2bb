#pragma once
// Small chains on analytic shapes for the manifold tests (no Embree scene needed: the walk
// projects with Shape::closest_point).
#include <cmath>
#include <vector>

#include "geometry/builders.h"
#include "geometry/mesh.h"
#include "geometry/sphere.h"
#include "manifold/constraints.h"
#include "manifold/manifold_vertex.h"

namespace snell::test {

inline ManifoldVertex vertex_on(const Shape& shape, const Vec3& near, double eta, const Vec2& h_target = Vec2()) {
    SurfaceInteraction si;
    const bool ok = shape.closest_point(near, kInfinity, &si);
    EXPECT_TRUE(ok);
    ManifoldVertex v = ManifoldVertex::from_interaction(si, eta);
    v.h_target = h_target;
    return v;
}

/// Tangent basis of a fixed endpoint lying in a plane with normal n.
inline TangentBasis endpoint(const Vec3& p, const Vec3& n) {
    const Frame f = Frame::from_normal(normalize(n));
    return {p, f.s, f.t};
}

/// A tessellated unit sphere (UV sphere) with exact vertex normals: smooth shading, so dn/du
/// comes from the interpolated normals.
inline MeshData uv_sphere_mesh(const Vec3& c, double r, int nu = 48, int nv = 24) {
    MeshData m;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const double th = kPi * j / nv, ph = 2 * kPi * i / nu;
            const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            m.positions.push_back(c + n * r);
            m.normals.push_back(n);
        }
    const auto idx = [&](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            // Counter-clockwise seen from outside.
            if (j > 0) m.triangles.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j)});
            if (j + 1 < nv) m.triangles.push_back({idx(i + 1, j), idx(i, j + 1), idx(i + 1, j + 1)});
        }
    return m;
}

}  // namespace snell::test
