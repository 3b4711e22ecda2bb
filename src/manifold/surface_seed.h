#pragma once
// Seeds on the caster shapes (Specular Manifold Sampling, Zeltner, Georgiev & Jakob 2020): a
// point drawn on a refractive shape as seen from x_b, and the ray x_b -> that point refracted
// through every interface it meets. Unlike the paper's straight seed (Sec. 3.1), every solution
// of the constraints has a nonzero chance to be the one the walk from such a seed reaches.
#include <vector>

#include "core/rng.h"
#include "core/vector.h"
#include "geometry/interaction.h"
#include "manifold/half_vectors.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"

namespace snell {

class Scene;
class Shape;

enum class SurfaceSeedEnd {
    Ok,
    MissedCaster,             ///< the ray towards the drawn point hits something else first
    TotalInternalReflection,  ///< the seed ray cannot leave an interface
    TooMany,                  ///< more refractive vertices than max_vertices
};

/// Draws y on `caster` as seen from x_b (u), traces x_b -> y, and refracts at every refractive
/// interface hit about the vertex's target half vector (slot i of `draws`: the shading normal for
/// smooth vertices, and for every vertex without `draws`), until the ray meets anything else or
/// leaves the scene. Fills `chain` with the interface vertices (h_target set). With settings.reflections and a
/// `scatter` stream, a vertex reflects instead with Fresnel's probability (always under total internal reflection) and
/// is marked `reflect`. `exit_dir`: the direction of the ray after the last vertex.
SurfaceSeedEnd trace_surface_seed(const Scene& scene, const SurfaceInteraction& xb, const Shape& caster, const Vec2& u,
                                  double lambda, const MneeSettings& settings, HalfVectorDraws* draws,
                                  std::vector<ManifoldVertex>* chain, PCG32* scatter = nullptr,
                                  Vec3* exit_dir = nullptr);

/// How far a traced seed's last ray (direction `exit_dir` from its last vertex) passes from the
/// light point x_c: 1 - cos of the angle between it and the direction to x_c, in [0, 2]; plus 2
/// where the ray is still inside the glass (the chain cannot reach the light). 0 for a seed that
/// is already a solution: seeds that pass close start near one.
double seed_miss(const std::vector<ManifoldVertex>& chain, const Vec3& exit_dir, const Vec3& xc);

/// The same from the light's side: draws y on `caster` as seen from the light point `xc`, traces
/// xc -> y and refracts about the shading normals until the ray meets anything else; the chain
/// is then ordered from x_b and each vertex gets its slot's target half vector. The walk then
/// moves its last segment's end onto x_b. Where the glass focuses light onto x_b, many directions
/// from the light land near it: such seeds find the bright solutions near a caustic's fold (whose
/// basins, seen from x_b, are small) with a high probability.
SurfaceSeedEnd trace_light_seed(const Scene& scene, const Vec3& xc, const Shape& caster, const Vec2& u, double lambda,
                                const MneeSettings& settings, HalfVectorDraws& draws,
                                std::vector<ManifoldVertex>* chain, PCG32* scatter = nullptr);

}  // namespace snell
