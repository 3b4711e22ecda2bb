#pragma once
// `pssmlt`: primary-sample-space Metropolis light transport (Kelemen et al. 2002) driving an
// ordinary per-sample estimator (`nee` or `mnee`) through a PrimarySampleSampler. Metropolis
// places samples anywhere on the film, so it renders with its own function, render_pssmlt,
// rather than through the per-pixel renderer.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"
#include "manifold/mnee_settings.h"
#include "render/renderer.h"

namespace snell {

/// Settings of `pssmlt` (scene-file names in parentheses).
struct PssmltSettings {
    std::string sampler = "nee";          ///< (sampler) inner estimator: "nee" or "mnee"
    double large_step_probability = 0.3;  ///< (large_step_probability) Kelemen's p_large
    /// (kelemen_weights) combine large steps as independent samples by the balance heuristic
    /// (Kelemen et al. 2002, Sec. 4); false: plain expected-value splats.
    bool kelemen_weights = true;
    /// (mutations_per_pixel) mutations in all chains together, per output pixel; 0: the
    /// render options' spp. Ignored in equal-time mode (RenderOptions::time_limit > 0).
    int64_t mutations_per_pixel = 0;
    int64_t bootstrap_samples = 100000;  ///< (bootstrap_samples) independent paths estimating b
    /// (chains) Markov chains; 0: 64, run `threads` at a time (so the image does not depend on
    /// the machine), in rounds in equal-time mode (metropolis_loop.h).
    int chains = 0;
    double s1 = 1.0 / 1024, s2 = 1.0 / 64;  ///< small-step range (Kelemen's defaults, not in scene files)
    PathSettings path;                      ///< (max_depth, rr_depth, hide_emitters) of the inner estimator
    MneeSettings mnee;                      ///< MNEE parameters when sampler = "mnee"
    static PssmltSettings from_props(const Props& props);
};

/// The inner per-sample estimator that the chains drive (`nee` or `mnee`).
std::shared_ptr<RadianceEstimator> make_pssmlt_inner(const PssmltSettings& settings);

/// Renders `film` with PSSMLT. The target function is the luminance Y of a sample's XYZ;
/// the normalisation b = E[Y] comes from `bootstrap_samples` independent paths, from which
/// the chain seeds are resampled proportionally to Y. Every proposal is splatted with the
/// expected-value weights (current 1 - a, proposed a); with kelemen_weights a large step also
/// counts as an independent sample (balance heuristic). The first two primary samples choose
/// the film position over the output (crop) window, the next two the wavelengths, as in render().
/// A pure function of (scene, settings, options.seed) when no time limit is set, whatever
/// the thread count: each chain owns its random stream and per-chain films are summed in order.
/// Each path carries `spectral_samples` wavelengths.
RenderResult render_pssmlt(const Scene& scene, const PssmltSettings& settings, int spectral_samples,
                           const FilmSpec& film, const RenderOptions& options,
                           const std::atomic<bool>* cancel = nullptr);

/// `type="pssmlt"`: Metropolis places its samples anywhere on the film, so it brings its own
/// render loop (render_pssmlt) instead of the tile loop.
class PssmltIntegrator final : public Integrator {
public:
    explicit PssmltIntegrator(PssmltSettings settings) : m_settings(std::move(settings)) {}
    RenderResult render(const Scene& scene, const FilmSpec& film, const RenderOptions& options,
                        const std::atomic<bool>* cancel = nullptr) const override {
        return render_pssmlt(scene, m_settings, spectral_samples(), film, options, cancel);
    }
    std::string name() const override { return m_settings.sampler == "mnee" ? "pssmlt(mnee)" : "pssmlt(nee)"; }
    const PssmltSettings& settings() const { return m_settings; }

private:
    PssmltSettings m_settings;
};

}  // namespace snell
