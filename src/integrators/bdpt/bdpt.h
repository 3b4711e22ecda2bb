#pragma once
#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"

namespace snell {

/// Bidirectional path tracing (Veach & Guibas 1994; Veach's thesis ch. 10). Per camera sample
/// it traces a camera subpath z_0..z_{t-1} (z_0 the pinhole) in Radiance mode and a light
/// subpath y_0..y_{s-1} (y_0 on a finite light: area, point or spot) in Importance mode, and
/// sums every connection strategy (s >= 0, t >= 2) weighted by the power heuristic over all
/// strategies of the same path length, from per-vertex forward/reverse area densities.
///
/// Not implemented (weights are consistent with what is): the light-tracing strategy t = 1
/// (it needs film splatting, which the renderer lacks) is excluded from every MIS sum.
/// Lights at infinity (envmap, constant, directional) do not start light subpaths; paths ending
/// on them are estimated by the two unidirectional strategies only, s = 0 (escaping camera path)
/// and s = 1 (light sample from the last camera vertex), combined by the power heuristic as
/// `nee` does. Settings: max_depth (segments, -1 unbounded), rr_depth, hide_emitters.
class BdptIntegrator : public Integrator {
public:
    explicit BdptIntegrator(const PathSettings& settings) : m_settings(settings) {}
    double li(const Ray& ray, const Scene& scene, Sampler& sampler, double lambda) const override;
    std::string name() const override { return "bdpt"; }
    const PathSettings& settings() const { return m_settings; }

private:
    PathSettings m_settings;
};

}  // namespace snell
