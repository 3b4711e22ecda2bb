#include "integrators/path/path_tracer.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "core/props.h"
#include "core/stats.h"
#include "geometry/scene.h"
#include "integrators/medium_stack.h"
#include "integrators/mis.h"

namespace snell {

PathSettings PathSettings::from_props(const Props& props) {
    PathSettings s;
    s.max_depth = int(props.get_int("max_depth", -1));
    s.rr_depth = int(props.get_int("rr_depth", 5));
    s.hide_emitters = props.get_bool("hide_emitters", false);
    if (s.max_depth < -1 || s.max_depth == 0) props.raise_param("max_depth", "must be -1 (unbounded) or >= 1");
    if (s.rr_depth < 1) props.raise_param("rr_depth", "must be >= 1");
    return s;
}

double PathTracer::bsdf_hit_weight(double bsdf_pdf, double light_pdf_sa) const {
    return power_heuristic(bsdf_pdf, light_pdf_sa);
}

double PathTracer::connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                    const BSDFContext& ctx, const MediumStack& media,
                                    Sampler& sampler) const {
    double pmf = 0;
    const Light* light = scene.light_sampler().sample(sampler.next_1d(), &pmf);
    const Vec2 u = sampler.next_2d();
    if (!light || pmf <= 0) return 0;
    const auto ls = light->sample_li({si.p, si.n}, u, ctx.lambda);
    if (!ls || !(ls->pdf > 0) || !(ls->Le > 0)) return 0;

    const Vec3 wo = si.to_local(si.wo), wi = si.to_local(ls->wi);
    const double f = bsdf.eval(ctx, wo, wi) * std::abs(wi.z);
    if (!(f > 0)) return 0;
    const Ray shadow = std::isinf(ls->dist) ? scene.spawn_ray(si, ls->wi) : scene.spawn_ray_to(si, ls->p);
    if (scene.occluded(shadow)) return 0;
    // Unoccluded, so the shadow segment lies entirely in the current medium.
    const double tr = media.inside() ? media.transmittance(ls->dist, ctx.lambda) : 1.0;
    // Power heuristic against BSDF sampling; delta lights cannot be hit by BSDF sampling.
    const double w = ls->delta ? 1.0 : power_heuristic(pmf * ls->pdf, bsdf.pdf(ctx, wo, wi));
    return f * tr * ls->Le * w / (pmf * ls->pdf);
}

double PathTracer::li(const Ray& camera_ray, const Scene& scene, Sampler& sampler, double lambda) const {
    thread_counters().paths++;
    const BSDFContext ctx{lambda, TransportMode::Radiance};
    const LightSampler& lights = scene.light_sampler();

    double L = 0, beta = 1, eta_scale = 1;
    Ray ray = camera_ray;
    MediumStack media;
    // State of the previous vertex for MIS of emitter hits (the camera acts like a delta).
    bool prev_delta = true;
    double prev_bsdf_pdf = 0;
    LightSampleContext prev{ray.o, Vec3()};

    for (int depth = 0;; ++depth) {
        SurfaceInteraction si;
        const bool emitters_visible = !(m_settings.hide_emitters && depth == 0);
        if (!scene.intersect(ray, &si)) {
            if (emitters_visible) {
                for (const Light* light : scene.infinite_lights()) {
                    const double le = light->le_escaped(ray.d, lambda);
                    if (!(le > 0)) continue;
                    double w = 1;
                    if (m_nee && !prev_delta)
                        w = bsdf_hit_weight(prev_bsdf_pdf, lights.pmf(light) * light->pdf_li(prev, Vec3(), Vec3(), ray.d));
                    L += beta * w * le;
                }
            }
            break;
        }
        // Beer-Lambert along the segment just traced.
        beta *= media.transmittance(si.t, lambda);

        if (const Light* em = si.emitter(); em && emitters_visible) {
            const double le = em->le(si.p, si.n, -ray.d, lambda);
            if (le > 0) {
                double w = 1;
                if (m_nee && !prev_delta)
                    w = bsdf_hit_weight(prev_bsdf_pdf, lights.pmf(em) * em->pdf_li(prev, si.p, si.n, ray.d));
                L += beta * w * le;
            }
        }
        if (m_settings.max_depth >= 0 && depth + 1 >= m_settings.max_depth) break;
        const BSDF* bsdf = si.bsdf();
        if (!bsdf) break;

        if (m_nee && bsdf->is_smooth_sampled()) {
            L += beta * connect_to_light(scene, si, *bsdf, ctx, media, sampler);
        }

        const Vec3 wo = si.to_local(si.wo);
        const auto bs = bsdf->sample(ctx, wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || !(bs->weight > 0)) break;
        const Vec3 wi = si.to_world(bs->wi);
        beta *= bs->weight;
        prev_delta = bs->is_delta();
        prev_bsdf_pdf = bs->pdf;
        prev = {si.p, si.n};
        if ((bs->lobe & kTransmission) && bs->eta != 1.0) {
            media.cross(bsdf->interior_absorption(), dot(si.wo, si.ng) > 0);
            eta_scale *= sqr(bs->eta);
        }
        ray = scene.spawn_ray(si, wi);

        // Russian roulette on the throughput with the radiance compression of refraction undone.
        if (depth + 1 >= m_settings.rr_depth) {
            const double q = std::min(0.95, beta * eta_scale);
            if (!(sampler.next_1d() < q)) break;
            beta /= q;
        }
    }
    return L;
}

}  // namespace snell
