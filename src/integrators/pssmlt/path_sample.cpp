#include "integrators/pssmlt/path_sample.h"

#include <algorithm>
#include <cmath>

#include "core/spectrum.h"
#include "integrators/path/path_tracer.h"
#include "render/camera_sample.h"

namespace snell {

// Same conversion as render(): raster jitter (2D), then the wavelengths (2D), then li().
PathSample evaluate(const Scene& scene, const Camera& camera, const RadianceEstimator& inner, int spectral_samples,
                    const FilmSpec& spec, Sampler& sampler) {
    const int w = spec.out_width(), h = spec.out_height();
    const Vec2 u = sampler.next_2d();
    PathSample s;
    // Film positions cover the output window grown by the filter margin, as camera samples do.
    const Vec2 o = spec.sample_origin(), e = spec.sample_extent();
    s.raster = Vec2(o.x + u.x * e.x, o.y + u.y * e.y);
    s.x = std::clamp(int(std::floor(s.raster.x)) - spec.crop_x, 0, w - 1);
    s.y = std::clamp(int(std::floor(s.raster.y)) - spec.crop_y, 0, h - 1);
    SplatList no_splats;
    const Vec2 centre(spec.crop_x + s.x + 0.5, spec.crop_y + s.y + 0.5);
    s.xyz = trace_camera_sample(scene, camera, RadianceTracer(inner), spectral_samples, centre, s.raster,
                                sampler.next_2d(), sampler, no_splats)
                .xyz;
    return s;
}

}  // namespace snell
