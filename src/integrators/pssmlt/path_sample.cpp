#include "integrators/pssmlt/path_sample.h"

#include <algorithm>
#include <cmath>

#include "core/spectrum.h"
#include "core/stats.h"
#include "integrators/integrator.h"

namespace snell {

// Same conversion as render(): raster jitter (2D), then the wavelength (1D), then li().
PathSample evaluate(const Scene& scene, const PerspectiveCamera& camera, const Integrator& inner, const FilmSpec& spec,
                    Sampler& sampler) {
    const int w = spec.out_width(), h = spec.out_height();
    const Vec2 u = sampler.next_2d();
    PathSample s;
    s.x = std::min(w - 1, int(u.x * w));
    s.y = std::min(h - 1, int(u.y * h));
    const double u_lambda = sampler.next_1d();
    const double lambda = sample_visible_wavelength(u_lambda);
    const double pdf_lambda = visible_wavelength_pdf(lambda);
    s.raster = Vec2(spec.crop_x + u.x * w, spec.crop_y + u.y * h);
    const Ray ray = camera.generate_ray(s.raster);
    double L = inner.li(ray, scene, sampler, lambda);
    // Invalid estimates stay off the film (as in render()), counted by kind.
    Counters& c = thread_counters();
    if (std::isnan(L)) c.discarded_nan++, L = 0;
    else if (std::isinf(L)) c.discarded_inf++, L = 0;
    else if (L < 0) c.discarded_negative++, L = 0;
    if (L > 0 && pdf_lambda > 0) s.xyz = radiance_to_xyz(L, lambda, pdf_lambda);
    return s;
}

}  // namespace snell
