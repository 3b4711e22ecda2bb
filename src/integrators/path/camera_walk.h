#pragma once
// The camera random walk of the path-tracing family (pt, nee, mnee), whatever its light
// connection: trace the ray, attenuate it in the medium it crossed, sample the BSDF, update the
// throughput and the media, Russian roulette. Each integrator writes its own loop from these
// pieces and keeps its own MIS bookkeeping beside them.
#include <optional>

#include "bsdf/bsdf.h"
#include "core/medium_stack.h"
#include "geometry/interaction.h"
#include "integrators/path/path_settings.h"
#include "integrators/path/radiance_estimator.h"
#include "integrators/path/technique_stats.h"
#include "integrators/scatter.h"
#include "light/light.h"
#include "scene/caster_sampling.h"

namespace snell {

class Scene;
class Sampler;

/// One camera sample's radiance, and the same radiance by technique for the statistics.
class SampleRadiance {
public:
    void add(Technique t, const SampledSpectrum& v) {
        m_L += v;
        m_log.add(t, v);
    }
    /// Records the sample's techniques (TechniqueLog::record) and returns its radiance with the
    /// technique of its largest part.
    SampleEstimate finish(const SampledWavelengths& wl) const {
        const int largest = m_log.record(wl);
        return {m_L, largest};
    }

private:
    SampledSpectrum m_L;
    TechniqueLog m_log;
};

/// The previous scattering vertex, for the MIS weight of an emitter that BSDF sampling reaches
/// against NEE from that vertex.
struct PreviousVertex {
    bool delta = true;      ///< sampled from a delta lobe (or the camera)
    double bsdf_pdf = 0;    ///< solid-angle density of the direction sampled there
    LightSampleContext at;  ///< its position and normal

    void record(const SurfaceInteraction& si, const BSDFSample& bs) {
        delta = bs.is_delta();
        bsdf_pdf = bs.pdf;
        at = {si.p, si.n};
    }
    /// Power-heuristic weight of BSDF sampling against NEE for the emitter `light` at (p, n)
    /// reached along d (zero p and n for lights at infinity); 1 after a delta vertex.
    double emitter_weight(const Scene& scene, const Light& light, const Vec3& p, const Vec3& n, const Vec3& d) const;
};

class CameraWalk {
public:
    CameraWalk(const Scene& scene, const PathSettings& settings, const SampledWavelengths& wl, const Ray& camera_ray,
               PathObserver* observer)
        : ray(camera_ray),
          m_scene(&scene),
          m_settings(&settings),
          m_wl(wl),
          m_observer(observer),
          m_casters(scene, settings.caster_probability) {}

    /// Traces `ray` to its next vertex `si`, attenuated by the medium it crossed (Beer-Lambert),
    /// and tells the observer. False when the ray escapes.
    bool trace(SurfaceInteraction* si);
    /// Whether emitters count at this vertex: hide_emitters hides them from the camera alone,
    /// hide_specular_emitters where every vertex before this one scattered by a delta lobe.
    bool emitters_visible() const {
        if (depth == 0) return !m_settings->hide_emitters;
        return !(m_settings->hide_specular_emitters && m_specular_prefix);
    }
    /// Adds emitted radiance `le` reaching the current vertex with MIS weight `weight()`: to
    /// Technique::Emitted at the camera's own vertex, else to `by` (the technique that sampled
    /// the last direction).
    template <class Weight>
    void add_emission(SampleRadiance& out, Technique by, const SampledSpectrum& le, Weight&& weight) const {
        if (le.is_nonzero()) out.add(depth == 0 ? Technique::Emitted : by, tp.beta * le * weight());
    }
    /// Whether max_depth lets the path scatter at the current vertex.
    bool may_scatter() const { return !(m_settings->max_depth >= 0 && depth + 1 >= m_settings->max_depth); }
    /// How scatter() samples directions: BSDF sampling, mixed with caster sampling where it
    /// applies; every MIS weight reads its density (CasterSampling::pdf).
    const CasterSampling& directions() const { return m_casters; }
    /// Samples the BSDF at `si` (mixed with caster sampling) and moves on: the throughput, the media, the next `ray`,
    /// then Russian roulette. The sample with its direction in world space, or nothing when the path ends here
    /// (absorbed, or stopped by roulette).
    std::optional<BSDFSample> scatter(const SurfaceInteraction& si, const BSDF& bsdf, const BSDFContext& sctx,
                                      Sampler& sampler);

    int depth = 0;      ///< index of the current vertex (0: the camera ray's hit)
    Throughput tp;      ///< path throughput up to the current vertex
    MediumStack media;  ///< interiors the path is in
    Ray ray;            ///< the ray that reached (or will reach) the current vertex

private:
    const Scene* m_scene;
    const PathSettings* m_settings;
    SampledWavelengths m_wl;
    PathObserver* m_observer;
    bool m_specular_prefix = true;  ///< every vertex so far scattered by a delta lobe
    CasterSampling m_casters;
};

}  // namespace snell
