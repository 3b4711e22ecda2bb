#include "integrators/path/camera_walk.h"

#include "core/sampler.h"
#include "integrators/mis.h"
#include "scene/scene.h"

namespace snell {

double PreviousVertex::emitter_weight(const Scene& scene, const Light& light, const Vec3& p, const Vec3& n,
                                      const Vec3& d) const {
    if (delta) return 1.0;
    const double light_pdf = scene.light_sampler().pmf(&light) * light.pdf_li(at, p, n, d);
    return power_heuristic(bsdf_pdf, light_pdf);
}

bool CameraWalk::trace(SurfaceInteraction* si) {
    if (!m_scene->intersect(ray, si)) return false;
    if (media.inside()) tp.beta *= media.transmittance(si->t, m_wl);
    if (m_observer) m_observer->arrived(*si);
    return true;
}

std::optional<BSDFSample> CameraWalk::scatter(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx,
                                              Sampler& sampler) {
    const auto bs = m_casters.sample(si, bsdf, sctx, sampler.next_1d(), sampler.next_2d());
    if (!bs || bs->weight.is_zero()) return std::nullopt;
    BSDFSample world = *bs;
    world.wi = si.to_world(bs->wi);
    tp.scatter(*bs, m_wl, TransportMode::Radiance);
    if (!bs->is_delta()) m_specular_prefix = false;
    if (crosses_interior(bsdf, world)) cross_interface(media, si, bsdf);
    ray = m_scene->spawn_ray(si, world.wi);
    if (depth + 1 >= m_settings->rr_depth && !tp.survives_roulette(sampler.next_1d())) return std::nullopt;
    return world;
}

}  // namespace snell
