#pragma once
// `hslt`: half-vector space light transport (Kaplanyan, Hanika & Dachsbacher, SIGGRAPH 2014), the
// last baseline of the MNEE paper's Fig. 5. Metropolis light transport over explicit paths
// (hslt_path.h) whose small steps perturb the path in half-vector space and solve it with the
// manifold walk, the ends held (hslt_mutation.h): half vectors, lens and light perturbations,
// with independent large steps by path tracing without light sampling (the MNEE paper's Sec. 4
// seeds its HSLT chains that way). Chains, bootstrap, expected-value splats and deterministic
// parallel chains are pssmlt's.
#include <atomic>
#include <cstdint>

#include "integrators/hslt/hslt_mutation.h"
#include "integrators/integrator.h"
#include "integrators/path/path_settings.h"
#include "render/renderer.h"

namespace snell {

/// Settings of `hslt` (scene-file names in parentheses).
struct HsltSettings {
    double large_step_probability = 0.3;  ///< (large_step_probability)
    /// Relative probabilities of the small steps (lens_probability, light_probability; the half
    /// vectors take the rest of 1).
    double lens_probability = 0.25, light_probability = 0.25;
    bool kelemen_weights = true;      ///< (kelemen_weights) as pssmlt's
    int64_t mutations_per_pixel = 0;  ///< (mutations_per_pixel) 0: the render options' spp
    /// (bootstrap_samples) MNEE paths estimating b, and large-step paths the chains start from.
    int64_t bootstrap_samples = 400000;
    /// (b_rate) MNEE paths per mutation that refine b when the chains are done, so that b's error
    /// falls as the render grows (0: b from the bootstrap alone).
    double b_rate = 0.25;
    int chains = 0;  ///< (chains) 0: 64, as pssmlt
    /// Longest path in segments (max_depth; HSLT needs a bound: 16 when the scene gives none).
    int max_depth = 16;
    bool hide_emitters = false;  ///< (hide_emitters)
    HsltMutationSettings mutation;
    static HsltSettings from_props(const Props& props);
};

RenderResult render_hslt(const Scene& scene, const HsltSettings& settings, int spectral_samples, const FilmSpec& film,
                         const RenderOptions& options, const std::atomic<bool>* cancel = nullptr);

class HsltIntegrator final : public Integrator {
public:
    explicit HsltIntegrator(HsltSettings settings) : m_settings(std::move(settings)) {}
    RenderResult render(const Scene& scene, const FilmSpec& film, const RenderOptions& options,
                        const std::atomic<bool>* cancel = nullptr) const override {
        return render_hslt(scene, m_settings, spectral_samples(), film, options, cancel);
    }
    std::string name() const override { return "hslt"; }
    /// x_0 is the pinhole: every perturbation holds it.
    bool needs_pinhole_camera() const override { return true; }
    const HsltSettings& settings() const { return m_settings; }

private:
    HsltSettings m_settings;
};

}  // namespace snell
