#include "render/camera_sample.h"

#include <cmath>

namespace snell {

namespace render_stats {
StatCounter paths{"render.paths", "camera paths traced"};
StatCounter discarded_nan{"render.discarded_nan", "samples dropped because they were NaN"};
StatCounter discarded_inf{"render.discarded_inf", "samples dropped because they were infinite"};
StatCounter discarded_negative{"render.discarded_negative", "samples dropped because they were negative"};
}  // namespace render_stats

double sanitize(double v) {
    if (std::isnan(v)) {
        ++render_stats::discarded_nan;
        return 0;
    }
    if (std::isinf(v)) {
        ++render_stats::discarded_inf;
        return 0;
    }
    if (v < 0) {
        ++render_stats::discarded_negative;
        return 0;
    }
    return v;
}

SampledSpectrum sanitize(const SampledSpectrum& L) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (sanitize(L[i]) != L[i]) return {};
    return L;
}

bool is_valid_radiance(const SampledSpectrum& L) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (!(L[i] >= 0) || std::isinf(L[i])) return false;
    return true;
}

TracedSample trace_camera_sample(const Scene& scene, const Camera& camera, const SampleTracer& tracer,
                                 int spectral_samples, const Vec2& pixel_centre, const Vec2& raster,
                                 const Vec2& u_lambda, Sampler& sampler, SplatList& splats) {
    TracedSample t;
    t.cs.raster = raster;
    t.cs.pixel_centre = pixel_centre;
    t.cs.u_lambda = u_lambda;
    t.cs.wl = SampledWavelengths::sample_visible(u_lambda, spectral_samples);
    const Ray ray = camera.generate_ray(raster, camera.has_lens() ? sampler.next_2d() : Vec2(0.5, 0.5));
    const SampleEstimate e = tracer.li_splat(t.cs, ray, scene, sampler, splats);
    t.L = sanitize(e.L);
    t.xyz = t.cs.wl.to_xyz(t.L);
    t.technique = e.technique;
    return t;
}

}  // namespace snell
