#pragma once
// The one pixel-sample pipeline that every render loop shares (the tile loop, PSSMLT's and
// ERPT's evaluations): wavelengths, camera ray, the integrator's estimate, sanitising, XYZ.
#include "camera/camera.h"
#include "core/stats.h"
#include "render/sample_tracer.h"

namespace snell {

/// Keeps an invalid estimate off the film (project promise 4): NaN, infinite or negative
/// values become 0 and are counted by kind in `c`.
double sanitize(double v, Counters& c);
/// The same for a sample's radiance: one invalid wavelength discards the whole sample.
SampledSpectrum sanitize(const SampledSpectrum& L, Counters& c);
/// Every value finite and non-negative.
bool is_valid_radiance(const SampledSpectrum& L);

struct TracedSample {
    CameraSample cs;
    SampledSpectrum L;  ///< sanitised radiance at cs.wl
    Vec3 xyz;           ///< its CIE XYZ estimate (cs.wl.to_xyz(L))
};

/// Draws the path's `spectral_samples` wavelengths from the pair `u_lambda`, traces the
/// camera ray through the full-film raster position `raster` (a sample of the pixel centred at
/// `pixel_centre`), and returns the sanitised estimate of tracer.li_splat() with its XYZ.
TracedSample trace_camera_sample(const Scene& scene, const PerspectiveCamera& camera, const SampleTracer& tracer,
                                 int spectral_samples, const Vec2& pixel_centre, const Vec2& raster,
                                 const Vec2& u_lambda, Sampler& sampler, SplatList& splats, Counters& counters);

}  // namespace snell
