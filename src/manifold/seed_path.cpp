#include "manifold/seed_path.h"

#include "bsdf/bsdf.h"
#include "scene/scene.h"

namespace snell {

bool is_manifold_interface(const BSDF* bsdf, double lambda) { return bsdf && bsdf->is_refractive_interface(lambda); }

SeedStatus trace_seed_path(const Scene& scene, const SurfaceInteraction& xb, const Vec3& xc, double lambda,
                           const MneeSettings& settings, std::vector<ManifoldVertex>* chain) {
    chain->clear();
    Ray ray = scene.spawn_ray_to(xb, xc);
    bool blocked = false;
    for (;;) {
        SurfaceInteraction si;
        if (!scene.intersect(ray, &si)) break;
        const BSDF* bsdf = si.bsdf();
        if (is_manifold_interface(bsdf, lambda)) {
            if (int(chain->size()) >= settings.max_vertices) return SeedStatus::TooMany;
            chain->push_back(ManifoldVertex::from_interaction(si, bsdf->eta(lambda)));
        } else if (!settings.ignore_occluders) {
            // The paper's estimator stops at a blocker; only the surface seeds of the
            // multi-solution estimators need to know whether glass lies beyond it.
            if (settings.solutions == MneeSolutions::One) return SeedStatus::Occluded;
            blocked = true;
        }
        ray = scene.spawn_ray_to(si, xc);
    }
    if (blocked) return chain->empty() ? SeedStatus::Occluded : SeedStatus::BlockedRefractive;
    return chain->empty() ? SeedStatus::Clear : SeedStatus::Refractive;
}

}  // namespace snell
