#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/warp.h"
#include "geometry/builders.h"
#include "geometry/mesh.h"
#include "scene/scene.h"
#include "test_geometry_util.h"

using namespace snell;
using snell::test::next_2d;

namespace {

/// Barycentrics (b1, b2) of the point with texture coordinates `uv` in triangle `prim`.
Vec2 bary_from_uv(const MeshData& m, uint32_t prim, const Vec2& uv) {
    const auto& t = m.triangles[prim];
    const Vec2 t0 = m.uvs[t[0]], d1 = m.uvs[t[1]] - t0, d2 = m.uvs[t[2]] - t0, r = uv - t0;
    const double det = d1.x * d2.y - d1.y * d2.x;
    return {(r.x * d2.y - r.y * d2.x) / det, (d1.x * r.y - d1.y * r.x) / det};
}

/// Checks the derivatives at uv (or at barycentrics when `use_uv` is false) against central
/// differences of the mesh's own p and n. Truncation is ~h^2 |n'''| (p is linear: exact up
/// to rounding); rounding ~1e-16 / h.
void check_fd(const TriangleMesh& mesh, const MeshData& data, uint32_t prim, const Vec2& x, bool use_uv, double tol) {
    auto eval = [&](const Vec2& q) {
        SurfaceInteraction si;
        mesh.interaction_at(prim, use_uv ? bary_from_uv(data, prim, q) : q, &si);
        return si;
    };
    const double h = 1e-6;
    const SurfaceInteraction si = eval(x);
    const SurfaceInteraction up = eval(x + Vec2(h, 0)), um = eval(x - Vec2(h, 0));
    const SurfaceInteraction vp = eval(x + Vec2(0, h)), vm = eval(x - Vec2(0, h));
    const double sp = std::max(length(si.dpdu), length(si.dpdv));
    EXPECT_LT(length((up.p - um.p) / (2 * h) - si.dpdu), tol * sp);
    EXPECT_LT(length((vp.p - vm.p) / (2 * h) - si.dpdv), tol * sp);
    const double sn = std::max({length(si.dndu), length(si.dndv), 1.0});
    EXPECT_LT(length((up.n - um.n) / (2 * h) - si.dndu), tol * sn);
    EXPECT_LT(length((vp.n - vm.n) / (2 * h) - si.dndv), tol * sn);
    EXPECT_NEAR(si.uv.x, x.x, 1e-12);
    EXPECT_NEAR(si.uv.y, x.y, 1e-12);
    EXPECT_NEAR(length(si.n), 1.0, 1e-13);
    EXPECT_NEAR(length(si.ng), 1.0, 1e-13);
    EXPECT_GT(dot(si.n, si.ng), 0);
    EXPECT_NEAR(dot(si.ng, si.dpdu), 0.0, 1e-12 * sp);
    EXPECT_NEAR(dot(si.ng, si.dpdv), 0.0, 1e-12 * sp);
    EXPECT_NEAR(dot(si.n, si.dndu), 0.0, 1e-12 * sn);  // derivative of a unit vector
    EXPECT_NEAR(dot(si.n, si.dndv), 0.0, 1e-12 * sn);
}

MeshData skewed_triangle(bool with_uv) {
    MeshData m;
    m.positions = {{0.1, 0.2, 0.0}, {1.3, -0.1, 0.2}, {0.4, 1.1, -0.3}};
    m.normals = {normalize(Vec3(0.1, 0.2, 1)), normalize(Vec3(-0.4, 0.1, 1)), normalize(Vec3(0.3, -0.5, 0.8))};
    if (with_uv) m.uvs = {{0.2, 0.1}, {0.9, 0.3}, {0.35, 0.8}};
    m.triangles = {{0, 1, 2}};
    return m;
}

}  // namespace

TEST(GeometryMesh, SingleTriangleDifferentialGeometry) {
    for (bool flip : {false, true}) {
        // Texture parametrisation.
        MeshData d = skewed_triangle(true);
        TriangleMesh m(d, false, flip);
        for (Vec2 uv : {Vec2(0.4, 0.3), Vec2(0.5, 0.4), Vec2(0.35, 0.6)}) check_fd(m, d, 0, uv, true, 1e-7);
        // Barycentric parametrisation (no uvs).
        MeshData d2 = skewed_triangle(false);
        TriangleMesh m2(d2, false, flip);
        for (Vec2 b : {Vec2(0.2, 0.3), Vec2(0.6, 0.1), Vec2(0.25, 0.5)}) check_fd(m2, d2, 0, b, false, 1e-7);
    }
    // The blended normal really varies, so dn/du is non-trivial, and flips with flip_normals.
    MeshData d = skewed_triangle(true);
    TriangleMesh a(d, false, false), b(d, false, true);
    SurfaceInteraction sa, sb;
    a.interaction_at(0, {0.3, 0.3}, &sa);
    b.interaction_at(0, {0.3, 0.3}, &sb);
    EXPECT_GT(length(sa.dndu), 0.1);
    EXPECT_NEAR(length(sa.dndu + sb.dndu), 0.0, 1e-15);
    EXPECT_NEAR(length(sa.n + sb.n), 0.0, 1e-15);
    EXPECT_NEAR(length(sa.ng + sb.ng), 0.0, 1e-15);
    EXPECT_NEAR(length(sa.dpdu - sb.dpdu), 0.0, 1e-15);
}

TEST(GeometryMesh, DegenerateUvFallsBackToBarycentrics) {
    MeshData d = skewed_triangle(true);
    d.uvs = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}};
    TriangleMesh m(d);
    check_fd(m, d, 0, {0.3, 0.2}, false, 1e-7);
}

TEST(GeometryMesh, FaceNormalsAreFlat) {
    MeshData d = skewed_triangle(true);
    TriangleMesh m(d, /*face_normals=*/true);
    SurfaceInteraction si;
    m.interaction_at(0, {0.3, 0.3}, &si);
    EXPECT_EQ(si.n, si.ng);
    EXPECT_EQ(length(si.dndu), 0.0);
    EXPECT_EQ(length(si.dndv), 0.0);
    // Winding decides the side: (p1 - p0) x (p2 - p0) has positive z here.
    EXPECT_GT(si.ng.z, 0);
}

TEST(GeometryMesh, TessellatedSphereDifferentialGeometry) {
    const MeshData d = test::make_uv_sphere({0.2, -0.1, 0.3}, 1.5, 24, 12);
    TriangleMesh m(d);
    PCG32 rng(2, 3);
    for (int k = 0; k < 200; ++k) {
        const uint32_t prim = uint32_t(rng.next_u32() % m.triangle_count());
        // Interior point away from the edges so the +-h stencil stays in the triangle.
        Vec2 b = warp::square_to_uniform_triangle(next_2d(rng));
        b = Vec2(0.1, 0.1) + b * 0.7;
        const auto& t = d.triangles[prim];
        const Vec2 uv = d.uvs[t[0]] * (1 - b.x - b.y) + d.uvs[t[1]] * b.x + d.uvs[t[2]] * b.y;
        check_fd(m, d, prim, uv, true, 1e-6);
        SurfaceInteraction si;
        m.interaction_at(prim, b, &si);
        EXPECT_GT(dot(si.ng, si.p - Vec3(0.2, -0.1, 0.3)), 0);  // outward winding
    }
}

TEST(GeometryMesh, ClosestPointOnTriangleIsMinimal) {
    PCG32 rng(4, 4);
    for (int k = 0; k < 300; ++k) {
        auto rp = [&] { return Vec3(rng.next_double(), rng.next_double(), rng.next_double()) * 2 - Vec3(1); };
        const Vec3 a = rp(), b = rp(), c = rp(), p = rp() * 1.5;
        const Vec2 bc = closest_point_on_triangle(p, a, b, c);
        ASSERT_GE(bc.x, -1e-15);
        ASSERT_GE(bc.y, -1e-15);
        ASSERT_LE(bc.x + bc.y, 1 + 1e-15);
        const double d = length(a + (b - a) * bc.x + (c - a) * bc.y - p);
        // No point of a dense random sample of the triangle is closer.
        for (int i = 0; i < 400; ++i) {
            const Vec2 w = warp::square_to_uniform_triangle(next_2d(rng));
            const Vec3 q = a * w.x + b * w.y + c * (1 - w.x - w.y);
            ASSERT_GE(length(q - p), d - 1e-12);
        }
        // Nor on the edges.
        for (int i = 0; i <= 100; ++i) {
            const double s = i / 100.0;
            ASSERT_GE(length(a + (b - a) * s - p), d - 1e-12);
            ASSERT_GE(length(b + (c - b) * s - p), d - 1e-12);
            ASSERT_GE(length(c + (a - c) * s - p), d - 1e-12);
        }
    }
}

TEST(GeometryMesh, ClosestPointMatchesBruteForceAndIntersection) {
    const MeshData d = test::make_uv_sphere({0, 0, 0}, 1.0, 32, 16);
    auto m = std::make_shared<TriangleMesh>(d);
    Scene scene;
    scene.add_shape(m);
    scene.add_shape(std::make_shared<TriangleMesh>(make_cube(Transform::translate({3, 0, 0}))));
    scene.build();  // builds the mesh's private point-query BVH
    PCG32 rng(8, 1);
    for (int k = 0; k < 500; ++k) {
        const Vec3 p = Vec3(rng.next_double(), rng.next_double(), rng.next_double()) * 4 - Vec3(2);
        double best = kInfinity;
        for (uint32_t i = 0; i < m->triangle_count(); ++i) {
            const auto& t = m->triangle(i);
            const Vec3 a = m->vertex(t[0]), b = m->vertex(t[1]), c = m->vertex(t[2]);
            const Vec2 bc = closest_point_on_triangle(p, a, b, c);
            best = std::min(best, length(a + (b - a) * bc.x + (c - a) * bc.y - p));
        }
        SurfaceInteraction si;
        ASSERT_TRUE(m->closest_point(p, kInfinity, &si));
        EXPECT_NEAR(length(si.p - p), best, 1e-12);
        EXPECT_EQ(si.shape, m.get());
        // Radius cut-off.
        EXPECT_TRUE(m->closest_point(p, best * (1 + 1e-9) + 1e-12, &si));
        EXPECT_FALSE(m->closest_point(p, best * (1 - 1e-6), &si));
    }
    // Projection of a hit point (pushed off the surface along ng) returns the same point and
    // the same normal as intersect().
    for (int k = 0; k < 500; ++k) {
        const Vec3 o = warp::square_to_uniform_sphere(next_2d(rng)) * 2.5;
        const Vec3 dir = normalize(warp::square_to_uniform_sphere(next_2d(rng)) * 0.5 - o);
        SurfaceInteraction hit, proj;
        if (!scene.intersect(Ray{o, dir}, &hit) || hit.shape != m.get()) continue;
        const Vec3 q = hit.p + hit.ng * 1e-3;
        ASSERT_TRUE(m->closest_point(q, 1.0, &proj));
        EXPECT_LT(length(proj.p - hit.p), 1e-6);
        EXPECT_LT(length(proj.n - hit.n), 1e-5);
        EXPECT_LT(length(proj.dndu - hit.dndu) + length(proj.dpdu - hit.dpdu), 1e-4);
    }
}

// The manifold walk's projection from a point on the mesh (closest_point_near) is the closest
// point wherever the mesh is convex towards p: on a tessellated sphere, from outside, both for
// steps that stay over the starting triangle and for steps of up to several triangles that
// leave it (crossing edges, or the query where too many lie between); the radius cuts off alike.
TEST(GeometryMesh, ClosestPointNearMatchesClosestPointOnAConvexMesh) {
    const MeshData d = test::make_uv_sphere({0, 0, 0}, 1.0, 32, 16);
    auto m = std::make_shared<TriangleMesh>(d);
    Scene scene;
    scene.add_shape(m);
    scene.build();
    PCG32 rng(9, 4);
    int stayed = 0, left = 0;
    for (int k = 0; k < 2000; ++k) {
        const uint32_t prim =
            std::min(uint32_t(rng.next_double() * double(m->triangle_count())), uint32_t(m->triangle_count() - 1));
        const auto& tri = m->triangle(prim);
        const Vec3 a = m->vertex(tri[0]), b = m->vertex(tri[1]), c = m->vertex(tri[2]);
        if (!(length(cross(b - a, c - a)) > 1e-12)) continue;  // the poles' collapsed triangles
        Vec2 bc = next_2d(rng);
        if (bc.x + bc.y > 1) bc = Vec2(1 - bc.x, 1 - bc.y);
        SurfaceInteraction near;
        m->interaction_at(prim, bc, &near);
        // A tangent step of up to about one and a half triangles, lifted off the surface.
        const Frame f = Frame::from_normal(near.ng);
        const double phi = 2 * kPi * rng.next_double(), step = 0.6 * std::pow(rng.next_double(), 2.0);
        const Vec3 p =
            near.p + (f.s * std::cos(phi) + f.t * std::sin(phi)) * step + near.ng * (0.01 * rng.next_double());
        SurfaceInteraction got, ref;
        ASSERT_TRUE(m->closest_point(p, kInfinity, &ref));
        ASSERT_TRUE(m->closest_point_near(near, p, kInfinity, &got));
        EXPECT_EQ(got.prim, ref.prim);
        EXPECT_LT(length(got.p - ref.p), 1e-12);
        EXPECT_LT(length(got.n - ref.n), 1e-12);
        EXPECT_EQ(got.shape, m.get());
        (got.prim == prim ? stayed : left)++;
        const double dist = length(ref.p - p);
        EXPECT_FALSE(m->closest_point_near(near, p, dist * (1 - 1e-6), &got));
        EXPECT_TRUE(m->closest_point_near(near, p, dist * (1 + 1e-9) + 1e-12, &got));
    }
    EXPECT_GT(stayed, 300);
    EXPECT_GT(left, 1000);
}

// Edges join the triangles that share them, both ways, also across a seam whose vertices are
// duplicated (the uv sphere's meridian seam, a mesh split at its normals); a boundary edge joins
// none.
TEST(GeometryMesh, NeighboursShareAnEdgeBothWaysAndAcrossSeams) {
    const MeshData d = test::make_uv_sphere({0, 0, 0}, 1.0, 32, 16);
    TriangleMesh m(d);
    int joined = 0;
    for (uint32_t t = 0; t < m.triangle_count(); ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t n = m.neighbour(t, e);
            if (n == TriangleMesh::kNoNeighbour) continue;
            ++joined;
            // The edge's ends (by position) are two of the neighbour's corners, and it points back.
            const auto& tri = m.triangle(t);
            int shared = 0;
            for (int k = 1; k <= 2; ++k)
                for (uint32_t v : m.triangle(n)) shared += m.vertex(v) == m.vertex(tri[size_t((e + k) % 3)]);
            EXPECT_EQ(shared, 2) << t << " " << e;
            bool back = false;
            for (int f = 0; f < 3; ++f) back |= m.neighbour(n, f) == t;
            EXPECT_TRUE(back) << t << " " << e;
        }
    // Every edge but the poles' collapsed ones (3 per pole triangle: one collapsed, two shared).
    EXPECT_GT(joined, int(3 * m.triangle_count()) - 4 * 32);

    MeshData sheet;
    sheet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    sheet.triangles = {{0, 1, 2}, {2, 1, 3}};
    TriangleMesh two(sheet);
    EXPECT_EQ(two.neighbour(0, 0), 1u);  // edge (1, 2), opposite vertex 0
    EXPECT_EQ(two.neighbour(1, 2), 0u);  // edge (2, 1), opposite vertex 3
    EXPECT_EQ(two.neighbour(0, 1), TriangleMesh::kNoNeighbour);
}

// A projection stays on the sheet its vertex walks on: two parallel sheets of one mesh, not
// joined by any edge, the point above the first one several triangles from the start but
// nearer the second. The BVH's closest point is on the second; the walk's continuation on the
// first (asking the BVH, as before the edges were crossed, would jump to the other interface).
TEST(GeometryMesh, ClosestPointNearStaysOnTheSheetItWalksOn) {
    MeshData d;
    const int n = 10;
    for (int sheet = 0; sheet < 2; ++sheet) {
        const uint32_t base = uint32_t(d.positions.size());
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) d.positions.push_back({0.1 * i, 0.1 * j, 0.1 * sheet});
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const uint32_t v = base + uint32_t(j * (n + 1) + i);
                d.triangles.push_back({v, v + 1, v + uint32_t(n + 1)});
                d.triangles.push_back({v + uint32_t(n + 1), v + 1, v + uint32_t(n + 2)});
            }
    }
    auto m = std::make_shared<TriangleMesh>(d);
    Scene scene;
    scene.add_shape(m);
    scene.build();
    SurfaceInteraction near, got, ref;
    m->interaction_at(0, {0.25, 0.25}, &near);  // on the first sheet, at (0.025, 0.025, 0)
    const Vec3 p(0.53, 0.47, 0.08);
    ASSERT_TRUE(m->closest_point(p, kInfinity, &ref));
    EXPECT_NEAR(ref.p.z, 0.1, 1e-6);
    ASSERT_TRUE(m->closest_point_near(near, p, 1.0, &got));
    EXPECT_LT(length(got.p - Vec3(0.53, 0.47, 0)), 1e-9);
    EXPECT_NE(got.prim, near.prim);
}

// Three triangles of unequal area tiling [0,2]x[0,1]: a uniform sampler fills equal grid
// cells equally (chi-square, p > 1e-6).
TEST(GeometryMesh, AreaSamplingIsUniform) {
    MeshData d;
    d.positions = {{0, 0, 0}, {2, 0, 0}, {0.5, 1, 0}, {2, 1, 0}, {0, 1, 0}};
    d.triangles = {{0, 1, 2}, {2, 1, 3}, {0, 2, 4}};
    TriangleMesh m(d);
    EXPECT_NEAR(m.area(), 2.0, 1e-12);
    const int nx = 20, ny = 10, n = 200000;
    std::vector<double> counts(nx * ny, 0);
    PCG32 rng(6, 6);
    for (int i = 0; i < n; ++i) {
        const ShapeSample s = m.sample_area(next_2d(rng));
        ASSERT_NEAR(s.pdf, 0.5, 1e-15);
        EXPECT_NEAR(s.n.z, 1.0, 1e-15);
        const int ix = std::min(nx - 1, int(s.p.x / 2 * nx)), iy = std::min(ny - 1, int(s.p.y * ny));
        counts[iy * nx + ix] += 1;
    }
    const double chi2 = test::chi2_uniform(counts, double(n) / counts.size());
    EXPECT_GT(test::chi2_upper_tail(chi2, counts.size() - 1), 1e-6) << chi2;
}

// Default sample_from/pdf_from (area sampling converted to solid angle): consistent with
// each other, and E[1/pdf] equals the solid angle of a rectangle seen from a point on its
// axis, 4 asin(a b / sqrt((a^2 + h^2)(b^2 + h^2))) for half-sides a, b at height h.
TEST(GeometryMesh, SampleFromSolidAngle) {
    TriangleMesh m(make_rectangle(Transform::scale({1.0, 0.5, 1.0})));
    const Vec3 ref(0, 0, 0.7);
    const int n = 200000;
    PCG32 rng(12, 3);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const auto s = m.sample_from(ref, next_2d(rng));
        ASSERT_TRUE(s.has_value());
        EXPECT_NEAR(m.pdf_from(ref, s->p, s->n) / s->pdf, 1.0, 1e-12);
        sum += 1 / s->pdf;
        sum2 += 1 / (s->pdf * s->pdf);
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    const double a = 1.0, b = 0.5, h = 0.7;
    const double omega = 4 * std::asin(a * b / std::sqrt((a * a + h * h) * (b * b + h * h)));
    EXPECT_NEAR(mean, omega, 5 * se);
}

TEST(GeometryMesh, BuildersFollowMitsubaConventions) {
    TriangleMesh rect(make_rectangle());
    EXPECT_NEAR(rect.area(), 4.0, 1e-12);
    SurfaceInteraction si;
    ASSERT_TRUE(rect.closest_point({0.2, 0.3, 1}, kInfinity, &si));
    EXPECT_NEAR(si.ng.z, 1.0, 1e-15);
    EXPECT_NEAR(si.uv.x, 0.6, 1e-12);
    EXPECT_NEAR(si.uv.y, 0.65, 1e-12);

    // A mirroring transform keeps the normal equal to the transformed normal.
    const Transform mirror = Transform::scale({1, 1, -1}) * Transform::rotate({1, 0, 0}, 30);
    TriangleMesh mr(make_rectangle(mirror));
    ASSERT_TRUE(mr.closest_point(mirror.point({0.1, 0.1, 1}), kInfinity, &si));
    EXPECT_NEAR(dot(si.ng, normalize(mirror.normal({0, 0, 1}))), 1.0, 1e-12);

    TriangleMesh disk(make_disk());
    EXPECT_NEAR(disk.area(), kPi, kPi * 1e-3);
    ASSERT_TRUE(disk.closest_point({0.1, -0.2, -1}, kInfinity, &si));
    EXPECT_NEAR(si.ng.z, 1.0, 1e-15);

    TriangleMesh cube(make_cube(Transform::scale({2, 1, 1})));
    EXPECT_NEAR(cube.area(), 2 * (8 + 8 + 4), 1e-12);
    for (uint32_t i = 0; i < cube.triangle_count(); ++i) {
        cube.interaction_at(i, {1.0 / 3, 1.0 / 3}, &si);
        EXPECT_GT(dot(si.ng, si.p), 0) << i;  // outward
        EXPECT_NEAR(std::max({std::abs(si.p.x) / 2, std::abs(si.p.y), std::abs(si.p.z)}), 1.0, 1e-12);
    }
}

TEST(GeometryMesh, InvalidMeshThrows) {
    MeshData d = skewed_triangle(true);
    d.triangles[0][2] = 7;
    EXPECT_THROW(TriangleMesh(d, false, false, "bad.ply"), std::runtime_error);
    try {
        TriangleMesh bad(d, false, false, "bad.ply");
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.ply"), std::string::npos);
    }
}

/// Meshes up to TriangleMesh::kMaxCachedTriangles keep the per-triangle part of the
/// differential geometry precomputed; larger ones recompute it per hit. Both must give the
/// same bits, for smooth, flat, textured and flipped meshes alike.
TEST(GeometryMesh, CachedTriangleParamsAreBitIdentical) {
    for (int variant = 0; variant < 8; ++variant) {
        const bool with_uv = variant & 1, face_normals = variant & 2, flip = variant & 4;
        MeshData small = skewed_triangle(with_uv);
        MeshData large = small;
        // Pad with reversed copies of the triangle until the cache is off.
        const size_t pad = TriangleMesh::kMaxCachedTriangles;
        for (size_t i = 0; i < pad; ++i) large.triangles.push_back({0, 2, 1});
        const TriangleMesh a(small, face_normals, flip), b(large, face_normals, flip);
        PCG32 rng(3, 5);
        for (int k = 0; k < 64; ++k) {
            Vec2 q = next_2d(rng);
            if (q.x + q.y > 1) q = Vec2(1 - q.x, 1 - q.y);
            SurfaceInteraction sa, sb;
            a.interaction_at(0, q, &sa);
            b.interaction_at(0, q, &sb);
            for (const auto& [x, y] : {std::pair{sa.p, sb.p},
                                       {sa.ng, sb.ng},
                                       {sa.n, sb.n},
                                       {sa.dpdu, sb.dpdu},
                                       {sa.dpdv, sb.dpdv},
                                       {sa.dndu, sb.dndu},
                                       {sa.dndv, sb.dndv},
                                       {sa.shading.s, sb.shading.s},
                                       {sa.shading.t, sb.shading.t},
                                       {sa.shading.n, sb.shading.n}})
                EXPECT_EQ(x, y) << "variant " << variant;
            EXPECT_EQ(sa.uv, sb.uv) << "variant " << variant;
        }
    }
}

// Mitsuba's disk parametrisation, uv = (r, phi / 2 pi), on the triangle fan (256 segments): r
// within the chord's sag, phi / 2 pi within half a segment (towards the centre a fan triangle
// interpolates v towards its centre vertex's).
TEST(GeometryMesh, DiskHasMitsubasPolarUv) {
    auto disk = std::make_shared<TriangleMesh>(make_disk(Transform::scale(Vec3(2, 2, 1))));
    Scene scene;
    scene.add_shape(disk);
    scene.build();
    for (double r : {0.2, 0.5, 0.9})
        for (double phi : {0.3, 2.0, 3.5, 6.1}) {
            const Vec3 target(2 * r * std::cos(phi), 2 * r * std::sin(phi), 0);
            SurfaceInteraction si;
            ASSERT_TRUE(scene.intersect(Ray{target + Vec3(0, 0, 1), Vec3(0, 0, -1), 0.0, kInfinity}, &si));
            EXPECT_NEAR(si.uv.x, r, 1e-4) << r << " " << phi;
            EXPECT_NEAR(si.uv.y, phi / (2 * kPi), 0.5 / 256) << r << " " << phi;  // half a segment
        }
}
