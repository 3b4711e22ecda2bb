#pragma once
// `erpt`: energy redistribution path tracing (Cline, Talbot & Egbert 2005). Every pixel sample
// is an ordinary path of the inner estimator (`nee` or `mnee`), the seed. Its energy e is then
// handed to short Metropolis chains started at the seed: floor(u + e / (M E_d)) chains of M
// mutations, each mutation depositing the quantum E_d (the deposition energy) on the film. A rare
// bright path (a caustic) thus spreads over the nearby paths that carry the same kind of light
// instead of landing in one pixel, while the expected deposit stays e (Cline et al.: the
// chains preserve the energy distribution they start from). Mutations are Kelemen small steps
// in primary sample space, as in `pssmlt`, and deposits are film splats.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "core/props.h"
#include "integrators/integrator.h"
#include "integrators/path/path_tracer.h"
#include "manifold/mnee_settings.h"

namespace snell {

class Shape;

/// Settings of `erpt` (scene-file names in parentheses).
struct ErptSettings {
    std::string sampler = "nee";  ///< (sampler) inner estimator: "nee" or "mnee"
    int mutations = 512;          ///< (mutations) M, mutations per chain (Hanika et al. 2015's ERPT)
    /// (deposition_energy) E_d, luminance Y deposited per mutation (in the units of a pixel
    /// sample's XYZ); 0: from the bootstrap, E_d = mean eligible Y / (M chains_per_sample).
    double deposition_energy = 0;
    /// (chains_per_sample) expected chains per pixel sample when E_d is automatic.
    double chains_per_sample = 0.1;
    int64_t bootstrap_samples = 20000;  ///< (bootstrap_samples) paths estimating the mean Y
    /// (max_chains) chains one seed may start; a brighter seed starts this many, each with
    /// quantum e / (max_chains M), so one extreme path cannot stall the render.
    int max_chains = 64;
    /// (shapes) comma-separated shape ids: only seeds whose camera subpath touches one of them
    /// are redistributed (the rest are plain path tracing), and their chains stay among such
    /// paths. Empty: every seed with e > 0.
    std::vector<std::string> shapes;
    double s1 = 1.0 / 1024, s2 = 1.0 / 64;  ///< small-step range (Kelemen's, as pssmlt; not in scene files)
    PathSettings path;                      ///< (max_depth, rr_depth, hide_emitters) of the inner estimator
    MneeSettings mnee;                      ///< MNEE parameters when sampler = "mnee"
    SourceLoc loc;                          ///< the <integrator> element, for errors found at prepare()
    static ErptSettings from_props(const Props& props);
};

/// ERPT for one render, built by ErptIntegrator::prepare(): the inner estimator (watching
/// `shapes`), the output window and E_d. li_splat() returns the seed's radiance when it is not
/// redistributed and 0 when it is, its chains' deposits going to `splats` (binned per pixel
/// with the film's filter). Deterministic for a seed: chains draw from streams seeded by the
/// pixel sample's own sampler.
class ErptTracer final : public SampleTracer {
public:
    ErptTracer(const ErptSettings& settings, std::shared_ptr<const RadianceEstimator> inner, const FilmSpec& film,
               int spectral_samples, double deposit, double mean_energy)
        : m_settings(settings),
          m_inner(std::move(inner)),
          m_film(film),
          m_spectral_samples(spectral_samples),
          m_deposit(deposit),
          m_mean_energy(mean_energy) {}
    SampleEstimate li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                            SplatList& splats) const override;
    bool splats() const override { return true; }
    /// E_d in use (0: no chains, plain path tracing).
    double deposition_energy() const { return m_deposit; }
    /// Bootstrap estimate of the mean luminance per sample of eligible seeds (0 if E_d was given).
    double mean_eligible_energy() const { return m_mean_energy; }

private:
    const ErptSettings& m_settings;
    std::shared_ptr<const RadianceEstimator> m_inner;
    FilmSpec m_film;
    int m_spectral_samples;
    double m_deposit, m_mean_energy;
};

class ErptIntegrator final : public TileIntegrator {
public:
    explicit ErptIntegrator(ErptSettings settings) : m_settings(std::move(settings)) {}
    /// Resolves `shapes` and sets E_d from a bootstrap (or the given deposition_energy).
    std::unique_ptr<SampleTracer> prepare(const Scene& scene, const FilmSpec& film,
                                          const RenderOptions& options) const override {
        return prepare_erpt(scene, film, options);
    }
    /// prepare() with its concrete type (E_d and the bootstrap's mean are readable).
    std::unique_ptr<ErptTracer> prepare_erpt(const Scene& scene, const FilmSpec& film,
                                             const RenderOptions& options) const;
    std::string name() const override { return "erpt"; }
    const ErptSettings& settings() const { return m_settings; }

private:
    ErptSettings m_settings;
};

}  // namespace snell
