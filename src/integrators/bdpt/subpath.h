#pragma once
// BDPT's two random walks: the camera subpath (Radiance) and the light subpath (Importance),
// each vertex recording its forward and reverse densities.
#include <cstddef>
#include <vector>

#include "core/sampler.h"
#include "integrators/bdpt/vertex.h"

namespace snell::bdpt {

// With max_depth = -1 subpaths end by Russian roulette; this cap only bounds memory (a path
// of this many vertices has a vanishing probability under roulette).
constexpr int kUnboundedVertices = 128;

/// Where a camera subpath escaped the scene (for lights at infinity).
struct Escape {
    bool escaped = false;
    Vec3 d;
    SampledSpectrum beta;
    double pdf_dir = 0;  // solid-angle density of d at the last vertex (0 after a delta lobe)
};

// Extends `path` (holding its first vertex) by BSDF sampling until `max_vertices`, absorption
// or roulette. `pdf_dir` is the density of `ray.d` at the first vertex.
void random_walk(const Scene& scene, Ray ray, Sampler& sampler, const SampledWavelengths& wl, SampledSpectrum beta,
                 double pdf_dir, size_t max_vertices, int rr_depth, TransportMode mode, std::vector<Vertex>& path,
                 Escape* escape);

// Samples y_0 on a light and walks the light subpath. A finite light gives a point and a
// cosine-weighted (area) or uniform (point, spot) direction; a light at infinity gives a
// direction d towards it (its own sample_li distribution) and a point on the scene disk facing
// d, from which the subpath travels along -d.
void light_subpath(const Scene& scene, const SceneDisk& disk, Sampler& sampler, const SampledWavelengths& wl,
                   size_t max_vertices, int rr_depth, std::vector<Vertex>& path);

}  // namespace snell::bdpt
