#pragma once
#include "camera/camera.h"
#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"

namespace snell {

/// Bidirectional path tracing (Veach & Guibas 1994; Veach's thesis ch. 10). Per camera sample
/// it traces a camera subpath z_0..z_{t-1} (z_0 the pinhole) in Radiance mode and a light
/// subpath y_0..y_{s-1} (y_0 on any light, picked by power) in Importance mode, and
/// sums every connection strategy (s >= 0, t >= 1; not (1, 1), which only a light seen
/// directly would use and (0, 2) covers) weighted by the power heuristic over all strategies
/// of the same path length, from per-vertex forward/reverse area densities. The light-tracing
/// strategy t = 1 connects light vertices to the pinhole and splats them onto the film.
///
/// Lights at infinity (envmap, constant, directional) start light subpaths from a disk facing
/// the sampled direction; their vertices carry solid-angle densities, so escaping camera paths
/// and light samples of them are weighted against light subpaths like any other strategies.
/// Settings: max_depth (segments, -1 unbounded), rr_depth, hide_emitters. With
/// RenderOptions::debug_layers (`snell render --strategies`) each strategy's weighted
/// contribution also goes to its own film layer d<k>_s<s>_t<t> (path length k <= 6).
class BdptIntegrator : public TileIntegrator {
public:
    explicit BdptIntegrator(const PathSettings& settings) : m_settings(settings) {}
    /// The tracer for one render: camera importance over the film's output window, and the
    /// per-strategy layers when options.debug_layers is set.
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override;
    std::string name() const override { return "bdpt"; }
    bool needs_pinhole_camera() const override { return true; }
    const PathSettings& settings() const { return m_settings; }

private:
    PathSettings m_settings;
};

}  // namespace snell
