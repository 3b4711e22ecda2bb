// Deterministic checks of BDPT's internals that renders barely see: the densities each random
// walk records must be the ones pdf_area() recomputes for the MIS weights, and a connection
// through a vertex with a tilted shading normal must carry the adjoint correction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bsdf/diffuse.h"
#include "integrators/bdpt/connect.h"
#include "integrators/bdpt/subpath.h"
#include "sampler/independent.h"
#include "stat/box_scene.h"
#include "stat/render_stats.h"

using namespace snell;
using namespace snell::bdpt;
using namespace snell::test;

namespace {

TransportMode opposite(TransportMode m) {
    return m == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
}

double rel_diff(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

}  // namespace

// Along light subpaths of the box (rough glass, rough metal, diffuse walls), every vertex's
// pdf_rev is the density with which the opposite subpath, continuing from the next vertex
// (reached from the one after), samples it; pdf_fwd of each vertex past the first two is the
// walk's own density from its predecessor. A swapped argument in the walk's reverse BSDF
// density changes only MIS weights, by < 0.1% of a render, but shows here at once. (The walk
// uses its sampled direction, pdf_area() the direction between the hit points, which differ in
// the last digits of the hits: hence "within 1%", and near-contact vertices are skipped.)
TEST(BdptVertices, WalkDensitiesMatchPdfArea) {
    const LoadedScene ls = load_xml(kCornellBox, {{"integrator", "bdpt"}});
    const Scene& scene = *ls.scene;
    const SceneDisk disk(scene.bounds());
    IndependentSampler sampler(17);
    // Count densities off by more than 1% (a swapped argument puts most of them there).
    int checked = 0, off = 0;
    for (uint64_t i = 0; i < 4000; ++i) {
        sampler.start_pixel_sample(3, 5, i);
        std::vector<Vertex> path;
        light_subpath(scene, disk, sampler, SampledWavelengths::single(550), 8, 100, path);
        for (size_t k = 1; k + 2 < path.size(); ++k) {
            const Vertex& v = path[k];
            if (v.delta || path[k + 1].delta) continue;  // a delta lobe records 0
            // Where the glass sphere touches the floor, vertices a hair apart make the direction
            // between hit points (which pdf_area() uses) differ from the sampled one.
            const double gap = std::min({length(path[k].si.p - path[k - 1].si.p), length(path[k + 1].si.p - v.si.p),
                                         length(path[k + 2].si.p - path[k + 1].si.p)});
            if (gap < 0.05) continue;
            const double rev = pdf_area(path[k + 1], &path[k + 2], v, opposite(TransportMode::Importance),
                                        SampledWavelengths::single(550), disk);
            const double fwd = pdf_area(path[k], &path[k - 1], path[k + 1], TransportMode::Importance,
                                        SampledWavelengths::single(550), disk);
            off += rel_diff(v.pdf_rev, rev) > 1e-2;
            off += rel_diff(path[k + 1].pdf_fwd, fwd) > 1e-2;
            checked += 2;
        }
    }
    std::printf("%d of %d densities differ by more than 1%%\n", off, checked);
    EXPECT_LE(off, checked / 1000);
    EXPECT_GT(checked, 1000);
}

// connect() for s >= 2 at a light vertex y whose shading normal leans 35 degrees off its
// geometric normal: the adjoint diffuse BSDF times |cos| at y is rho/pi |wo.ns| |wi.ng| / |wo.ng|
// (Veach's thesis, Sec. 5.3), wo towards y's predecessor, wi towards the camera vertex.
TEST(BdptVertices, ConnectionCarriesTheAdjointShadingCorrection) {
    const LoadedScene ls = load_xml(kCornellBox, {{"integrator", "bdpt"}});
    const Scene& scene = *ls.scene;
    const DiffuseBSDF white(Spectrum::constant(0.5));
    const auto surface = [&](const Vec3& p, const Vec3& ng, const Vec3& ns, const Vec3& wo) {
        Vertex v;
        v.si.p = p;
        v.si.ng = normalize(ng);
        v.si.n = normalize(ns);
        v.si.shading = Frame::from_normal(v.si.n);
        v.si.wo = normalize(wo);
        v.bsdf = &white;
        v.beta = SampledSpectrum(1.0);
        return v;
    };
    // z on the floor of the box, y in mid-air facing down with its shading normal tilted; the
    // segment between them passes both spheres.
    const Vec3 up(0, 1, 0), down(0, -1, 0);
    const Vec3 pz(-0.6, 0.001, 0.6), py(0.2, 0.8, 0.3);
    const Vec3 ns_tilted(std::sin(0.6), -std::cos(0.6), 0);
    std::vector<Vertex> cam{Vertex{}, surface(pz, up, up, Vec3(0, 1, 1))};
    std::vector<Vertex> lig{Vertex{}, surface(py, down, ns_tilted, Vec3(0.3, -1, 0.2))};
    const double c = connect(scene, cam, lig, 2, 2, SampledWavelengths::single(550))[0];

    const Vec3 d = normalize(py - pz);  // from z towards y
    const double d2 = length_squared(py - pz);
    const double fz = 0.5 * kInvPi * std::abs(dot(up, d));
    const Vertex& y = lig[1];
    const double fy =
        0.5 * kInvPi * std::abs(dot(y.si.wo, y.si.n)) * std::abs(dot(-d, y.si.ng)) / std::abs(dot(y.si.wo, y.si.ng));
    ASSERT_GT(c, 0);
    EXPECT_LT(rel_diff(c, fz * fy / d2), 1e-9) << c << " vs " << fz * fy / d2;
}
