#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/object.h"
#include "core/sampled_spectrum.h"
#include "core/sampler.h"
#include "core/vector.h"

namespace snell {

class Scene;
class Props;
struct FilmSpec;
struct RenderOptions;

/// What the renderer drew for one pixel sample before calling the integrator: the film
/// position (full-film raster, pixels) and the wavelengths with the uniform number behind them.
/// Integrators that re-evaluate or mutate the sample (ERPT) need these numbers.
struct CameraSample {
    Vec2 raster;
    double u_lambda = 0;
    SampledWavelengths wl;
};

/// A contribution that lands on the film somewhere other than the sample's own pixel (light
/// tracing in BDPT, ERPT's deposits). `raster` is a full-film position; `xyz` is already
/// divided by the wavelength density. The renderer adds splats in a fixed order and scales
/// them by 1 / (camera samples per pixel), so an estimator of pixel j is the sum of its
/// splats divided by the number of samples each pixel receives.
struct FilmSplat {
    Vec2 raster;
    Vec3 xyz;
    int layer = 0;  ///< 0: the image; > 0: a debug layer (BDPT's per-strategy images)
};
using SplatList = std::vector<FilmSplat>;

/// A per-sample estimator of radiance (Tungsten's "tracer"); the renderer owns tiles and
/// threads. `li` must be thread-safe (const) and draw all randomness from `sampler`.
class Integrator : public Object {
public:
    /// Radiance arriving at the camera along `ray` at the wavelengths `wl` (nm).
    virtual SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler,
                               const SampledWavelengths& wl) const = 0;
    /// The renderer's entry point: radiance along the camera sample's `ray`, plus any splats
    /// appended to `splats`. Default: li() without splats.
    virtual SampledSpectrum li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                                     SplatList& /*splats*/) const {
        return li(ray, scene, sampler, cs.wl);
    }
    /// True when li_splat() may produce splats; the renderer then merges them per tile group.
    virtual bool splats() const { return false; }
    /// Names of the debug layers 1, 2, ... that splats may target (empty: none).
    virtual std::vector<std::string> layer_names() const { return {}; }
    /// Called once by the renderer before the first sample (bootstrap estimates, tables).
    virtual void prepare(const Scene& /*scene*/, const FilmSpec& /*film*/, const RenderOptions& /*options*/) const {}
    /// The scene-file name of this technique ("path", "nee", ...).
    virtual std::string name() const = 0;
    /// Wavelengths each path carries (`spectral_samples`; 1 is the paper's set-up).
    int spectral_samples() const { return m_spectral_samples; }
    void set_spectral_samples(int n) { m_spectral_samples = n; }

private:
    int m_spectral_samples = kSpectrumSamples;
};

/// Builds an integrator from its `type`; unknown types are a SceneError at props' location.
std::shared_ptr<Integrator> create_integrator(const Props& props);

}  // namespace snell
