#pragma once
// Mitsuba's `direct` integrator: direct illumination only. Emission seen by the camera, plus, at
// the first surface, `emitter_samples` light samples and `bsdf_samples` BSDF samples combined
// by the power heuristic over their sample counts (Veach 1997, Sec. 9.2.4). No further bounces:
// glass shows the lights it reflects or refracts directly, not the scene behind it.
#include "integrators/path/path_tracer.h"

namespace snell {

struct DirectSettings {
    int emitter_samples = 1;              ///< (emitter_samples; shading_samples sets both)
    int bsdf_samples = 1;                 ///< (bsdf_samples)
    bool hide_emitters = false;           ///< (hide_emitters)
    bool hide_specular_emitters = false;  ///< (hide_specular_emitters) emitters seen through a delta lobe
    static DirectSettings from_props(const Props& props);
};

class DirectIntegrator : public PathTracer {
public:
    explicit DirectIntegrator(const DirectSettings& s);
    /// (`observer` is not told: `direct` is nobody's inner estimator.)
    SampleEstimate radiance(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                            PathObserver* observer) const override;

private:
    DirectSettings m_direct;
};

}  // namespace snell
