#include "render/camera_sample.h"

#include <cmath>

namespace snell {

double sanitize(double v, Counters& c) {
    if (std::isnan(v)) {
        c.discarded_nan++;
        return 0;
    }
    if (std::isinf(v)) {
        c.discarded_inf++;
        return 0;
    }
    if (v < 0) {
        c.discarded_negative++;
        return 0;
    }
    return v;
}

SampledSpectrum sanitize(const SampledSpectrum& L, Counters& c) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (sanitize(L[i], c) != L[i]) return {};
    return L;
}

bool is_valid_radiance(const SampledSpectrum& L) {
    for (int i = 0; i < kSpectrumSamples; ++i)
        if (!(L[i] >= 0) || std::isinf(L[i])) return false;
    return true;
}

TracedSample trace_camera_sample(const Scene& scene, const PerspectiveCamera& camera, const SampleTracer& tracer,
                                 int spectral_samples, const Vec2& pixel_centre, const Vec2& raster,
                                 const Vec2& u_lambda, Sampler& sampler, SplatList& splats, Counters& counters) {
    TracedSample t;
    t.cs.raster = raster;
    t.cs.pixel_centre = pixel_centre;
    t.cs.u_lambda = u_lambda;
    t.cs.wl = SampledWavelengths::sample_visible(u_lambda, spectral_samples);
    const Ray ray = camera.generate_ray(raster);
    t.L = sanitize(tracer.li_splat(t.cs, ray, scene, sampler, splats), counters);
    t.xyz = t.cs.wl.to_xyz(t.L);
    return t;
}

}  // namespace snell
