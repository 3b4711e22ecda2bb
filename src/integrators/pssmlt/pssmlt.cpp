#include "integrators/pssmlt/pssmlt.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/distribution.h"
#include "core/props.h"
#include "core/spectrum.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/pssmlt/metropolis_loop.h"
#include "integrators/pssmlt/path_sample.h"
#include "integrators/pssmlt/primary_sample_sampler.h"
#include "scene/scene.h"

namespace snell {

PssmltSettings PssmltSettings::from_props(const Props& props) {
    PssmltSettings s;
    s.sampler = props.get_string("sampler", s.sampler);
    if (s.sampler != "nee" && s.sampler != "mnee")
        props.raise("pssmlt: sampler must be 'nee' or 'mnee', not '" + s.sampler + "'");
    s.large_step_probability = props.get_float("large_step_probability", s.large_step_probability);
    if (!(s.large_step_probability >= 0 && s.large_step_probability <= 1))
        props.raise("pssmlt: large_step_probability must lie in [0, 1]");
    s.kelemen_weights = props.get_bool("kelemen_weights", s.kelemen_weights);
    parse_chain_counts(props, "pssmlt", 1, &s.mutations_per_pixel, &s.bootstrap_samples, &s.chains);
    s.path = PathSettings::from_props(props);
    if (s.sampler == "mnee") s.mnee = MneeSettings::from_props(props);
    return s;
}

std::shared_ptr<RadianceEstimator> make_pssmlt_inner(const PssmltSettings& s) {
    if (s.sampler == "mnee") return std::make_shared<MneeIntegrator>(s.path, s.mnee);
    return std::make_shared<PathTracer>(s.path, true);
}

namespace {

// Stream identities: bootstrap path i and chain c never share a PCG32 stream.
uint64_t bootstrap_seed(uint64_t seed, uint64_t i) { return mix_bits(mix_bits(seed) ^ (i * 2 + 1)); }
uint64_t chain_seed(uint64_t seed, uint64_t c) { return mix_bits(mix_bits(seed + 0x632be59bd9b4e019ULL) ^ (c * 2)); }

}  // namespace

RenderResult render_pssmlt(const Scene& scene, const PssmltSettings& settings, int spectral_samples,
                           const FilmSpec& spec, const RenderOptions& opt, const std::atomic<bool>* cancel) {
    const Camera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");
    MetropolisLoop loop(spec, opt, cancel, settings.chains, settings.mutations_per_pixel, "pssmlt");
    const auto inner = make_pssmlt_inner(settings);
    const double p_large = settings.large_step_probability;

    // Bootstrap: b = E[Y] over independent primary samples (an unbiased estimate of the
    // normalisation), and the Y of each as the weight of its path as a chain seed. Computed
    // once over the team, so that every process holds the same values.
    const size_t n_boot = size_t(settings.bootstrap_samples);
    const std::vector<double> boot_y = team_bootstrap(loop.team(), loop.arena(), n_boot, [&](size_t i) {
        PrimarySampleSampler sampler(bootstrap_seed(opt.seed, i), i, p_large, settings.s1, settings.s2);
        return evaluate(scene, *camera, *inner, spectral_samples, spec, sampler).target();
    });
    double b = 0;
    for (double y : boot_y) b += y;  // fixed order: deterministic
    b /= double(n_boot);
    if (b <= 0) return loop.black();  // no bootstrap path carried light: an (estimated) black image
    const Distribution1D seeds(boot_y);

    // A chain's state, kept between the rounds of an equal-time render.
    struct Chain {
        PrimarySampleSampler sampler;
        PathSample current;
    };
    std::vector<std::unique_ptr<Chain>> chains(size_t(loop.chains()));
    return loop.run([&](int c, uint64_t quota, std::vector<Vec3>& film) {
        std::unique_ptr<Chain>& chain = chains[size_t(c)];
        if (!chain) {
            // Resample a bootstrap path proportionally to Y and reproduce it exactly (same
            // stream, iteration 0 draws every dimension fresh), then give the chain its own stream.
            PCG32 pick(chain_seed(opt.seed, uint64_t(c)), uint64_t(c) * 2 + 1);
            const size_t i = seeds.sample_discrete(pick.next_double());
            chain = std::make_unique<Chain>(
                Chain{PrimarySampleSampler(bootstrap_seed(opt.seed, i), i, p_large, settings.s1, settings.s2), {}});
            chain->current = evaluate(scene, *camera, *inner, spectral_samples, spec, chain->sampler);
            chain->sampler.accept();
            chain->sampler.reseed(chain_seed(opt.seed, uint64_t(c)), uint64_t(c) * 2);
        }
        PrimarySampleSampler& sampler = chain->sampler;
        PathSample& current = chain->current;
        uint64_t m = 0;
        for (; loop.keep_going(m, quota); ++m) {
            sampler.start_iteration();
            const PathSample proposed = evaluate(scene, *camera, *inner, spectral_samples, spec, sampler);
            const double fc = current.target(), fp = proposed.target();
            const double a = fc > 0 ? std::min(1.0, fp / fc) : 1.0;
            // Expected-value accumulation: each state splats XYZ / Y with its probability
            // of being the next state; the image scale b / (mutations per pixel) comes last.
            // Kelemen et al. (2002, Sec. 4) also count a large step as an independent
            // sample of density 1 and combine both by the balance heuristic: Y / b becomes
            // Y / b + p_large and a large-step proposal earns one more unit of weight.
            const bool large = sampler.large_step();
            const double pk = settings.kelemen_weights ? p_large : 0.0;
            const double wc = (1 - a) / (fc / b + pk);
            const double wp = (a + (settings.kelemen_weights && large ? 1.0 : 0.0)) / (fp / b + pk);
            if (wc > 0 && fc > 0) loop.deposit(film, current.raster, current.xyz * wc);
            if (wp > 0 && fp > 0) loop.deposit(film, proposed.raster, proposed.xyz * wp);
            if (sampler.uniform() < a) {
                current = proposed;
                sampler.accept();
            } else {
                sampler.reject();
            }
        }
        return m;
    });
}

}  // namespace snell
