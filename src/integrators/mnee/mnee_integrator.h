#pragma once
// `mnee`: path tracing whose light connection is manifold next event estimation (paper Sec. 3),
// combined with BSDF sampling and with NEE at rough interface vertices by the power heuristic.
#include "integrators/path/path_settings.h"
#include "integrators/path/radiance_estimator.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// The biased mode's outlier clamp (apply_outlier_clamp, camera/outlier_clamp.h): the largest sample of a pixel
/// carries at most half of it. The fireflies that remain after Sec. 3.5's rule are MNEE's own
/// (a fold's penumbra, rare solutions in a lens's aberration halo; docs/mnee.md), which no rule
/// on the paths can tell from the caustic; the clamp is relative to the pixel, so scale-free.
inline constexpr double kBiasedMaxSampleShare = 0.5;
/// ... and the light the clamp takes is spread over discs of up to this many pixels rather than
/// dropped (apply_outlier_clamp, camera/outlier_clamp.h): a caustic's dim halo, which at a few samples per pixel
/// is all rare bright samples, keeps its light (docs/mnee.md, "Biased mode").
inline constexpr int kBiasedClampSpread = 8;

/// `mnee`'s default caster_probability (PathSettings; scene/caster_sampling.h): three quarters
/// of the directions at a diffuse vertex in a caster's shadow aim at the glass. Why this share,
/// and how 0.5 and 0.9 fared on the caustic gallery: docs/experiments.md, "Caster sampling in
/// the casters' shadows" and "The default over three seeds".
inline constexpr double kMneeCasterProbability = 0.75;

/// The loop of one camera sample is MneePath's (mnee_path.h); the integrator holds the settings
/// and builds the per-render tracer, which owns the connection allocation.
class MneeIntegrator : public RadianceEstimator {
public:
    MneeIntegrator(const PathSettings& path, const MneeSettings& mnee) : m_settings(path), m_mnee(mnee) {}
    /// One camera sample at MneeSettings::connect_probability (PSSMLT's and ERPT's inner
    /// estimator; the tile loop goes through prepare()'s tracer).
    SampleEstimate radiance(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                            PathObserver* observer) const override;
    /// The per-render tracer: with a learned allocation it learns q per region from its pilot
    /// samples; otherwise every sample runs at connect_probability.
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override;
    std::string name() const override { return m_mnee.biased ? "mnee-biased" : "mnee"; }
    const PathSettings& settings() const override { return m_settings; }
    const MneeSettings& mnee_settings() const { return m_mnee; }
    /// The path tracer's settings; `biased` defaults max_sample_share to 0.5, so that no single
    /// sample carries more than half of a pixel (docs/mnee.md, "Biased mode").
    static PathSettings path_settings_from_props(const Props& props);

private:
    PathSettings m_settings;
    MneeSettings m_mnee;
};

}  // namespace snell
