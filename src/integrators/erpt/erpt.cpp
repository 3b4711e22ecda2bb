#include "integrators/erpt/erpt.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "core/rng.h"
#include "core/spectrum.h"
#include "integrators/erpt/energy_redistribution.h"
#include "integrators/erpt/recording_sampler.h"
#include "integrators/erpt/shape_watch.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/pssmlt/path_sample.h"
#include "integrators/pssmlt/primary_sample_sampler.h"
#include "render/camera_sample.h"
#include "render/renderer.h"
#include "render/team_pass.h"
#include "sampler/independent.h"
#include "scene/scene.h"

namespace snell {

ErptSettings ErptSettings::from_props(const Props& props) {
    ErptSettings s;
    s.loc = props.loc();
    s.sampler = props.get_string("sampler", s.sampler);
    if (s.sampler != "nee" && s.sampler != "mnee")
        props.raise_param("sampler", "erpt: sampler must be 'nee' or 'mnee', not '" + s.sampler + "'");
    const int64_t m = props.get_int("mutations", s.mutations);
    if (m < 1 || m > (int64_t(1) << 30)) props.raise_param("mutations", "erpt: mutations must be >= 1");
    s.mutations = int(m);
    s.deposition_energy = props.get_float("deposition_energy", s.deposition_energy);
    if (!(s.deposition_energy >= 0) || std::isinf(s.deposition_energy))
        props.raise_param("deposition_energy", "erpt: deposition_energy must be finite and >= 0 (0: automatic)");
    s.chains_per_sample = props.get_float("chains_per_sample", s.chains_per_sample);
    if (!(s.chains_per_sample > 0) || std::isinf(s.chains_per_sample))
        props.raise_param("chains_per_sample", "erpt: chains_per_sample must be finite and > 0");
    s.bootstrap_samples = props.get_int("bootstrap_samples", s.bootstrap_samples);
    if (s.bootstrap_samples < 1 || s.bootstrap_samples > kMaxBootstrapSamples)  // one double each
        props.raise_param("bootstrap_samples", "erpt: bootstrap_samples must lie in [1, 16777216]");
    const int64_t mc = props.get_int("max_chains", s.max_chains);
    if (mc < 1 || mc > (int64_t(1) << 30)) props.raise_param("max_chains", "erpt: max_chains must be >= 1");
    s.max_chains = int(mc);
    s.shapes = parse_shape_ids(props, "shapes", props.get_string("shapes", ""));
    s.path = PathSettings::from_props(props);
    if (s.sampler == "mnee") s.mnee = MneeSettings::from_props(props);
    return s;
}

std::unique_ptr<ErptTracer> ErptIntegrator::prepare_erpt(const Scene& scene, const FilmSpec& film,
                                                         const RenderOptions& opt) const {
    const std::shared_ptr<const RadianceEstimator> inner =
        make_watching_estimator(m_settings.sampler, m_settings.path, m_settings.mnee,
                                resolve_shape_ids(scene, m_settings.shapes, m_settings.loc));
    const int n_lambda = spectral_samples();
    if (m_settings.deposition_energy > 0)
        return std::make_unique<ErptTracer>(m_settings, inner, film, n_lambda, m_settings.deposition_energy, 0.0);
    const Camera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");

    // Bootstrap: the mean luminance per pixel sample of the seeds that will start chains,
    // from independent paths over the output window. Each path owns a stream that depends on
    // (seed, index) only, and the sum runs in index order: E_d is a pure function of the seed,
    // computed once over the processes of the team (team_pass.h).
    const size_t n = size_t(m_settings.bootstrap_samples);
    const bool restricted = !m_settings.shapes.empty();
    const IndependentSampler prototype(mix_bits(opt.seed ^ 0x45525054626f6f74ULL));  // "ERPTboot"
    tbb::task_arena arena(render_threads(opt));
    const std::vector<double> energy = team_bootstrap(render_team(opt), arena, n, [&](size_t i) {
        auto sampler = prototype.clone();
        sampler->start_pixel_sample(-1, -1, i);  // no pixel of the film uses (-1, -1)
        const PathSample s = evaluate(scene, *camera, *inner, n_lambda, film, *sampler);
        return !restricted || camera_path_touched() ? s.target() : 0.0;
    });
    double sum = 0;
    for (double e : energy) sum += e;
    const double mean_energy = sum / double(n);
    // E[chains per sample] = E[e] / (M E_d) = chains_per_sample.
    const double deposit =
        mean_energy > 0 ? mean_energy / (double(m_settings.mutations) * m_settings.chains_per_sample) : 0.0;
    return std::make_unique<ErptTracer>(m_settings, inner, film, n_lambda, deposit, mean_energy);
}

namespace {

/// One pixel sample's deposits summed per output pixel, in order of first visit (so the
/// splat list is deterministic). A chain deposits M times but visits few pixels, and the film
/// bins splats by pixel anyway, so this only saves memory.
///
/// A deposit at film position x goes to every output pixel k whose filter f covers it, with
/// weight f(x - c_k) / s(x), s(x) = sum_j f(x - c_j) over the output pixels. The seeds are
/// camera samples, which cover the film with density proportional to s(x) (filter importance
/// sampling per pixel), and the chains keep their energy near where it started; dividing by
/// s(x) makes the expected deposit in pixel k its filtered integral, edges included (Cline et
/// al. redistribute over one-pixel boxes, where s = 1).
class Deposits {
public:
    explicit Deposits(const FilmSpec& film) : m_film(film), m_filter(film.pixel_filter()) {}
    void add(const Vec2& raster, const Vec3& xyz) {
        const Vec2 p(raster.x - m_film.crop_x, raster.y - m_film.crop_y);
        const int w = m_film.out_width(), h = m_film.out_height();
        double coverage = 0;
        for_each_pixel_in_support(m_filter, p, w, h, [&](int, int, double f) { coverage += f; });
        if (!(coverage > 0)) return;
        for_each_pixel_in_support(m_filter, p, w, h, [&](int x, int y, double f) {
            const auto [it, fresh] = m_index.try_emplace(int64_t(y) * (int64_t(1) << 32) + x, m_sums.size());
            if (fresh) m_sums.push_back({x, y, Vec3()});
            m_sums[it->second].xyz += xyz * (f / coverage);
        });
    }
    /// Appends one binned splat per visited pixel, at the pixel's centre (full-film raster).
    void flush(SplatList& splats) const {
        for (const Sum& s : m_sums)
            splats.push_back({Vec2(m_film.crop_x + s.x + 0.5, m_film.crop_y + s.y + 0.5), s.xyz, 0, true});
    }

private:
    struct Sum {
        int x, y;
        Vec3 xyz;
    };
    const FilmSpec& m_film;
    const Filter& m_filter;
    std::unordered_map<int64_t, size_t> m_index;
    std::vector<Sum> m_sums;
};

}  // namespace

SampleEstimate ErptTracer::li_splat(const CameraSample& cs, const Ray& ray, const Scene& scene, Sampler& sampler,
                                    SplatList& splats) const {
    const FilmSpec& film = m_film;
    const int w = film.out_width(), h = film.out_height();
    const bool restricted = !m_settings.shapes.empty();

    // Step 1: the seed, an ordinary path whose numbers are recorded after the film position
    // and wavelength: the primary sample in pssmlt's layout (evaluate(), path_sample.h).
    const double below_one = std::nextafter(1.0, 0.0);
    std::vector<double> state;
    state.reserve(64);
    const Vec2 origin = film.sample_origin(), extent = film.sample_extent();
    state.push_back(std::clamp((cs.raster.x - origin.x) / extent.x, 0.0, below_one));
    state.push_back(std::clamp((cs.raster.y - origin.y) / extent.y, 0.0, below_one));
    state.push_back(cs.u_lambda.x);
    state.push_back(cs.u_lambda.y);
    RecordingSampler recorder(sampler, state);
    const SampledSpectrum L = m_inner->li(ray, scene, recorder, cs.wl);
    const bool touched = camera_path_touched();

    // Steps 2-3: its energy, and whether it is redistributed at all.
    if (!(m_deposit > 0) || L.is_zero() || !is_valid_radiance(L)) return L;
    if (restricted && !touched) return L;
    const Vec3 xyz = cs.wl.to_xyz(L);
    const double e = xyz.y;
    if (!(e > 0) || !std::isfinite(e)) return L;

    // Step 4: chains from the seed (energy_redistribution.h), their deposits summed per pixel.
    const ChainPlan plan = plan_chains(e, m_settings.mutations, m_deposit, m_settings.max_chains, sampler.next_1d());
    const uint64_t stream_bits = uint64_t(sampler.next_1d() * 0x1p53);
    PathSample seed;
    seed.x = std::clamp(int(std::floor(cs.raster.x)) - film.crop_x, 0, w - 1);
    seed.y = std::clamp(int(std::floor(cs.raster.y)) - film.crop_y, 0, h - 1);
    seed.raster = cs.raster;
    seed.xyz = xyz;
    const Camera& camera = *scene.camera();
    Deposits deposits(film);
    redistribute_energy(
        state, seed, plan, m_settings.mutations, stream_bits, m_settings.s1, m_settings.s2,
        [&](PrimarySampleSampler& mutator) {
            PathSample p = evaluate(scene, camera, *m_inner, m_spectral_samples, film, mutator);
            // Outside the `shapes` set the target is zero: the chain never leaves it.
            if (restricted && !camera_path_touched()) p.xyz = Vec3();
            return p;
        },
        [&](const PathSample& p, const Vec3& v) { deposits.add(p.raster, v); });
    deposits.flush(splats);
    return {};  // the seed's energy is in its chains' deposits
}

}  // namespace snell
