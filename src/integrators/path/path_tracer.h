#pragma once
#include "integrators/integrator.h"

namespace snell {

class Props;
class Scene;
struct SurfaceInteraction;
class BSDF;
struct BSDFContext;
class MediumStack;

/// Settings shared by the path-tracing family (Mitsuba names).
struct PathSettings {
    int max_depth = -1;     ///< longest path in segments; -1: unbounded; 1: visible emitters only
    int rr_depth = 5;       ///< Russian roulette starts at this depth
    bool hide_emitters = false;  ///< directly visible emitters are black
    static PathSettings from_props(const Props& props);
};

/// Unidirectional path tracer. `path` samples only the BSDF (the paper's PT); `nee` adds next
/// event estimation combined with BSDF sampling by the power heuristic (the paper's NEE).
/// Later techniques (MNEE) derive from it and replace the light connection.
class PathTracer : public Integrator {
public:
    PathTracer(const PathSettings& settings, bool nee) : m_settings(settings), m_nee(nee) {}
    double li(const Ray& ray, const Scene& scene, Sampler& sampler, double lambda) const override;
    std::string name() const override { return m_nee ? "nee" : "path"; }
    const PathSettings& settings() const { return m_settings; }

protected:
    /// Light connection from a non-delta vertex (NEE with MIS). Returns the contribution
    /// (to be multiplied by the path throughput).
    virtual double connect_to_light(const Scene& scene, const SurfaceInteraction& si, const BSDF& bsdf,
                                    const BSDFContext& ctx, const MediumStack& media,
                                    Sampler& sampler) const;
    /// MIS weight of an emitter hit by BSDF sampling from `prev` with solid-angle density
    /// `bsdf_pdf` (light density computed inside). `light_pdf_sa` is the light sampling
    /// density of the hit point seen from prev.
    virtual double bsdf_hit_weight(double bsdf_pdf, double light_pdf_sa) const;

    PathSettings m_settings;
    bool m_nee;
};

}  // namespace snell
