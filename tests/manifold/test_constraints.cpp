// Finite-difference checks of the constraint derivative blocks A_i, B_i, C_i (paper Eq. 4) and
// of |dH/dX| as the product of pivot determinants (Eq. 8).
#include <gtest/gtest.h>

#include <functional>

#include "manifold/block_tridiagonal.h"
#include "manifold/chain_fixture.h"
#include "manifold/generalized_geometry.h"
#include "manifold/manifold_walk.h"

using namespace snell;
using namespace snell::test;

namespace {

// Moves vertex j of the chain by tangent offsets (a, b) and projects it back to its shape.
std::vector<ManifoldVertex> moved(const std::vector<ManifoldVertex>& chain, size_t j, const Vec2& ab) {
    std::vector<ManifoldVertex> c = chain;
    ManifoldVertex v;
    EXPECT_TRUE(project_vertex(nullptr, chain[j], Vec3(), chain[j].offset(ab), Projection::ClosestPoint, &v));
    c[j] = v;
    return c;
}

std::vector<Vec2> values(const Vec3& xb, const std::vector<ManifoldVertex>& chain, const Vec3& xc) {
    std::vector<Vec2> out;
    for (size_t i = 0; i < chain.size(); ++i) {
        const Vec3& prev = i == 0 ? xb : chain[i - 1].p;
        const Vec3& next = i + 1 == chain.size() ? xc : chain[i + 1].p;
        out.push_back(half_vector_constraint_value(prev, chain[i], next));
    }
    return out;
}

void expect_mat_near(const Mat2& a, const Mat2& b, double tol, const std::string& what) {
    const double s = std::max(1.0, b.max_abs());
    EXPECT_NEAR(a.a, b.a, tol * s) << what;
    EXPECT_NEAR(a.b, b.b, tol * s) << what;
    EXPECT_NEAR(a.c, b.c, tol * s) << what;
    EXPECT_NEAR(a.d, b.d, tol * s) << what;
}

// Checks every block of the chain's constraint matrix against central differences.
void check_blocks(const Vec3& xb, const std::vector<ManifoldVertex>& chain, const TangentBasis& xc) {
    BlockTridiagonal m;
    std::vector<Vec2> c;
    ASSERT_TRUE(build_constraints(xb, chain, xc, &m, &c));
    const double h = 1e-6;
    const size_t k = chain.size();
    for (size_t j = 0; j < k; ++j) {
        Vec2 col[2][8];  // d c_i / d (a|b) of vertex j, for each i
        for (int axis = 0; axis < 2; ++axis) {
            const Vec2 e = axis == 0 ? Vec2(h, 0) : Vec2(0, h);
            const auto plus = values(xb, moved(chain, j, e), xc.p);
            const auto minus = values(xb, moved(chain, j, e * -1.0), xc.p);
            for (size_t i = 0; i < k; ++i) col[axis][i] = (plus[i] - minus[i]) / (2 * h);
        }
        for (size_t i = 0; i < k; ++i) {
            const Mat2 fd = Mat2::from_columns(col[0][i], col[1][i]);
            if (i == j)
                expect_mat_near(m.B[i], fd, 1e-5, "B_" + std::to_string(i));
            else if (i == j + 1)
                expect_mat_near(m.A[i], fd, 1e-5, "A_" + std::to_string(i));
            else if (j == i + 1)
                expect_mat_near(m.C[i], fd, 1e-5, "C_" + std::to_string(i));
            else
                expect_mat_near(Mat2(), fd, 1e-5, "zero block");
        }
    }
    // C block of the last vertex with respect to the light point x_c.
    for (int axis = 0; axis < 2; ++axis) {
        const Vec3 e = (axis == 0 ? xc.dp_ds : xc.dp_dt) * h;
        const auto plus = values(xb, chain, xc.p + e), minus = values(xb, chain, xc.p - e);
        const Vec2 fd = (plus[k - 1] - minus[k - 1]) / (2 * h);
        const Vec2 an = axis == 0 ? Vec2(m.C[k - 1].a, m.C[k - 1].c) : Vec2(m.C[k - 1].b, m.C[k - 1].d);
        EXPECT_NEAR(an.x, fd.x, 1e-5 * (1 + std::abs(fd.x)));
        EXPECT_NEAR(an.y, fd.y, 1e-5 * (1 + std::abs(fd.y)));
    }
}

// Determinant of a dense matrix by partial-pivot elimination.
double dense_det(std::vector<std::vector<double>> a) {
    const size_t n = a.size();
    double det = 1;
    for (size_t c = 0; c < n; ++c) {
        size_t p = c;
        for (size_t r = c + 1; r < n; ++r)
            if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
        if (a[p][c] == 0) return 0;
        if (p != c) {
            std::swap(a[p], a[c]);
            det = -det;
        }
        det *= a[c][c];
        for (size_t r = c + 1; r < n; ++r) {
            const double f = a[r][c] / a[c][c];
            for (size_t k = c; k < n; ++k) a[r][k] -= f * a[c][k];
        }
    }
    return det;
}

}  // namespace

TEST(Constraints, SphereTwoInterfacesMatchFiniteDifferences) {
    Sphere s(Vec3(0, 0, 0), 1.0);
    const Vec3 xb(0.3, -0.2, -2.5);
    std::vector<ManifoldVertex> chain = {vertex_on(s, Vec3(0.1, 0.05, -1), 1.33, Vec2(0.05, -0.02)),
                                         vertex_on(s, Vec3(0.2, -0.1, 1), 1.33, Vec2(-0.03, 0.04))};
    check_blocks(xb, chain, endpoint(Vec3(0.5, 0.4, 3), Vec3(0.1, 0.2, -1)));
}

TEST(Constraints, ReflectionAndThreeVerticesMatchFiniteDifferences) {
    // Refract into a sphere, reflect inside it, refract out: three vertices, mixed types.
    Sphere s(Vec3(0, 0, 0), 1.0);
    const Vec3 xb(-2.0, 0.3, -1.0);
    std::vector<ManifoldVertex> chain = {vertex_on(s, Vec3(-1, 0.2, -0.3), 1.5), vertex_on(s, Vec3(0.2, 0.1, -1), 1.5),
                                         vertex_on(s, Vec3(0.9, 0.1, 0.3), 1.5, Vec2(0.01, 0.02))};
    check_blocks(xb, chain, endpoint(Vec3(2.5, 0.5, 1.5), Vec3(-1, 0, -0.5)));
}

TEST(Constraints, SmoothMeshMatchesFiniteDifferences) {
    // Interpolated vertex normals: dn comes from the mesh's normal derivatives.
    TriangleMesh mesh(uv_sphere_mesh(Vec3(0, 0, 0), 1.0), false, false, "uvsphere");
    const Vec3 xb(0.3, -0.2, -2.5);
    std::vector<ManifoldVertex> chain = {vertex_on(mesh, Vec3(0.13, 0.07, -1), 1.33, Vec2(0.05, -0.02)),
                                         vertex_on(mesh, Vec3(0.21, -0.12, 1), 1.33)};
    check_blocks(xb, chain, endpoint(Vec3(0.5, 0.4, 3), Vec3(0, 0, -1)));
}

TEST(Constraints, DeterminantIsProductOfPivots) {
    Sphere s(Vec3(0, 0, 0), 1.0);
    Sphere inner(Vec3(0.05, 0, 0), 0.5);
    const Vec3 xb(0.3, -0.2, -2.5);
    std::vector<ManifoldVertex> chain = {
        vertex_on(s, Vec3(0.1, 0.05, -1), 1.33, Vec2(0.05, -0.02)), vertex_on(inner, Vec3(0.1, 0.0, -0.5), 1.2),
        vertex_on(inner, Vec3(0.15, 0.0, 0.5), 1.2), vertex_on(s, Vec3(0.2, -0.1, 1), 1.33, Vec2(-0.03, 0.04))};
    const TangentBasis xc = endpoint(Vec3(0.5, 0.4, 3), Vec3(0, 0, -1));
    BlockTridiagonal m;
    std::vector<Vec2> c;
    ASSERT_TRUE(build_constraints(xb, chain, xc, &m, &c));
    BlockLU lu;
    ASSERT_TRUE(lu.factor(m));
    // Dense finite-difference Jacobian dH/dX of the whole chain.
    const size_t k = chain.size(), n = 2 * k;
    std::vector<std::vector<double>> J(n, std::vector<double>(n));
    const double h = 1e-6;
    for (size_t j = 0; j < k; ++j)
        for (int axis = 0; axis < 2; ++axis) {
            const Vec2 e = axis == 0 ? Vec2(h, 0) : Vec2(0, h);
            const auto p = values(xb, moved(chain, j, e), xc.p), q = values(xb, moved(chain, j, e * -1.0), xc.p);
            for (size_t i = 0; i < k; ++i) {
                J[2 * i][2 * j + axis] = (p[i].x - q[i].x) / (2 * h);
                J[2 * i + 1][2 * j + axis] = (p[i].y - q[i].y) / (2 * h);
            }
        }
    const double fd = std::abs(dense_det(J));
    EXPECT_NEAR(lu.abs_det(), fd, 1e-5 * fd);
    const ChainJacobians jac = chain_jacobians(xb, chain, xc);
    EXPECT_NEAR(jac.dH_dX, fd, 1e-5 * fd);

    // The block solve agrees with the dense system.
    std::vector<Vec2> dx;
    ASSERT_TRUE(solve_matrix_h_to_x(m, c, &dx));
    for (size_t i = 0; i < n; ++i) {
        double r = 0;
        for (size_t j = 0; j < k; ++j) r += J[i][2 * j] * dx[j].x + J[i][2 * j + 1] * dx[j].y;
        EXPECT_NEAR(r, -(i % 2 ? c[i / 2].y : c[i / 2].x), 1e-6);
    }
}
