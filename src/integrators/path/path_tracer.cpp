#include "integrators/path/path_tracer.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "core/props.h"
#include "integrators/light_connection.h"
#include "integrators/mis.h"
#include "integrators/scatter.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

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

PathSettings PathSettings::tracer_from_props(const Props& props) {
    PathSettings s = from_props(props);
    s.max_sample_share = props.get_float("max_sample_share", 0.0);
    if (!(s.max_sample_share >= 0 && s.max_sample_share < 1))
        props.raise_param("max_sample_share", "must lie in [0, 1) (0: no clamp)");
    const int64_t spread = props.get_int("clamp_spread", 0);
    if (spread < 0 || spread > 255)
        props.raise_param("clamp_spread", "must lie in [0, 255] pixels (0: the clamped light is dropped)");
    s.clamp_spread = int(spread);
    return s;
}

std::unique_ptr<SampleTracer> PathTracer::prepare(const Scene&, const FilmSpec&, const RenderOptions&) const {
    return std::make_unique<RadianceTracer>(*this);
}

void PathTracer::connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                  const BSDFContext& ctx, const PathState& state, Sampler& sampler,
                                  LightConnection& out) const {
    const Light* light = nullptr;
    double pmf = 0;
    const auto ls = sample_light(scene, si, ctx.wl, sampler, &light, &pmf);
    if (ls) out.add(Technique::Nee, nee_connect(scene, si, bsdf, ctx, state.media, *ls, pmf));
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
    if (crosses_interior(bsdf, bs)) cross_interface(state.media, si, bsdf);
}

SampledSpectrum PathTracer::trace(const Ray& camera_ray, const Scene& scene, Sampler& sampler,
                                  const SampledWavelengths& wl, PathState& state) const {
    ++render_stats::paths;
    const BSDFContext ctx{wl, TransportMode::Radiance};

    SampledSpectrum L;
    TechniqueLog log;  // the same radiance by technique, for the statistics
    const auto add = [&](Technique t, const SampledSpectrum& v) {
        L += v;
        log.add(t, v);
    };
    Throughput tp;
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
                    state.emitter_value = tp.beta * le;
                    if (le.is_nonzero())
                        add(depth == 0 ? Technique::Emitted : emitter_hit_technique(state),
                            tp.beta * le * emitter_hit_weight(scene, state, *light, Vec3(), Vec3(), ray.d, ctx));
                }
            }
            break;
        }
        // Beer-Lambert along the segment just traced.
        if (state.media.inside()) tp.beta *= state.media.transmittance(si.t, wl);
        // The emitter's weight depends on the path *before* this vertex (it ends here), so
        // it is computed before the vertex is recorded.
        if (const Light* em = si.emitter(); em && emitters_visible) {
            const SampledSpectrum le = em->le(si.p, si.n, si.uv, -ray.d, wl);
            state.emitter_value = tp.beta * le;
            if (le.is_nonzero())
                add(depth == 0 ? Technique::Emitted : emitter_hit_technique(state),
                    tp.beta * le * emitter_hit_weight(scene, state, *em, si.p, si.n, ray.d, ctx));
        }
        on_arrival(state, si, ray, ctx);
        const BSDFContext sctx = ctx.at(si);  // textures are read at this vertex
        if (m_settings.max_depth >= 0 && depth + 1 >= m_settings.max_depth) break;
        const BSDF* bsdf = si.bsdf();
        if (!bsdf) break;

        if (m_nee && bsdf->is_smooth_sampled()) {
            state.beta = tp.beta;
            LightConnection c;
            connect_to_light(scene, si, *bsdf, sctx, state, sampler, c);
            for (int t = 0; t < kTechniqueCount; ++t)
                if (c.by[size_t(t)].is_nonzero()) add(Technique(t), tp.beta * c.by[size_t(t)]);
        }

        const Vec3 wo = si.to_local(si.wo);
        const auto bs = bsdf->sample(sctx, wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || bs->weight.is_zero()) break;
        BSDFSample bs_world = *bs;
        bs_world.wi = si.to_world(bs->wi);
        tp.scatter(*bs, wl, TransportMode::Radiance);
        state.hero_only = tp.hero_only;  // the light connections of derived integrators read it
        on_scatter(state, si, *bsdf, bs_world, sctx);
        ray = scene.spawn_ray(si, bs_world.wi);
        if (depth + 1 >= m_settings.rr_depth && !tp.survives_roulette(sampler.next_1d())) break;
    }
    log.record(wl);
    return L;
}

}  // namespace snell
