#pragma once
// Helpers shared by the geometry tests.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/mesh_data.h"
#include "core/rng.h"
#include "core/vector.h"
#include "geometry/interaction.h"

namespace snell::test {

/// The interaction's dp/du, dp/dv, dn/du, dn/dv against central differences of p and n from the
/// interactions at (u +- h, v) and (u, v +- h), within `tol_p` and `tol_n`; n unit and normal
/// to both tangents.
inline void expect_differential_geometry(const SurfaceInteraction& si, const SurfaceInteraction& up,
                                         const SurfaceInteraction& um, const SurfaceInteraction& vp,
                                         const SurfaceInteraction& vm, double h, double tol_p, double tol_n) {
    EXPECT_LT(length((up.p - um.p) / (2 * h) - si.dpdu), tol_p);
    EXPECT_LT(length((vp.p - vm.p) / (2 * h) - si.dpdv), tol_p);
    EXPECT_LT(length((up.n - um.n) / (2 * h) - si.dndu), tol_n);
    EXPECT_LT(length((vp.n - vm.n) / (2 * h) - si.dndv), tol_n);
    EXPECT_NEAR(length(si.n), 1.0, 1e-14);
    EXPECT_NEAR(dot(si.n, si.dpdu), 0.0, 1e-12);
    EXPECT_NEAR(dot(si.n, si.dpdv), 0.0, 1e-12);
}

/// Upper-tail probability of a chi-square statistic with k degrees of freedom, through the
/// Wilson-Hilferty cube-root normal approximation (accurate to ~1e-3 relative for k >= 30,
/// ample for thresholds like 1e-6).
inline double chi2_upper_tail(double chi2, double k) {
    const double z = (std::cbrt(chi2 / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

/// Pearson statistic of observed counts against equal expected counts.
inline double chi2_uniform(const std::vector<double>& counts, double expected) {
    double s = 0;
    for (double c : counts) s += (c - expected) * (c - expected) / expected;
    return s;
}

/// Latitude-longitude sphere of radius r about c: (nu+1) x (nv+1) grid with seam and pole
/// vertices duplicated so that uv = (phi/2pi, theta/pi) is continuous within each triangle,
/// exact unit normals, and pole triangles kept (their uv map is non-degenerate).
inline MeshData make_uv_sphere(const Vec3& c, double r, int nu, int nv) {
    MeshData m;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const double u = double(i) / nu, v = double(j) / nv;
            const double th = kPi * v, ph = 2 * kPi * u;
            const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
            m.positions.push_back(c + n * r);
            m.normals.push_back(n);
            m.uvs.push_back({u, v});
        }
    auto id = [&](int i, int j) { return uint32_t(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            // Outward winding: (u, v) increases east and south, so (i,j),(i,j+1),(i+1,j+1) is CCW
            // from outside.
            if (j > 0) m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
            if (j < nv - 1) m.triangles.push_back({id(i + 1, j), id(i, j + 1), id(i + 1, j + 1)});
        }
    return m;
}

inline Vec2 next_2d(PCG32& rng) {
    const double a = rng.next_double();
    return {a, rng.next_double()};
}

}  // namespace snell::test
