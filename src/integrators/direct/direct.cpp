#include "integrators/direct/direct.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "core/props.h"
#include "integrators/light_connection.h"
#include "integrators/mis.h"
#include "integrators/path/camera_walk.h"
#include "integrators/scatter.h"
#include "light/light.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

namespace snell {

DirectSettings DirectSettings::from_props(const Props& props) {
    DirectSettings s;
    const int64_t shading = props.get_int("shading_samples", 1);
    const int64_t e = props.get_int("emitter_samples", shading), b = props.get_int("bsdf_samples", shading);
    s.hide_emitters = props.get_bool("hide_emitters", false);
    s.hide_specular_emitters = props.get_bool("hide_specular_emitters", false);
    const auto check = [&](const char* name, int64_t v) {
        if (v < 0 || v > 4096) props.raise_param(name, std::string(name) + " must lie in [0, 4096]");
    };
    check("shading_samples", shading);
    check("emitter_samples", e);
    check("bsdf_samples", b);
    if (e + b == 0) props.raise_param("emitter_samples", "emitter_samples and bsdf_samples are both 0");
    s.emitter_samples = int(e);
    s.bsdf_samples = int(b);
    return s;
}

namespace {
PathSettings one_bounce(const DirectSettings& s) {
    PathSettings p;
    p.max_depth = 2;
    p.hide_emitters = s.hide_emitters;
    p.hide_specular_emitters = s.hide_specular_emitters;
    return p;
}
}  // namespace

DirectIntegrator::DirectIntegrator(const DirectSettings& s) : PathTracer(one_bounce(s), true, "direct"), m_direct(s) {}

SampleEstimate DirectIntegrator::radiance(const Ray& ray, const Scene& scene, Sampler& sampler,
                                          const SampledWavelengths& wl, PathObserver* /*observer*/) const {
    ++render_stats::paths;
    const BSDFContext ctx{wl, TransportMode::Radiance};
    SampleRadiance out;
    SurfaceInteraction si;
    if (!scene.intersect(ray, &si)) {
        if (!m_direct.hide_emitters)
            for (const Light* light : scene.infinite_lights())
                out.add(Technique::Emitted, light->le_escaped(ray.d, wl));
        return out.finish(wl);
    }
    if (const Light* em = si.emitter(); em && !m_direct.hide_emitters)
        out.add(Technique::Emitted, em->le(si.p, si.n, si.uv, -ray.d, wl));
    const BSDF* bsdf = si.bsdf();
    if (!bsdf) {
        return out.finish(wl);
    }
    const int ne = bsdf->is_smooth_sampled() ? m_direct.emitter_samples : 0, nb = m_direct.bsdf_samples;
    // Each technique's density weighted by its share of the samples (Veach's n_i p_i).
    const double frac_e = double(ne) / double(ne + nb), frac_b = double(nb) / double(ne + nb);
    const Vec3 wo = si.to_local(si.wo);
    const MediumStack none;

    for (int i = 0; i < ne; ++i) {
        const Light* light = nullptr;
        double pmf = 0;
        const auto ls = sample_light(scene, si, wl, sampler, &light, &pmf);
        if (ls)
            out.add(Technique::Nee,
                    nee_connect(scene, si, *bsdf, ctx.at(si), none, *ls, pmf, frac_e, frac_b) / double(ne));
    }

    for (int j = 0; j < nb; ++j) {
        const auto bs = bsdf->sample(ctx.at(si), wo, sampler.next_1d(), sampler.next_2d());
        if (!bs || bs->weight.is_zero()) continue;
        if (bs->is_delta() && m_direct.hide_specular_emitters) continue;  // camera, delta lobe, emitter
        Throughput tp;
        tp.scatter(*bs, wl, TransportMode::Radiance);
        const Vec3 d = si.to_world(bs->wi);
        const MediumStack media = medium_towards(none, si, *bsdf, d, ctx.hero());
        // The light's density for the same direction, if light sampling could have drawn it.
        const auto weight = [&](const Light& light, const Vec3& p, const Vec3& n) {
            if (bs->is_delta() || ne == 0) return 1.0;
            const double light_pdf = scene.light_sampler().pmf(&light) * light.pdf_li({si.p, si.n}, p, n, d);
            return power_heuristic(frac_b * bs->pdf, frac_e * light_pdf);
        };
        SurfaceInteraction hit;
        if (!scene.intersect(scene.spawn_ray(si, d), &hit)) {
            for (const Light* light : scene.infinite_lights())
                out.add(Technique::BsdfHit, tp.beta * light->le_escaped(d, wl) * (weight(*light, Vec3(), Vec3()) / nb));
            continue;
        }
        const Light* em = hit.emitter();
        if (!em) continue;
        const SampledSpectrum tr = media.inside() ? media.transmittance(hit.t, wl) : SampledSpectrum(1.0);
        out.add(Technique::BsdfHit,
                tp.beta * tr * em->le(hit.p, hit.n, hit.uv, -d, wl) * (weight(*em, hit.p, hit.n) / nb));
    }
    return out.finish(wl);
}

}  // namespace snell
