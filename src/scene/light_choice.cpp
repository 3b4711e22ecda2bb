#include "scene/light_choice.h"

#include <cmath>

#include "core/sampler.h"
#include "scene/scene.h"

namespace snell {

std::optional<LightSample> sample_light(const Scene& scene, const SurfaceInteraction& si, const SampledWavelengths& wl,
                                        Sampler& sampler, const Light** light, double* pmf, bool keep_dark) {
    *light = scene.light_sampler().sample(sampler.next_1d(), pmf);
    const Vec2 u = sampler.next_2d();
    if (!*light || !(*pmf > 0)) return std::nullopt;
    auto ls = (*light)->sample_li({si.p, si.n}, u, wl);
    if (!ls || !(ls->pdf > 0) || !(keep_dark || ls->Le.is_nonzero())) return std::nullopt;
    return ls;
}

bool light_visible(const Scene& scene, const SurfaceInteraction& si, const LightSample& ls) {
    return !scene.occluded(std::isinf(ls.dist) ? scene.spawn_ray(si, ls.wi) : scene.spawn_ray_to(si, ls.p, ls.p_error));
}

}  // namespace snell
