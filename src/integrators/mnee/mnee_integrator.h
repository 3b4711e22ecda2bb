#pragma once
// `mnee`: path tracing whose light connection is manifold next event estimation (paper Sec. 3),
// combined with BSDF sampling and with NEE at rough interface vertices by the power heuristic.
#include "integrators/mnee/connection_allocation.h"
#include "integrators/path/path_tracer.h"
#include "manifold/light_point.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// What MNEE remembers per path beyond the path tracer: the refractive suffix since the last
/// vertex that connects to lights (for the MIS weights of Alg. 2).
struct MneePathState : PathState {
    RefractiveSuffix suffix;
    /// q of this camera sample (its region's, ConnectionAllocation); < 0: connect_probability.
    double q = -1;
    PilotSample* pilot = nullptr;  ///< the allocation's pilot records this sample here
};

/// The biased mode's outlier clamp (Film::set_max_sample_share): the largest sample of a pixel
/// carries at most half of it. The fireflies that remain after Sec. 3.5's rule are MNEE's own
/// (a fold's penumbra, rare solutions in a lens's aberration halo; docs/mnee.md), which no rule
/// on the paths can tell from the caustic; the clamp is relative to the pixel, so scale-free.
inline constexpr double kBiasedMaxSampleShare = 0.5;
/// ... and the light the clamp takes is spread over discs of up to this many pixels rather than
/// dropped (Film::set_max_sample_share): a caustic's dim halo, which at a few samples per pixel
/// is all rare bright samples, keeps its light (docs/mnee.md, "Biased mode").
inline constexpr int kBiasedClampSpread = 8;

class MneeIntegrator : public PathTracer {
public:
    MneeIntegrator(const PathSettings& path, const MneeSettings& mnee) : PathTracer(path, true), m_mnee(mnee) {}
    SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler,
                       const SampledWavelengths& wl) const override {
        MneePathState state;
        return trace(ray, scene, sampler, wl, state);
    }
    /// One camera sample with the caller's state (its q and pilot record).
    SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                       MneePathState& state) const {
        return trace(ray, scene, sampler, wl, state);
    }
    /// With a learned allocation, a tracer that learns q per region from its pilot samples;
    /// otherwise the path tracer's.
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override;
    std::string name() const override { return m_mnee.biased ? "mnee-biased" : "mnee"; }
    const MneeSettings& mnee_settings() const { return m_mnee; }
    /// The path tracer's settings; `biased` defaults max_sample_share to 0.5, so that no single
    /// sample carries more than half of a pixel (docs/mnee.md, "Biased mode").
    static PathSettings path_settings_from_props(const Props& props);

protected:
    void connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& ctx,
                          const PathState& state, Sampler& sampler, LightConnection& out) const override;
    Technique emitter_hit_technique(const PathState& state) const override;
    double emitter_hit_weight(const Scene& scene, const PathState& state, const Light& light, const Vec3& p,
                              const Vec3& n, const Vec3& d, const BSDFContext& ctx) const override;
    void on_arrival(PathState& state, const SurfaceInteraction& si, const Ray& ray,
                    const BSDFContext& ctx) const override;
    void on_scatter(PathState& state, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                    const BSDFContext& ctx) const override;

private:
    /// NEE at a rough refractive vertex x_k, weighted against BSDF sampling and against MNEE
    /// from x_b when the path so far is x_b followed by refractions.
    SampledSpectrum connect_at_interface(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                         const BSDFContext& ctx, const PathState& state, Sampler& sampler) const;

    /// Whether the manifold technique can produce a path whose suffix after x_b is `s` (the
    /// last vertex refracting or not): refractions only, or any suffix when its surface seeds
    /// also reflect (solutions=all or unbiased with reflections).
    bool covers(const RefractiveSuffix& s, bool last_refracts) const;

    /// q for a light on this sample's path: the sample's (its region's) or
    /// MneeSettings::connect_probability; 1 for lights BSDF sampling cannot hit.
    double connect_probability(const Light& light, const PathState& state) const;
    /// MNEE's density of the BSDF-sampled suffix `s` ending at the light point (p, n), or 0 when
    /// the technique cannot produce it or q is 0; its work goes to the pilot's record.
    double mnee_density(const Scene& scene, const MneePathState& state, bool last_refracts, const Light& light,
                        double pmf, const Vec3& p, const Vec3& n, double q, double lambda) const;

    MneeSettings m_mnee;
};

}  // namespace snell
