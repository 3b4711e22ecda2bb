#pragma once
// `mnee`: path tracing whose light connection is manifold next event estimation (paper Sec. 3),
// combined with BSDF sampling and with NEE at rough interface vertices by the power heuristic.
#include "integrators/path/path_tracer.h"
#include "manifold/light_point.h"
#include "manifold/manifold_vertex.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// What MNEE remembers per path beyond the path tracer: the refractive suffix since the last
/// vertex that connects to lights (for the MIS weights of Alg. 2).
struct MneePathState : PathState {
    RefractiveSuffix suffix;
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
/// The default surface_weight of solutions=unbiased (MneeSettings::surface_weight): a trial finds
/// a droplet's post-fold solution about one time in seven (mean 1 / p estimate 7.0 on the smooth
/// droplet's caustic), so its count multiplies its second moment by about 2 / p = 14; of 1, 0.3,
/// 0.1, 0.03, 0.01 and 0.003, 0.03 gave the lowest variance per second on both droplets'
/// caustics (docs/mnee.md).
inline constexpr double kSurfaceWeight = 0.03;

class MneeIntegrator : public PathTracer {
public:
    MneeIntegrator(const PathSettings& path, const MneeSettings& mnee) : PathTracer(path, true), m_mnee(mnee) {}
    SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler,
                       const SampledWavelengths& wl) const override {
        MneePathState state;
        return trace(ray, scene, sampler, wl, state);
    }
    std::string name() const override { return m_mnee.biased ? "mnee-biased" : "mnee"; }
    const MneeSettings& mnee_settings() const { return m_mnee; }
    static MneeSettings settings_from_props(const Props& props);
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

    /// q of MneeSettings::connect_probability for a light: 1 for lights BSDF sampling cannot hit.
    double connect_probability(const Light& light) const;

    MneeSettings m_mnee;
};

}  // namespace snell
