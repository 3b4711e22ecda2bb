#pragma once
// The one pixel-sample pipeline that every render loop shares (the tile loop, PSSMLT's and
// ERPT's evaluations): wavelengths, camera ray, the integrator's estimate, sanitising, XYZ.
#include "camera/camera.h"
#include "core/stats.h"
#include "render/sample_tracer.h"

namespace snell {

// Counts of every render loop (core/stats.h). Paths are counted by the integrators' tracers,
// one per camera path they trace; discarded samples by sanitize().
namespace render_stats {
extern StatCounter paths;               ///< "render.paths": camera paths traced
extern StatCounter discarded_nan;       ///< "render.discarded_nan": samples dropped as NaN
extern StatCounter discarded_inf;       ///< "render.discarded_inf": samples dropped as infinite
extern StatCounter discarded_negative;  ///< "render.discarded_negative": samples dropped as negative
}  // namespace render_stats

/// Keeps an invalid estimate off the film (project promise 4): NaN, infinite or negative
/// values become 0 and are counted by kind (render_stats::discarded_*).
double sanitize(double v);
/// The same for a sample's radiance: one invalid wavelength discards the whole sample.
SampledSpectrum sanitize(const SampledSpectrum& L);
/// Every value finite and non-negative.
bool is_valid_radiance(const SampledSpectrum& L);

struct TracedSample {
    CameraSample cs;
    SampledSpectrum L;   ///< sanitised radiance at cs.wl
    Vec3 xyz;            ///< its CIE XYZ estimate (cs.wl.to_xyz(L))
    int technique = -1;  ///< the estimate's technique (SampleEstimate; -1: none)
};

/// Draws the path's `spectral_samples` wavelengths from the pair `u_lambda`, traces the
/// camera ray through the full-film raster position `raster` (a sample of the pixel centred at
/// `pixel_centre`), and returns the sanitised estimate of tracer.li_splat() with its XYZ.
TracedSample trace_camera_sample(const Scene& scene, const Camera& camera, const SampleTracer& tracer,
                                 int spectral_samples, const Vec2& pixel_centre, const Vec2& raster,
                                 const Vec2& u_lambda, Sampler& sampler, SplatList& splats);

}  // namespace snell
