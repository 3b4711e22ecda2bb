#include "integrators/pssmlt/metropolis_loop.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/props.h"
#include "core/stats.h"
#include "integrators/integrator.h"

namespace snell {

namespace {
// Chains of a fixed-length render without a `chains` setting.
constexpr int kDefaultChains = 64;
constexpr uint64_t kCheck = 1024;
}  // namespace

void parse_chain_counts(const Props& props, const char* who, int64_t min_bootstrap, int64_t* mutations_per_pixel,
                        int64_t* bootstrap_samples, int* chains) {
    const std::string w(who);
    *mutations_per_pixel = props.get_int("mutations_per_pixel", *mutations_per_pixel);
    if (*mutations_per_pixel < 0 || *mutations_per_pixel > (int64_t(1) << 30))
        props.raise_param("mutations_per_pixel", w + ": mutations_per_pixel must lie in [0, 1073741824]");
    *bootstrap_samples = props.get_int("bootstrap_samples", *bootstrap_samples);
    if (*bootstrap_samples < min_bootstrap || *bootstrap_samples > kMaxBootstrapSamples)
        props.raise_param("bootstrap_samples",
                          w + ": bootstrap_samples must lie in [" + std::to_string(min_bootstrap) + ", 16777216]");
    const int64_t c = props.get_int("chains", *chains);
    if (c < 0 || c > 65536) props.raise_param("chains", w + ": chains must lie in [0, 65536]");
    *chains = int(c);
}

MetropolisLoop::MetropolisLoop(const FilmSpec& film, const RenderOptions& opt, const std::atomic<bool>* cancel,
                               int chains, int64_t mutations_per_pixel, const char* label)
    : m_spec(film),
      m_opt(opt),
      m_team(&render_team(opt)),
      m_stopping(opt, cancel),
      m_timed(opt.time_limit > 0),
      m_threads(render_threads(opt)),
      m_arena(m_threads),
      m_label(label) {
    // A chain roams the whole film and its samples have no index: a crop or a sample range of
    // it is not a part of the frame. Split the chains over MPI ranks or seeds instead.
    if (!opt.crop.empty() || opt.sample_begin > 0 || opt.sample_end > 0)
        throw std::runtime_error(std::string(label) +
                                 " renders the whole film with Markov chains: --crop and --sample-range do not apply "
                                 "(run it under mpirun, which splits the chains, or merge renders of other seeds)");
    // The chain count decides the image, so it must come from neither the machine nor the team.
    // Equal-time renders run the same chains, in rounds (run()).
    m_chains = chains > 0 ? chains : kDefaultChains;
    const uint64_t pixels = uint64_t(film.out_width()) * uint64_t(film.out_height());
    m_total = uint64_t(mutations_per_pixel > 0 ? mutations_per_pixel : opt.spp) * pixels;
    reset_stats();
}

void MetropolisLoop::deposit(std::vector<Vec3>& film, const Vec2& raster, const Vec3& v) const {
    const int w = m_spec.out_width(), h = m_spec.out_height();
    const Vec2 p(raster.x - m_spec.crop_x, raster.y - m_spec.crop_y);
    for_each_pixel_in_support(m_spec.pixel_filter(), p, w, h,
                              [&](int x, int y, double wt) { film[size_t(y) * size_t(w) + size_t(x)] += v * wt; });
}

bool MetropolisLoop::keep_going(uint64_t m, uint64_t quota) const {
    if (m >= quota) return false;
    if (m % kCheck == 0 && m > 0) {
        if (m_bar) m_bar->add(m_timed ? 0 : kCheck * uint64_t(m_team->size()));  // MPI: rank 0's share, scaled
        if (m_stopping.requested()) return false;
    }
    return true;
}

RenderResult MetropolisLoop::finish(RenderResult result, double splat_scale, uint64_t mutations) const {
    const int w = m_spec.out_width(), h = m_spec.out_height();
    const size_t pixels = size_t(w) * size_t(h);
    result.counters = stat_totals();
    m_team->reduce(result.film, result.counters);
    result.team = m_team->times();
    // Every pixel counts one sample of value zero plus its splats (the chains' deposits).
    if (m_team->rank() == 0)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) result.film.add_sum(x, y, Vec3(), 1);
    result.film.set_splat_scale(splat_scale);
    result.seconds = m_stopping.elapsed();
    result.spp_mean = double(mutations) / double(pixels);
    result.spp_completed = mutations / pixels;
    return result;
}

RenderResult MetropolisLoop::black() {
    RenderResult r;
    r.film = Film(m_spec.out_width(), m_spec.out_height());
    return finish(std::move(r), 0.0, 0);
}

RenderResult MetropolisLoop::run(const std::function<uint64_t(int c, uint64_t quota, std::vector<Vec3>& film)>& chain) {
    return run_parts([&](int c, uint64_t quota, ChainFilms& films) { return chain(c, quota, films.metropolis); },
                     nullptr);
}

RenderResult MetropolisLoop::run_parts(const PartsChain& chain,
                                       const std::function<double(uint64_t mutations)>& metropolis_scale) {
    const int w = m_spec.out_width(), h = m_spec.out_height();
    const size_t pixels = size_t(w) * size_t(h);
    RenderResult result;
    result.film = Film(w, h);
    // With a scale to come, the Metropolis part waits in splat layer 1 (reduced over the team
    // with the rest) and is folded into the image at the end.
    const int metropolis_layer = metropolis_scale ? 1 : 0;
    // One pair of films per thread for the chain it runs; a finished chain's films are added to
    // the film's splats exactly (ExactSum), so the image depends on neither the order the chains
    // finish in nor the process that ran them.
    std::vector<ChainFilms> films(static_cast<size_t>(m_threads));
    std::mutex film_mutex;
    std::atomic<uint64_t> mutations{0};
    m_bar = render_progress(m_opt, *m_team, m_label, m_total);
    const uint64_t n = uint64_t(m_chains);
    const auto add = [&](const std::vector<Vec3>& film, int layer) {
        for (size_t p = 0; p < film.size(); ++p)
            if (film[p].x != 0 || film[p].y != 0 || film[p].z != 0)
                result.film.add_splat(int(p % size_t(w)), int(p / size_t(w)), film[p], layer);
    };
    // A fixed-length render runs each chain once, to its share of the mutations. An equal-time
    // render runs every chain in rounds of growing length until the budget is spent: with one
    // chain per thread (as before), a chain that found a rare bright path (a caustic path tracing
    // seldom samples) stayed near it for most of the budget, and two chains made the image
    // (hslt on the droplet: 60 % of its light in 11 pixels).
    uint64_t round = 1024;
    for (;;) {
        const PassOutcome pass = run_team_pass(
            *m_team, m_arena, m_threads, m_chains, [&] { return m_stopping.requested(); }, SIZE_MAX,
            [&](int64_t c, int slot) {
                ChainFilms& f = films[size_t(slot)];
                f.metropolis.assign(pixels, Vec3());
                f.independent.assign(metropolis_scale ? pixels : 0, Vec3());
                const uint64_t quota = m_timed ? round : m_total / n + (uint64_t(c) < m_total % n ? 1 : 0);
                mutations += chain(int(c), quota, f);
                const std::lock_guard<std::mutex> lock(film_mutex);
                add(f.metropolis, metropolis_layer);
                add(f.independent, 0);
                return !m_stopping.cancelled();
            });
        if (!m_timed || pass.stop || !pass.complete) break;
        round = std::min<uint64_t>(round * 2, uint64_t(1) << 20);
    }
    if (m_bar) m_bar->finish();
    // Pixel value = (film area) / (mutations) * splat sum: the chains visit the film with density
    // Y / b over the window grown by the filter margin, whose area replaces the pixel count.
    std::vector<double> all{double(mutations.load())};
    m_team->sum_exactly(all);  // integers below 2^53: exact in any order
    const uint64_t done = uint64_t(all[0]);
    // An interrupted render keeps the weights' scale: its image is wanted now (every process
    // takes the same branch).
    const bool cancelled = metropolis_scale && m_team->any(m_stopping.cancelled());
    const double scale = metropolis_scale && !cancelled ? metropolis_scale(done) : 1.0;
    const Vec2 extent = m_spec.sample_extent();
    result = finish(std::move(result), done > 0 ? extent.x * extent.y / double(done) : 0.0, done);
    if (metropolis_scale) result.film.fold_splat_layer(metropolis_layer, scale);
    result.interrupted = m_team->any(m_stopping.cancelled()) && (m_timed || done < m_total);
    return result;
}

}  // namespace snell
