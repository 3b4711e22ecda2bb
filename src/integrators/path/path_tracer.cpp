#include "integrators/path/path_tracer.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "core/props.h"
#include "geometry/scene.h"
#include "integrators/mis.h"
#include "render/camera_sample.h"

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

std::unique_ptr<SampleTracer> PathTracer::prepare(const Scene&, const FilmSpec&, const RenderOptions&) const {
    return std::make_unique<RadianceTracer>(*this);
}

std::optional<LightSample> PathTracer::sample_light(const Scene& scene, const SurfaceInteraction& si,
                                                    const SampledWavelengths& wl, Sampler& sampler, const Light** light,
                                                    double* pmf, bool keep_dark) {
    *light = scene.light_sampler().sample(sampler.next_1d(), pmf);
    const Vec2 u = sampler.next_2d();
    if (!*light || !(*pmf > 0)) return std::nullopt;
    auto ls = (*light)->sample_li({si.p, si.n}, u, wl);
    if (!ls || !(ls->pdf > 0) || !(keep_dark || ls->Le.is_nonzero())) return std::nullopt;
    return ls;
}

SampledSpectrum PathTracer::nee_estimate(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                                         const PathState& state, const LightSample& ls, const SampledSpectrum& f,
                                         double pmf, double w) {
    // Unoccluded, so the shadow segment lies entirely in one medium: the current one, or the
    // one on the other side when the light is reached by refracting here (rough dielectrics).
    MediumStack media = state.media;
    if (dot(si.wo, si.ng) * dot(ls.wi, si.ng) < 0 && (bsdf.eta(ctx.hero()) != 1.0 || bsdf.interior_absorption()))
        media.cross(bsdf.interior_absorption(), dot(si.wo, si.ng) > 0);
    const SampledSpectrum tr = media.inside() ? media.transmittance(ls.dist, ctx.wl) : SampledSpectrum(1.0);
    return f * tr * ls.Le * (std::abs(dot(si.n, ls.wi)) * w / (pmf * ls.pdf));
}

double PathTracer::nee_weight(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                              const LightSample& ls, double pmf) {
    // Delta lights cannot be hit by BSDF sampling.
    if (ls.delta) return 1.0;
    return power_heuristic(pmf * ls.pdf, bsdf.pdf(ctx, si.to_local(si.wo), si.to_local(ls.wi)));
}

SampledSpectrum PathTracer::nee_connect(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                        const BSDFContext& ctx, const PathState& state, const LightSample& ls,
                                        double pmf) {
    const SampledSpectrum f = bsdf.eval(ctx, si.to_local(si.wo), si.to_local(ls.wi));
    if (f.is_zero()) return {};
    const Ray shadow = std::isinf(ls.dist) ? scene.spawn_ray(si, ls.wi) : scene.spawn_ray_to(si, ls.p);
    if (scene.occluded(shadow)) return {};
    return nee_estimate(si, bsdf, ctx, state, ls, f, pmf, nee_weight(si, bsdf, ctx, ls, pmf));
}

SampledSpectrum PathTracer::connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                             const BSDFContext& ctx, const PathState& state, Sampler& sampler) const {
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, si, ctx.wl, sampler, &light, &pmf);
    return ls ? nee_connect(scene, si, bsdf, ctx, state, *ls, pmf) : SampledSpectrum();
}

double PathTracer::emitter_hit_weight(const Scene& scene, const PathState& state, const Light& light, const Vec3& p,
                                      const Vec3& n, const Vec3& d, const BSDFContext& /*ctx*/) const {
    if (!m_nee || state.prev_delta) return 1.0;
    const double light_pdf = scene.light_sampler().pmf(&light) * light.pdf_li(state.prev, p, n, d);
    return power_heuristic(state.prev_bsdf_pdf, light_pdf);
}

void PathTracer::on_scatter(PathState& state, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                            const BSDFContext& /*ctx*/) const {
    state.prev_delta = bs.is_delta();
    state.prev_bsdf_pdf = bs.pdf;
    state.prev = {si.p, si.n};
    // Crossing into or out of a dielectric's interior (a thin sheet, eta 1 and no interior,
    // encloses nothing; an index-matched absorbing dielectric still does).
    if ((bs.lobe & kTransmission) && (bs.eta != 1.0 || bsdf.interior_absorption()))
        state.media.cross(bsdf.interior_absorption(), dot(si.wo, si.ng) > 0);
}

SampledSpectrum PathTracer::trace(const Ray& camera_ray, const Scene& scene, Sampler& sampler,
                                  const SampledWavelengths& wl, PathState& state) const {
    ++render_stats::paths;
    const BSDFContext ctx{wl, TransportMode::Radiance};

    SampledSpectrum L, beta(1.0);
    double eta_scale = 1;
    Ray ray = camera_ray;
    state.prev = {ray.o, Vec3()};

    SurfaceInteraction si;  // overwritten by every hit (a fresh one per bounce costs a 300-byte fill)
    for (int depth = 0;; ++depth) {
        state.depth = depth;
        const bool emitters_visible = !(m_settings.hide_emitters && depth == 0);
        if (!scene.intersect(ray, &si)) {
            if (emitters_visible) {
                for (const Light* light : scene.infinite_lights()) {
                    const SampledSpectrum le = light->le_escaped(ray.d, wl);
                    if (le.is_nonzero())
                        L += beta * le * emitter_hit_weight(scene, state, *light, Vec3(), Vec3(), ray.d, ctx);
                }
            }
            break;
        }
        // Beer-Lambert along the segment just traced.
        if (state.media.inside()) beta *= state.media.transmittance(si.t, wl);
        // The emitter's weight depends on the path *before* this vertex (it ends here), so
        // it is computed before the vertex is recorded.
        if (const Light* em = si.emitter(); em && emitters_visible) {
            const SampledSpectrum le = em->le(si.p, si.n, -ray.d, wl);
            if (le.is_nonzero()) L += beta * le * emitter_hit_weight(scene, state, *em, si.p, si.n, ray.d, ctx);
        }
        on_arrival(state, si, ray, ctx);
        if (m_settings.max_depth >= 0 && depth + 1 >= m_settings.max_depth) break;
        const BSDF* bsdf = si.bsdf();
        if (!bsdf) break;

        if (m_nee && bsdf->is_smooth_sampled()) L += beta * connect_to_light(scene, si, *bsdf, ctx, state, sampler);

        const Vec3 wo = si.to_local(si.wo);
        const auto bs = bsdf->sample(ctx, wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || bs->weight.is_zero()) break;
        BSDFSample bs_world = *bs;
        bs_world.wi = si.to_world(bs->wi);
        beta *= bs->weight;
        // A dispersive refraction: from here on the path exists for the hero alone.
        if (bs->hero_only && !state.hero_only) {
            beta = wl.hero_only(beta);
            state.hero_only = true;
        }
        on_scatter(state, si, *bsdf, bs_world, ctx);
        if ((bs->lobe & kTransmission) && bs->eta != 1.0) eta_scale *= sqr(bs->eta);
        ray = scene.spawn_ray(si, bs_world.wi);

        // Russian roulette on the throughput with the radiance compression of refraction undone.
        if (depth + 1 >= m_settings.rr_depth) {
            const double q = std::min(0.95, beta.max_component() * eta_scale);
            if (!(sampler.next_1d() < q)) break;
            beta /= q;
        }
    }
    return L;
}

}  // namespace snell
