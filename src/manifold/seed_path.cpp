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
    // Blocked even with no glass on the segment: the surface seeds may find a refracted path
    // around the blocker. Without them the environment-lit pool's floor near its walls was
    // BSDF sampling's alone, and the biased mode, which drops what MNEE cannot reach, lost part
    // of its caustic (issue 26, point 6; docs/experiments.md, nineteenth measurement).
    // A scene without glass has nothing to find there: Occluded, so that MNEE stays NEE sample for
    // sample (Sec. 3.1).
    if (blocked)
        return chain->empty() && scene.refractive_casters().empty() ? SeedStatus::Occluded : SeedStatus::Blocked;
    return chain->empty() ? SeedStatus::Clear : SeedStatus::Refractive;
}

}  // namespace snell
