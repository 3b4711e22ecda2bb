#pragma once
#include <optional>
#include <string>

#include "integrators/integrator.h"
#include "integrators/path/path_state.h"
#include "integrators/path/technique_stats.h"

namespace snell {

class Props;
class Scene;
struct SurfaceInteraction;
class BSDF;
struct BSDFContext;
struct BSDFSample;
class Light;
struct LightSample;

/// Settings shared by the path-tracing family (Mitsuba names).
struct PathSettings {
    int max_depth = -1;          ///< longest path in segments; -1: unbounded; 1: visible emitters only
    int rr_depth = 5;            ///< Russian roulette starts at this depth
    bool hide_emitters = false;  ///< directly visible emitters are black
    /// (max_sample_share) the film's outlier clamp (Film::set_max_sample_share): a pixel's
    /// largest sample carries at most this share of it. Biased; 0 (default): off. mnee's
    /// `biased` mode defaults it to 0.5 (MneeIntegrator::path_settings_from_props).
    double max_sample_share = 0;
    /// (clamp_spread) with the clamp, the widest disc (pixels) its light is spread over instead
    /// of being dropped (Film::set_max_sample_share); 0 (default): dropped. mnee's `biased` mode
    /// defaults it to kBiasedClampSpread.
    int clamp_spread = 0;
    /// The settings every integrator built on paths reads (bdpt, pssmlt and erpt too).
    static PathSettings from_props(const Props& props);
    /// from_props plus max_sample_share: the integrators whose samples the film clamps (the
    /// RadianceTracer family: pt, path, nee, mnee); elsewhere the parameter is not read.
    static PathSettings tracer_from_props(const Props& props);
};

/// Unidirectional path tracer. With `nee`, next event estimation combined with BSDF sampling by
/// the power heuristic: Mitsuba's and pbrt's `path`, the paper's NEE (also named `nee`).
/// Without, BSDF sampling alone: `pt`, the paper's pure path tracing (PT). MNEE derives from it
/// and replaces the light connection and the emitter-hit weights.
class PathTracer : public TileIntegrator {
public:
    PathTracer(const PathSettings& settings, bool nee, std::string name = "")
        : m_settings(settings), m_nee(nee), m_name(name.empty() ? (nee ? "nee" : "pt") : std::move(name)) {}
    /// Radiance arriving at the camera along `ray` at the wavelengths `wl` (nm). Thread-safe;
    /// all randomness from `sampler`.
    virtual SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler,
                               const SampledWavelengths& wl) const {
        PathState state;
        return trace(ray, scene, sampler, wl, state);
    }
    /// Stateless: the tracer calls li() for each camera sample.
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override;
    std::string name() const override { return m_name; }
    const PathSettings& settings() const { return m_settings; }

protected:
    /// The path tracer's loop; `state` is the derived integrator's (MNEE keeps more per path),
    /// so li() of a derived class only chooses the state type.
    SampledSpectrum trace(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                          PathState& state) const;
    /// Light connection from a vertex with a non-delta BSDF: adds its contributions (to be
    /// multiplied by the path throughput) to `out` by technique. Default: NEE with MIS.
    virtual void connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                  const BSDFContext& ctx, const PathState& state, Sampler& sampler,
                                  LightConnection& out) const;
    /// MIS weight of an emitter found by BSDF sampling at point p (normal n; zero for lights at
    /// infinity) along unit direction d from the previous vertex.
    virtual double emitter_hit_weight(const Scene& scene, const PathState& state, const Light& light, const Vec3& p,
                                      const Vec3& n, const Vec3& d, const BSDFContext& ctx) const;
    /// The technique credited with an emitter that BSDF sampling reached (statistics only).
    virtual Technique emitter_hit_technique(const PathState& /*state*/) const { return Technique::BsdfHit; }
    /// Called when the path arrives at `si` along `ray` (before connecting or scattering).
    virtual void on_arrival(PathState& /*state*/, const SurfaceInteraction& /*si*/, const Ray& /*ray*/,
                            const BSDFContext& /*ctx*/) const {}
    /// Called after the BSDF at `si` sampled `bs` (directions in world space: wi is the new one).
    virtual void on_scatter(PathState& state, const SurfaceInteraction& si, const BSDF& bsdf, const BSDFSample& bs,
                            const BSDFContext& ctx) const;

    PathSettings m_settings;
    bool m_nee;
    std::string m_name;  ///< the scene-file name it was created under
};

/// The path-tracing family's tracer: li() for every camera sample, no splats. Also how PSSMLT
/// and ERPT evaluate their inner estimator.
class RadianceTracer final : public SampleTracer {
public:
    explicit RadianceTracer(const PathTracer& estimator) : m_estimator(estimator) {}
    SampledSpectrum li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                             SplatList& /*splats*/) const override {
        return m_estimator.li(ray, scene, sampler, cs.wl);
    }
    double max_sample_share() const override { return m_estimator.settings().max_sample_share; }
    int clamp_spread() const override { return m_estimator.settings().clamp_spread; }
    std::vector<std::string> technique_names() const override { return path_technique_names(); }

private:
    const PathTracer& m_estimator;
};

}  // namespace snell
