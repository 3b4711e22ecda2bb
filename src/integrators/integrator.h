#pragma once
// Integrators own their render loop (pbrt-v4's Integrator::Render): most estimate one pixel
// sample at a time and share the tile loop (TileIntegrator); Metropolis places its samples
// anywhere on the film and brings its own loop (PSSMLT).
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "core/object.h"
#include "core/sampled_spectrum.h"
#include "render/renderer.h"
#include "render/sample_tracer.h"

namespace snell {

/// Upper bound on the bootstrap paths of the Metropolis integrators (pssmlt, erpt): each keeps
/// one double per path, so 2^24 is 128 MiB, 168 times Mitsuba's default of 100,000.
constexpr int64_t kMaxBootstrapSamples = int64_t(1) << 24;

class Scene;
class Props;

class Integrator : public Object {
public:
    /// Renders `film` of `scene`. Deterministic for (scene, options.seed, spp) whatever the
    /// thread count; never lets a NaN, infinite or negative estimate reach the film.
    virtual RenderResult render(const Scene& scene, const FilmSpec& film, const RenderOptions& options,
                                const std::atomic<bool>* cancel = nullptr) const = 0;
    /// The scene-file name of this technique ("path", "nee", ...).
    virtual std::string name() const = 0;
    /// Connects light paths to the camera (light tracing): needs a pinhole camera
    /// (Camera::pinhole()); the loader says so at the sensor otherwise.
    virtual bool needs_pinhole_camera() const { return false; }
    /// Wavelengths each path carries (`spectral_samples`; 1 is the paper's set-up).
    int spectral_samples() const { return m_spectral_samples; }
    void set_spectral_samples(int n) { m_spectral_samples = n; }

private:
    int m_spectral_samples = kSpectrumSamples;
};

/// An integrator whose estimates are per pixel sample, rendered by the shared tile loop
/// (render_tiles) through the tracer prepare() builds for each render.
class TileIntegrator : public Integrator {
public:
    RenderResult render(const Scene& scene, const FilmSpec& film, const RenderOptions& options,
                        const std::atomic<bool>* cancel = nullptr) const override;
    /// The per-render estimator: bootstrap estimates, the output window, tables. Called once
    /// per render, before the first sample.
    virtual std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                                  const RenderOptions& options) const = 0;
};

/// Renders with the integrator's own loop (the free-function form every caller uses).
inline RenderResult render(const Scene& scene, const Integrator& integrator, const FilmSpec& film,
                           const RenderOptions& options, const std::atomic<bool>* cancel = nullptr) {
    return integrator.render(scene, film, options, cancel);
}

/// Builds an integrator from its `type`; unknown types are a SceneError at props' location.
std::shared_ptr<Integrator> create_integrator(const Props& props);

}  // namespace snell
