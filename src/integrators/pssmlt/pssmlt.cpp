#include "integrators/pssmlt/pssmlt.h"

#include <tbb/task_arena.h>

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "core/distribution.h"
#include "core/progress.h"
#include "core/props.h"
#include "core/spectrum.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/pssmlt/path_sample.h"
#include "integrators/pssmlt/primary_sample_sampler.h"
#include "render/team_pass.h"
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
    // Range-checked as 64-bit integers before use (issue 12: the fuzzer's bootstrap_samples of
    // 2^31 allocated 16 GiB; chains were narrowed to int).
    s.mutations_per_pixel = props.get_int("mutations_per_pixel", s.mutations_per_pixel);
    if (s.mutations_per_pixel < 0 || s.mutations_per_pixel > (int64_t(1) << 30))
        props.raise_param("mutations_per_pixel", "pssmlt: mutations_per_pixel must lie in [0, 1073741824]");
    s.bootstrap_samples = props.get_int("bootstrap_samples", s.bootstrap_samples);
    if (s.bootstrap_samples < 1 || s.bootstrap_samples > kMaxBootstrapSamples)
        props.raise_param("bootstrap_samples", "pssmlt: bootstrap_samples must lie in [1, 16777216]");
    const int64_t chains = props.get_int("chains", s.chains);
    if (chains < 0 || chains > 65536) props.raise_param("chains", "pssmlt: chains must lie in [0, 65536]");
    s.chains = int(chains);
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

// Chains of a fixed-length render without a `chains` setting (see render_pssmlt).
constexpr int kDefaultChains = 64;

}  // namespace

RenderResult render_pssmlt(const Scene& scene, const PssmltSettings& settings, int spectral_samples,
                           const FilmSpec& spec, const RenderOptions& opt, const std::atomic<bool>* cancel) {
    const Camera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");
    // A chain roams the whole film and its samples have no index: a crop or a sample range of
    // it is not a part of the frame. Split PSSMLT over MPI ranks (chains) or seeds instead.
    if (!opt.crop.empty() || opt.sample_begin > 0 || opt.sample_end > 0)
        throw std::runtime_error(
            "pssmlt renders the whole film with Markov chains: --crop and --sample-range do not apply "
            "(run it under mpirun, which splits the chains, or merge renders of other seeds)");
    RenderTeam& team = render_team(opt);
    const RenderStop stopping(opt, cancel);
    const bool timed = opt.time_limit > 0;
    const int w = spec.out_width(), h = spec.out_height();
    const size_t pixels = size_t(w) * size_t(h);
    const auto inner = make_pssmlt_inner(settings);
    const int threads = render_threads(opt);
    // The chain count decides the image, so it must come from neither the machine nor the team:
    // without a `chains` setting a fixed-length render runs kDefaultChains chains, handed out
    // to the threads of the team's processes. An equal-time render cannot run chains in turn,
    // so it runs one per thread of every process.
    const int n_chains = settings.chains > 0 ? settings.chains : (timed ? threads * team.size() : kDefaultChains);
    const double p_large = settings.large_step_probability;
    // A state's weight goes to every pixel whose reconstruction filter covers its position.
    const Filter& filter = spec.pixel_filter();
    const auto deposit = [&](std::vector<Vec3>& film, const PathSample& s, const Vec3& v) {
        const Vec2 p(s.raster.x - spec.crop_x, s.raster.y - spec.crop_y);
        for_each_pixel_in_support(filter, p, w, h, [&](int x, int y, double wt) { film[size_t(y) * w + x] += v * wt; });
    };
    tbb::task_arena arena(threads);
    reset_stats();

    const auto stop_requested = [&] { return stopping.requested(); };

    // Bootstrap: b = E[Y] over independent primary samples (an unbiased estimate of the
    // normalisation), and the Y of each as the weight of its path as a chain seed. Computed
    // once over the team, so that every process holds the same values.
    const size_t n_boot = size_t(settings.bootstrap_samples);
    const std::vector<double> boot_y = team_bootstrap(team, arena, n_boot, [&](size_t i) {
        PrimarySampleSampler sampler(bootstrap_seed(opt.seed, i), i, p_large, settings.s1, settings.s2);
        return evaluate(scene, *camera, *inner, spectral_samples, spec, sampler).target();
    });
    double b = 0;
    for (double y : boot_y) b += y;  // fixed order: deterministic
    b /= double(n_boot);

    RenderResult result;
    result.film = Film(w, h);
    const auto finish = [&](double splat_scale, uint64_t mutations) {
        result.counters = stat_totals();
        team.reduce(result.film, result.counters);
        result.team = team.times();
        // Every pixel counts one sample of value zero plus its splats (the chains' deposits).
        if (team.rank() == 0)
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) result.film.add_sum(x, y, Vec3(), 1);
        result.film.set_splat_scale(splat_scale);
        result.seconds = stopping.elapsed();
        result.spp_mean = double(mutations) / double(pixels);
        result.spp_completed = mutations / pixels;
    };
    if (b <= 0) {
        finish(0.0, 0);
        return result;
    }  // no bootstrap path carried light: an (estimated) black image
    const Distribution1D seeds(boot_y);

    // Mutations per chain: the total split as evenly as possible (equal-time: unbounded).
    const uint64_t mpp = uint64_t(settings.mutations_per_pixel > 0 ? settings.mutations_per_pixel : opt.spp);
    const uint64_t total = mpp * pixels;
    // One film per thread for the chain it runs; a finished chain's film is added to the film's
    // splats exactly (ExactSum), so the image depends on neither the order the chains finish
    // in nor the process that ran them.
    std::vector<std::vector<Vec3>> films(static_cast<size_t>(threads));
    std::mutex film_mutex;
    std::atomic<uint64_t> mutations{0};
    const std::unique_ptr<ProgressBar> bar = render_progress(opt, team, "pssmlt", total);

    const auto run_chain = [&](int c, std::vector<Vec3>& film) -> bool {
        const uint64_t quota = total / uint64_t(n_chains) + (uint64_t(c) < total % uint64_t(n_chains) ? 1 : 0);
        film.assign(pixels, Vec3());
        // Resample a bootstrap path proportionally to Y and reproduce it exactly (same
        // stream, iteration 0 draws every dimension fresh), then give the chain its own stream.
        PCG32 pick(chain_seed(opt.seed, uint64_t(c)), uint64_t(c) * 2 + 1);
        const size_t i = seeds.sample_discrete(pick.next_double());
        PrimarySampleSampler sampler(bootstrap_seed(opt.seed, i), i, p_large, settings.s1, settings.s2);
        PathSample current = evaluate(scene, *camera, *inner, spectral_samples, spec, sampler);
        sampler.accept();
        sampler.reseed(chain_seed(opt.seed, uint64_t(c)), uint64_t(c) * 2);

        uint64_t m = 0;
        const uint64_t kCheck = 1024;
        for (; timed || m < quota; ++m) {
            if (m % kCheck == 0 && m > 0) {
                if (bar) bar->add(timed ? 0 : kCheck * uint64_t(team.size()));  // MPI: rank 0's share, scaled
                if (stop_requested()) break;
            }
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
            if (wc > 0 && fc > 0) deposit(film, current, current.xyz * wc);
            if (wp > 0 && fp > 0) deposit(film, proposed, proposed.xyz * wp);
            if (sampler.uniform() < a) {
                current = proposed;
                sampler.accept();
            } else {
                sampler.reject();
            }
        }
        mutations += m;
        {
            const std::lock_guard<std::mutex> lock(film_mutex);
            for (size_t p = 0; p < pixels; ++p)
                if (film[p].x != 0 || film[p].y != 0 || film[p].z != 0)
                    result.film.add_splat(int(p % size_t(w)), int(p / size_t(w)), film[p]);
        }
        return !stopping.cancelled();
    };
    run_team_pass(team, arena, threads, n_chains, stop_requested, SIZE_MAX,
                  [&](int64_t c, int slot) { return run_chain(int(c), films[size_t(slot)]); });
    if (bar) bar->finish();

    // Pixel value = b * (pixel count) / (mutations) * splat sum: the chains visit the film
    // with density Y / b over the unit square of film positions, each pixel covering 1/area.
    // Film positions cover the window grown by the filter margin: its area replaces the count.
    std::vector<double> all{double(mutations.load())};
    team.sum_exactly(all);  // integers below 2^53: exact in any order
    const uint64_t done = uint64_t(all[0]);
    const Vec2 extent = spec.sample_extent();
    finish(done > 0 ? extent.x * extent.y / double(done) : 0.0, done);
    result.interrupted = team.any(stopping.cancelled()) && (timed || done < total);
    return result;
}

}  // namespace snell
