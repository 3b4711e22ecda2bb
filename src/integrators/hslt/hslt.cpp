#include "integrators/hslt/hslt.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

#include "bsdf/bsdf.h"
#include "core/distribution.h"
#include "core/props.h"
#include "core/stats.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/pssmlt/metropolis_loop.h"
#include "integrators/pssmlt/path_sample.h"
#include "light/light.h"
#include "sampler/independent.h"
#include "scene/scene.h"

namespace snell {

HsltSettings HsltSettings::from_props(const Props& props) {
    HsltSettings s;
    const auto probability = [&](const char* name, double v) {
        const double p = props.get_float(name, v);
        if (!(p >= 0 && p <= 1)) props.raise_param(name, std::string("hslt: ") + name + " must lie in [0, 1]");
        return p;
    };
    s.large_step_probability = probability("large_step_probability", s.large_step_probability);
    s.lens_probability = probability("lens_probability", s.lens_probability);
    s.light_probability = probability("light_probability", s.light_probability);
    if (s.lens_probability + s.light_probability > 1)
        props.raise_param("light_probability", "hslt: lens_probability + light_probability must be at most 1");
    s.kelemen_weights = props.get_bool("kelemen_weights", s.kelemen_weights);
    parse_chain_counts(props, "hslt", 2, &s.mutations_per_pixel, &s.bootstrap_samples, &s.chains);
    const int64_t depth = props.get_int("max_depth", -1);
    if (depth == 0 || depth < -1 || depth > 64)
        props.raise_param("max_depth", "hslt: max_depth must lie in [1, 64] (or -1)");
    if (depth > 0) s.max_depth = int(depth);
    s.hide_emitters = props.get_bool("hide_emitters", s.hide_emitters);
    // Read so that scenes written for the path family load; HSLT mutates whole paths and has no
    // switch for the camera's specular-only prefix.
    if (props.get_bool("hide_specular_emitters", false))
        props.raise_param("hide_specular_emitters",
                          "hslt: not supported (render the caustic alone with pt, nee, mnee or bdpt)");
    props.get_int("rr_depth", 5);  // accepted for scenes written for the path tracers; no roulette here
    const auto positive = [&](const char* name, double v) {
        const double x = props.get_float(name, v);
        if (!(x > 0) || !std::isfinite(x)) props.raise_param(name, std::string("hslt: ") + name + " must be > 0");
        return x;
    };
    HsltMutationSettings& m = s.mutation;
    m.footprint = props.get_float("footprint", m.footprint);
    if (!(m.footprint >= 0) || !std::isfinite(m.footprint))
        props.raise_param("footprint", "hslt: footprint must be >= 0 (pixels; 0: fixed widths)");
    m.width = positive("perturbation_width", m.width);
    m.rough_width = positive("rough_width", m.rough_width);
    m.lens_width = positive("lens_width", m.lens_width);
    m.light_width = positive("light_width", m.light_width);
    m.walk = WalkSettings::from_props(props);
    s.b_rate = props.get_float("b_rate", s.b_rate);
    if (!(s.b_rate >= 0 && s.b_rate <= 16))
        props.raise_param("b_rate", "hslt: b_rate must lie in [0, 16] (MNEE paths per mutation refining b)");
    return s;
}

namespace {

StatCounter proposed[4] = {{"hslt.large.proposed", "large steps proposed"},
                           {"hslt.half_vector.proposed", "half-vector perturbations proposed"},
                           {"hslt.lens.proposed", "lens perturbations proposed"},
                           {"hslt.light.proposed", "light perturbations proposed"}};
StatCounter accepted[4] = {{"hslt.large.accepted", "large steps accepted"},
                           {"hslt.half_vector.accepted", "half-vector perturbations accepted"},
                           {"hslt.lens.accepted", "lens perturbations accepted"},
                           {"hslt.light.accepted", "light perturbations accepted"}};

uint64_t bootstrap_seed(uint64_t seed, uint64_t i) { return mix_bits(mix_bits(seed ^ 0x48534c54ULL) ^ (i * 2 + 1)); }
uint64_t chain_seed(uint64_t seed, uint64_t c) { return mix_bits(mix_bits(seed + 0x2545f4914f6cdd1dULL) ^ (c * 2)); }

void check_scene(const Scene& scene) {
    if (!scene.camera() || !scene.camera()->pinhole())
        throw std::runtime_error("hslt renders through a pinhole (perspective) sensor only");
    // Its paths reach the lights by hitting them.
    for (const auto& l : scene.lights())
        if (l->kind() == LightKind::Point || l->kind() == LightKind::Spot || l->kind() == LightKind::Projector ||
            l->kind() == LightKind::Directional)
            throw std::runtime_error(
                "hslt: point, spot, projector and directional lights cannot be hit by a path; render this scene "
                "with bdpt or mnee");
}

}  // namespace

RenderResult render_hslt(const Scene& scene, const HsltSettings& st, int spectral_samples, const FilmSpec& spec,
                         const RenderOptions& opt, const std::atomic<bool>* cancel) {
    check_scene(scene);
    const PerspectiveCamera& camera = *scene.camera()->pinhole();
    // An equal-time render leaves the MNEE paths that refine b (b_rate per mutation, about as
    // costly each as a mutation) their share of the budget.
    RenderOptions chain_opt = opt;
    if (chain_opt.time_limit > 0) chain_opt.time_limit = opt.time_limit / (1 + st.b_rate);
    MetropolisLoop loop(spec, chain_opt, cancel, st.chains, st.mutations_per_pixel, "hslt");
    const HsltContext ctx{&scene, &camera, &spec, length(scene.bounds().extent())};

    // Bootstrap, in two rounds over the team: first with every length equally likely, to learn
    // how the light divides over the lengths; then with lengths drawn in those proportions (each
    // kept at a tenth of its uniform share at least, so every length stays reachable), for the
    // normalisation b = E[T] and the chain seeds.
    const size_t n_boot = size_t(st.bootstrap_samples);
    const size_t n_lengths = size_t(st.max_depth);
    std::vector<double> pmf(n_lengths, 1.0 / double(n_lengths));
    const auto bootstrap_path = [&](size_t i, const std::vector<double>& depth_pmf, HsltPath* path) {
        PCG32 rng(bootstrap_seed(opt.seed, i), i * 2 + 1);
        return sample_hslt_path(scene, camera, spec, depth_pmf, spectral_samples, st.hide_emitters, rng, path);
    };
    {
        const std::vector<double> y = team_bootstrap(loop.team(), loop.arena(), n_boot / 2, [&](size_t i) {
            HsltPath p;
            return bootstrap_path(i, pmf, &p) ? p.target() * p.depth_pmf : 0.0;
        });
        std::vector<double> per_length(n_lengths, 0.0);
        double total = 0;
        for (size_t i = 0; i < y.size(); ++i) {
            if (!(y[i] > 0)) continue;
            HsltPath p;
            bootstrap_path(i, pmf, &p);
            per_length[size_t(p.length() - 1)] += y[i];
            total += y[i];
        }
        if (total > 0)
            for (size_t j = 0; j < n_lengths; ++j) pmf[j] = (per_length[j] / total + 0.1 / double(n_lengths)) / 1.1;
    }
    const std::vector<double> boot_y = team_bootstrap(loop.team(), loop.arena(), n_boot, [&](size_t i) {
        HsltPath p;
        return bootstrap_path(i, pmf, &p) ? p.target() : 0.0;
    });
    // The normalisation b = E[T] from MNEE (the paper's estimator) rather than from those paths:
    // path tracing without light sampling is heavy-tailed wherever a small light lies behind
    // glass, and b scales the whole image. On the droplet, 400,000 of those paths gave b 0.0955
    // to 0.137 over seeds, MNEE's 0.1130 to 0.1138 (the reference image's mean: 0.1135).
    PathSettings inner_path;
    inner_path.max_depth = st.max_depth;
    inner_path.hide_emitters = st.hide_emitters;
    const MneeIntegrator inner(inner_path, MneeSettings{});
    const IndependentSampler prototype(mix_bits(opt.seed ^ 0x48534c5462ULL));
    const auto mnee_energy = [&](size_t first, size_t count) {
        const std::vector<double> y = team_bootstrap(loop.team(), loop.arena(), count, [&](size_t i) {
            auto sampler = prototype.clone();
            sampler->start_pixel_sample(-1, -1, first + i);  // no pixel of the film uses (-1, -1)
            return hslt_importance(evaluate(scene, camera, inner, spectral_samples, spec, *sampler).xyz);
        });
        double sum = 0;
        for (double v : y) sum += v;  // fixed order: deterministic
        return sum;
    };
    const double boot_energy = mnee_energy(0, n_boot);
    const double b = boot_energy / double(n_boot);
    double boot_sum = 0;
    for (double y : boot_y) boot_sum += y;
    // No large step found light (or there is none): no chain can start.
    if (!(b > 0) || !(boot_sum > 0)) return loop.black();
    const Distribution1D seeds(boot_y);
    const double p_large = st.large_step_probability;
    const double pk = st.kelemen_weights ? p_large : 0.0;

    // A chain's state, kept between the rounds of an equal-time render.
    struct Chain {
        PCG32 rng;
        HsltPath current, proposal;
    };
    std::vector<std::unique_ptr<Chain>> chains(size_t(loop.chains()));
    // b weighs the splats (Kelemen's (1 - a) / (Y / b + p_large)) and scales the chains' part of
    // the image (their states have density Y / b_true). A fixed bootstrap leaves b's error in
    // the image however long the chains run (the glass sphere's image means spread 0.86-1.16 over
    // seeds with 400,000 paths), so the chains' part is rescaled at the end by b refined with b_rate more
    // MNEE paths per mutation: the image converges as the render grows.
    const auto refined_scale = [&](uint64_t mutations) {
        const size_t extra = size_t(std::llround(double(mutations) * st.b_rate));
        if (extra == 0) return 1.0;
        const double refined = (boot_energy + mnee_energy(n_boot, extra)) / double(n_boot + extra);
        return refined / b;
    };
    const auto chain_step = [&](int c, uint64_t quota, MetropolisLoop::ChainFilms& films) {
        std::unique_ptr<Chain>& chain = chains[size_t(c)];
        if (!chain) {
            chain = std::make_unique<Chain>();
            chain->rng = PCG32(chain_seed(opt.seed, uint64_t(c)), uint64_t(c) * 2);
            bootstrap_path(seeds.sample_discrete(chain->rng.next_double()), pmf, &chain->current);
        }
        PCG32& rng = chain->rng;
        HsltPath &current = chain->current, &proposal = chain->proposal;
        uint64_t m = 0;
        for (; loop.keep_going(m, quota); ++m) {
            const double u = rng.next_double();
            HsltMutation kind = HsltMutation::Large;
            double a = 0;
            if (u < p_large) {
                if (!sample_hslt_path(scene, camera, spec, pmf, spectral_samples, st.hide_emitters, rng, &proposal))
                    proposal.xyz = Vec3();
                a = std::min(1.0, proposal.target() / current.target());
            } else {
                const double v = (u - p_large) / (1 - p_large);
                HsltProposal pr;
                if (v < st.lens_probability) {
                    kind = HsltMutation::Lens;
                    pr = perturb_lens(ctx, current, st.mutation, rng, &proposal);
                } else if (v < st.lens_probability + st.light_probability) {
                    kind = HsltMutation::Light;
                    pr = perturb_light(ctx, current, st.mutation, rng, &proposal);
                } else {
                    kind = HsltMutation::HalfVector;
                    pr = perturb_half_vectors(ctx, current, st.mutation, rng, &proposal);
                }
                if (!pr.valid) proposal.xyz = Vec3();
                a = pr.valid ? std::min(1.0, pr.ratio) : 0.0;
            }
            ++proposed[int(kind)];
            // Expected-value splats, a large step counted as an independent sample as well
            // (Kelemen et al. 2002, Sec. 4), as pssmlt does.
            const bool large = kind == HsltMutation::Large;
            const double fc = current.target(), fp = proposal.target();
            // The chain's part (its states' expected values) and the large step's own sample.
            const double wc = (1 - a) / (fc / b + pk);
            const double wp = a / (fp / b + pk);
            const double wl = st.kelemen_weights && large ? 1.0 / (fp / b + pk) : 0.0;
            if (wc > 0) loop.deposit(films.metropolis, current.raster, current.xyz * wc);
            if (fp > 0 && wp > 0) loop.deposit(films.metropolis, proposal.raster, proposal.xyz * wp);
            if (fp > 0 && wl > 0)
                loop.deposit(st.b_rate > 0 ? films.independent : films.metropolis, proposal.raster, proposal.xyz * wl);
            if (rng.next_double() < a) {
                std::swap(current, proposal);
                ++accepted[int(kind)];
            }
        }
        return m;
    };
    // Without refinement the large steps' samples join the chains' film (no scale to apply).
    return loop.run_parts(chain_step, st.b_rate > 0 ? std::function<double(uint64_t)>(refined_scale) : nullptr);
}

}  // namespace snell
