#pragma once
// Paper Sec. 3.1: the seed path is the straight segment x_b -> x_c with every refractive
// vertex on it collected. It needs no energy balance; it only starts the manifold walk.
#include <vector>

#include "core/vector.h"
#include "geometry/interaction.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"

namespace snell {

class Scene;
class BSDF;

enum class SeedStatus {
    Clear,       ///< nothing in between: MNEE is plain NEE for this sample
    Refractive,  ///< one or more refractive vertices (the chain to walk)
    Occluded,    ///< an opaque surface blocks the segment (solutions=one: the paper's MNEE stops)
    /// An opaque surface blocks the segment (the multi-solution estimators). The straight seed is
    /// blocked, but refracted paths may pass the blocker: through glass on the segment (an object
    /// inside glass), or beside it with no glass on the segment at all (a pool floor's line to a
    /// low sun meets the wall under water, while the refracted path leaves the water first).
    /// Surface seeds look for them. The chain holds the refractive vertices on the segment, if
    /// any, the blockers passed through. (Occluded where the scene holds no glass at all.)
    Blocked,
    TooMany,  ///< more refractive vertices than max_vertices
};

/// Whether a BSDF is a refractive interface that MNEE treats as a chain vertex: a dielectric,
/// smooth or rough (something that bends light: eta != 1 with a transmission lobe).
bool is_manifold_interface(const BSDF* bsdf, double lambda);

/// Traces the straight segment from `xb` to `xc` and collects the refractive vertices
/// (h_target zero; the half-vector sampler sets it). With settings.ignore_occluders, opaque
/// surfaces on the segment are not reported (Refractive or Clear). With solutions=one a blocked
/// segment is Occluded at its first blocker; the multi-solution estimators trace on and call it
/// Blocked.
SeedStatus trace_seed_path(const Scene& scene, const SurfaceInteraction& xb, const Vec3& xc, double lambda,
                           const MneeSettings& settings, std::vector<ManifoldVertex>* chain);

}  // namespace snell
