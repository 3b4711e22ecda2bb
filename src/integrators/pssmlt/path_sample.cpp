#include "integrators/pssmlt/path_sample.h"

#include <algorithm>
#include <cmath>

#include "core/spectrum.h"
#include "core/stats.h"
#include "integrators/camera_sample.h"

namespace snell {

// Same conversion as render(): raster jitter (2D), then the wavelength (1D), then li().
PathSample evaluate(const Scene& scene, const PerspectiveCamera& camera, const Integrator& inner, const FilmSpec& spec,
                    Sampler& sampler) {
    const int w = spec.out_width(), h = spec.out_height();
    const Vec2 u = sampler.next_2d();
    PathSample s;
    s.x = std::min(w - 1, int(u.x * w));
    s.y = std::min(h - 1, int(u.y * h));
    s.raster = Vec2(spec.crop_x + u.x * w, spec.crop_y + u.y * h);
    SplatList no_splats;
    s.xyz = trace_camera_sample(scene, camera, inner, s.raster, sampler.next_1d(), sampler, no_splats,
                                thread_counters()).xyz;
    return s;
}

}  // namespace snell
