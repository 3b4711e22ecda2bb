#include "integrators/path/path_tracer.h"

#include <cmath>

#include "bsdf/bsdf.h"
#include "integrators/light_connection.h"
#include "integrators/path/camera_walk.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

namespace snell {

std::unique_ptr<SampleTracer> PathTracer::prepare(const Scene&, const FilmSpec&, const RenderOptions&) const {
    return std::make_unique<RadianceTracer>(*this);
}

SampleEstimate PathTracer::radiance(const Ray& camera_ray, const Scene& scene, Sampler& sampler,
                                    const SampledWavelengths& wl, PathObserver* observer) const {
    ++render_stats::paths;
    const BSDFContext ctx{wl, TransportMode::Radiance};
    SampleRadiance out;
    CameraWalk walk(scene, m_settings, wl, camera_ray, observer);
    PreviousVertex prev;
    prev.at = {camera_ray.o, Vec3()};
    const auto bsdf_weight = [&](const Light& light, const Vec3& p, const Vec3& n) {
        return m_nee ? prev.emitter_weight(scene, light, p, n, walk.ray.d) : 1.0;
    };

    SurfaceInteraction si;  // overwritten by every hit (a fresh one per bounce costs a 300-byte fill)
    for (;; ++walk.depth) {
        if (!walk.trace(&si)) {
            if (walk.emitters_visible())
                for (const Light* light : scene.infinite_lights())
                    walk.add_emission(out, Technique::BsdfHit, light->le_escaped(walk.ray.d, wl),
                                      [&] { return bsdf_weight(*light, Vec3(), Vec3()); });
            break;
        }
        if (const Light* em = si.emitter(); em && walk.emitters_visible())
            walk.add_emission(out, Technique::BsdfHit, em->le(si.p, si.n, si.uv, -walk.ray.d, wl),
                              [&] { return bsdf_weight(*em, si.p, si.n); });
        const BSDF* bsdf = si.bsdf();
        if (!walk.may_scatter() || !bsdf) break;
        const BSDFContext sctx = ctx.at(si);  // textures are read at this vertex

        if (m_nee && bsdf->is_smooth_sampled()) {
            const Light* light = nullptr;
            double pmf = 0;
            if (const auto ls = sample_light(scene, si, wl, sampler, &light, &pmf))
                out.add(Technique::Nee,
                        walk.tp.beta * nee_connect(scene, si, *bsdf, sctx, walk.media, *ls, pmf, walk.directions()));
        }
        const auto bs = walk.scatter(si, *bsdf, sctx, sampler);
        if (!bs) break;
        prev.record(si, *bs);
    }
    return out.finish(wl);
}

}  // namespace snell
