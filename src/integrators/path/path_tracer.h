#pragma once
#include <string>

#include "integrators/path/path_settings.h"
#include "integrators/path/radiance_estimator.h"

namespace snell {

class Scene;

/// Unidirectional path tracer. With `nee`, next event estimation combined with BSDF sampling by
/// the power heuristic: Mitsuba's and pbrt's `path`, the paper's NEE (also named `nee`).
/// Without, BSDF sampling alone: `pt`, the paper's pure path tracing (PT).
class PathTracer : public RadianceEstimator {
public:
    PathTracer(const PathSettings& settings, bool nee, std::string name = "")
        : m_settings(settings), m_nee(nee), m_name(name.empty() ? (nee ? "nee" : "pt") : std::move(name)) {}
    SampleEstimate radiance(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                            PathObserver* observer) const override;
    /// Stateless: the tracer calls li() for each camera sample.
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override;
    std::string name() const override { return m_name; }
    const PathSettings& settings() const override { return m_settings; }

protected:
    PathSettings m_settings;
    bool m_nee;
    std::string m_name;  ///< the scene-file name it was created under
};

}  // namespace snell
