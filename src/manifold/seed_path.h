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
    Occluded,    ///< an opaque surface blocks the segment, and no refractive vertex lies on it
    /// An opaque surface blocks the segment, and refractive vertices lie on it too (an object
    /// inside glass). The straight seed is blocked (the paper's MNEE stops here), but the
    /// refracted paths may pass the blocker: surface seeds still look for them. The chain holds
    /// the refractive vertices, the blockers passed through.
    BlockedRefractive,
    TooMany,  ///< more refractive vertices than max_vertices
};

/// Whether a BSDF is a refractive interface that MNEE treats as a chain vertex: a dielectric,
/// smooth or rough (something that bends light: eta != 1 with a transmission lobe).
bool is_manifold_interface(const BSDF* bsdf, double lambda);

/// Traces the straight segment from `xb` to `xc` and collects the refractive vertices
/// (h_target zero; the half-vector sampler sets it). With settings.ignore_occluders, opaque
/// surfaces on the segment are not reported (Refractive or Clear). With solutions=one a blocked
/// segment is Occluded at its first blocker (BlockedRefractive only for the multi-solution
/// estimators, which trace on).
SeedStatus trace_seed_path(const Scene& scene, const SurfaceInteraction& xb, const Vec3& xc, double lambda,
                           const MneeSettings& settings, std::vector<ManifoldVertex>* chain);

}  // namespace snell
