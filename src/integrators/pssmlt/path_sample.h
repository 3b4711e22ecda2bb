#pragma once
// A point of primary sample space evaluated by an ordinary per-sample estimator, with the
// dimension layout of render(): film position (2D, over the output window), wavelengths (2D),
// then the estimator's own numbers. The Metropolis integrators (pssmlt, erpt) share it, so a
// chain of either visits the same function of the same numbers.
#include "camera/camera.h"
#include "core/sampler.h"
#include "core/vector.h"

namespace snell {

class Scene;
class RadianceEstimator;

/// One evaluation of the inner estimator at the sampler's current primary sample.
struct PathSample {
    int x = 0, y = 0;  ///< output (crop) pixel containing `raster` (the nearest one in the filter margin)
    Vec2 raster;       ///< full-film raster position of the camera ray (pixels)
    Vec3 xyz;          ///< contribution, as render() accumulates it
    double target() const { return xyz.y; }  // luminance Y: the Metropolis target function
};

/// Draws the film position u in [0,1)^2 (over the output window) and the wavelength from
/// `sampler` (`spectral_samples` wavelengths), then runs `inner`. Invalid (NaN, infinite, negative) estimates become
/// zero and are counted, as in render().
PathSample evaluate(const Scene& scene, const Camera& camera, const RadianceEstimator& inner, int spectral_samples,
                    const FilmSpec& spec, Sampler& sampler);

}  // namespace snell
