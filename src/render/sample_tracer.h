#pragma once
// What the shared tile loop renders: a per-render estimator of one pixel sample (Tungsten's
// Tracer), built by a TileIntegrator's prepare() for one render.
#include <string>
#include <vector>

#include "core/sampled_spectrum.h"
#include "core/sampler.h"
#include "core/vector.h"
#include "render/pixel_rect.h"

namespace snell {

class Scene;

/// What the render loop drew for one pixel sample before calling the estimator: the film
/// position (full-film raster, pixels) and the wavelengths with the uniform number behind them.
/// Estimators that re-evaluate or mutate the sample (ERPT) need these numbers.
struct CameraSample {
    Vec2 raster;
    Vec2 pixel_centre;  ///< centre (full-film raster) of the pixel whose estimate this sample is
    Vec2 u_lambda;      ///< the pair behind `wl` (SampledWavelengths::sample_visible)
    SampledWavelengths wl;
};

/// A contribution that lands on the film somewhere other than the sample's own pixel (light
/// tracing in BDPT, ERPT's deposits). `raster` is a full-film position; `xyz` is already
/// divided by the wavelength density. The render loop adds splats in a fixed order, spreads
/// each over the pixels whose reconstruction filter covers `raster` (filter weights), and
/// scales them by 1 / (camera samples per pixel), so an estimator of pixel j is the sum of its
/// splats divided by the number of samples each pixel receives. A `binned` splat is already a
/// pixel's sum (filter applied by its producer) and goes to the pixel containing `raster`.
struct FilmSplat {
    Vec2 raster;
    Vec3 xyz;
    int layer = 0;        ///< 0: the image; > 0: a debug layer (BDPT's per-strategy images)
    bool binned = false;  ///< already filtered into the pixel that contains `raster`
};
using SplatList = std::vector<FilmSplat>;

/// One camera sample's estimate: its radiance and the technique (an index into the tracer's
/// technique_names(), -1: none) that delivered the largest part of its luminance. The render
/// loop keeps the technique of each pixel's largest sample, so that dominated pixels are counted
/// by the technique behind them (issue 10) in every render, not only in an instrumented build.
struct SampleEstimate {
    SampleEstimate() = default;
    SampleEstimate(const SampledSpectrum& radiance, int by = -1) : L(radiance), technique(by) {}  // NOLINT: implicit
    SampledSpectrum L;
    int technique = -1;
};

/// The estimator of one pixel sample for one render. Thread-safe (const) while rendering; all
/// randomness comes from `sampler`.
class SampleTracer {
public:
    virtual ~SampleTracer() = default;
    /// Radiance along the camera sample's `ray` at cs.wl, plus any splats appended to `splats`.
    virtual SampleEstimate li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                                    SplatList& splats) const = 0;
    /// True when li_splat() may produce splats; the render loop then merges them per tile group.
    virtual bool splats() const { return false; }
    /// Names of the debug layers 1, 2, ... that splats may target (empty: none).
    virtual std::vector<std::string> layer_names() const { return {}; }
    /// The film's outlier clamp (apply_outlier_clamp, camera/outlier_clamp.h) for this estimator; 0: none.
    virtual double max_sample_share() const { return 0; }
    /// The clamp's spread radius in pixels (apply_outlier_clamp, camera/outlier_clamp.h); 0: the clamped light
    /// is dropped.
    virtual int clamp_spread() const { return 0; }
    /// Names of the techniques li_splat() reports in SampleEstimate::technique (empty: none).
    virtual std::vector<std::string> technique_names() const { return {}; }
    /// Called by the render loop on one thread between passes, once every pixel holds
    /// `samples_per_pixel` samples: a tracer that learns from its first samples (MNEE's
    /// ConnectionAllocation) changes its estimator here, never while a pass runs.
    virtual void end_pass(uint64_t /*samples_per_pixel*/) {}

    // A tracer that learns from a pilot (its first samples of every pixel) needs the pilot's
    // samples whatever part of the frame a process renders (issue 27): a crop, a sample range
    // or an MPI rank's tiles. The render loop renders the pilot over pilot_window() even where
    // it adds nothing to the film, and sums pilot_state() over MPI ranks before end_pass().
    /// True while the tracer is still learning (its estimator changes in a later end_pass()).
    virtual bool learning() const { return false; }
    /// The samples per pixel its pilot takes (0: no pilot).
    virtual uint64_t pilot_samples() const { return 0; }
    /// The pixels (output window) whose pilot samples the estimator of `crop` depends on.
    virtual void pilot_window(int& x0, int& y0, int& x1, int& y1) const { (void)x0, (void)y0, (void)x1, (void)y1; }
    /// Pixels outside `window` (the pilot window) whose pilot samples every part of the frame
    /// depends on (MNEE's lattice of regions that learn the image's price of work): rendered in
    /// the pilot and added to no film.
    virtual std::vector<PixelRect> pilot_extra(const PixelRect& window) const {
        (void)window;
        return {};
    }
    /// What the pilot recorded, as doubles that are zero for pixels this process did not render,
    /// so that summing over processes is exact; set_pilot_state() puts the sum back.
    virtual std::vector<double> pilot_state() const { return {}; }
    virtual void set_pilot_state(const std::vector<double>& /*state*/) {}
};

}  // namespace snell
