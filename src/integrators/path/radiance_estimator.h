#pragma once
// The integrators that estimate radiance along a camera ray one path at a time (pt, nee, mnee,
// direct), as the tile loop, PSSMLT and ERPT use them: PSSMLT and ERPT take either `nee` or
// `mnee` as their inner estimator through this interface.
#include <memory>

#include "integrators/integrator.h"
#include "integrators/path/path_settings.h"
#include "integrators/path/technique_stats.h"

namespace snell {

struct SurfaceInteraction;

/// Told of every vertex of a camera subpath (the surface hit by the camera ray and by each
/// BSDF-sampled ray; not light samples, not manifold walks). ERPT's `shapes` option watches
/// the shapes a path touches with it.
class PathObserver {
public:
    virtual ~PathObserver() = default;
    virtual void arrived(const SurfaceInteraction& si) = 0;
};

class RadianceEstimator : public TileIntegrator {
public:
    /// Radiance arriving at the camera along `ray` at the wavelengths `wl` (nm). Thread-safe;
    /// all randomness from `sampler`.
    SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl) const {
        return radiance(ray, scene, sampler, wl, nullptr).L;
    }
    /// li() telling `observer` (when not null) of every camera-subpath vertex, with the technique
    /// that delivered the largest part of the sample (technique_stats.h).
    virtual SampleEstimate radiance(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                                    PathObserver* observer) const = 0;
    virtual const PathSettings& settings() const = 0;
};

/// The path-tracing family's tracer: li() for every camera sample, no splats. Also how PSSMLT
/// and ERPT evaluate their inner estimator.
class RadianceTracer final : public SampleTracer {
public:
    explicit RadianceTracer(const RadianceEstimator& estimator) : m_estimator(estimator) {}
    SampleEstimate li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                            SplatList& /*splats*/) const override {
        return m_estimator.radiance(ray, scene, sampler, cs.wl, nullptr);
    }
    double max_sample_share() const override { return m_estimator.settings().max_sample_share; }
    int clamp_spread() const override { return m_estimator.settings().clamp_spread; }
    std::vector<std::string> technique_names() const override { return path_technique_names(); }

private:
    const RadianceEstimator& m_estimator;
};

}  // namespace snell
