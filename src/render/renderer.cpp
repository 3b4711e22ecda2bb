#include "render/renderer.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/progress.h"
#include "core/sampler.h"
#include "core/spectrum.h"
#include "geometry/scene.h"
#include "integrators/integrator.h"
#include "integrators/pssmlt/pssmlt.h"

namespace snell {

namespace {

struct Tile {
    int x0, y0, x1, y1;  // output (crop) coordinates, half-open
};

std::vector<Tile> make_tiles(int w, int h, int size) {
    std::vector<Tile> tiles;
    for (int y = 0; y < h; y += size)
        for (int x = 0; x < w; x += size) tiles.push_back({x, y, std::min(w, x + size), std::min(h, y + size)});
    return tiles;
}

// Pass sizes 1, 1, 2, 4, 8, 16, 16, ...: early passes give quick previews and a fine-grained
// equal-time cut-off; later ones amortise scheduling. Fixed, so images are reproducible.
uint64_t pass_size(int pass) { return pass < 1 ? 1 : std::min<uint64_t>(16, uint64_t(1) << (pass - 1)); }

/// Keeps invalid estimates off the film (project promise 4) and counts them by kind.
double sanitize(double L, Counters& c) {
    if (std::isnan(L)) {
        c.discarded_nan++;
        return 0;
    }
    if (std::isinf(L)) {
        c.discarded_inf++;
        return 0;
    }
    if (L < 0) {
        c.discarded_negative++;
        return 0;
    }
    return L;
}

}  // namespace

RenderResult render(const Scene& scene, const Integrator& integrator, const FilmSpec& spec,
                    const RenderOptions& opt, const std::atomic<bool>* cancel) {
    // Metropolis places its samples anywhere on the film: it has its own render loop.
    if (const auto* mlt = dynamic_cast<const PssmltIntegrator*>(&integrator))
        return render_pssmlt(scene, mlt->settings(), spec, opt, cancel);
    using Clock = std::chrono::steady_clock;
    const PerspectiveCamera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");
    const auto start = Clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const bool timed = opt.time_limit > 0;
    const int w = spec.out_width(), h = spec.out_height();
    const std::vector<Tile> tiles = make_tiles(w, h, std::max(1, opt.tile_size));

    RenderResult result;
    result.film = Film(w, h);
    reset_counters();

    const int threads = opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    tbb::task_arena arena(threads);
    const IndependentSampler prototype(opt.seed);

    std::unique_ptr<ProgressBar> bar;
    if (opt.progress)
        bar.reset(timed ? new ProgressBar(ProgressBar::for_time("render", opt.time_limit))
                        : new ProgressBar("render", uint64_t(opt.spp) * uint64_t(w) * uint64_t(h)));

    const auto stop_requested = [&] {
        return (cancel && cancel->load(std::memory_order_relaxed)) || (timed && elapsed() >= opt.time_limit);
    };

    uint64_t done_spp = 0;
    for (int pass = 0; !stop_requested(); ++pass) {
        uint64_t n = pass_size(pass);
        if (!timed) {
            if (done_spp >= uint64_t(opt.spp)) break;
            n = std::min<uint64_t>(n, uint64_t(opt.spp) - done_spp);
        }
        const uint64_t s0 = done_spp, s1 = done_spp + n;
        std::atomic<bool> pass_complete{true};
        arena.execute([&] {
            tbb::parallel_for(size_t(0), tiles.size(), [&](size_t ti) {
                if (stop_requested()) {
                    pass_complete = false;
                    return;
                }
                const Tile& t = tiles[ti];
                auto sampler = prototype.clone();
                Counters& counters = thread_counters();
                for (int y = t.y0; y < t.y1; ++y) {
                    if (y > t.y0 && cancel && cancel->load(std::memory_order_relaxed)) {
                        pass_complete = false;
                        return;
                    }
                    for (int x = t.x0; x < t.x1; ++x) {
                        const int fx = x + spec.crop_x, fy = y + spec.crop_y;  // full-film pixel
                        Vec3 sum;
                        for (uint64_t s = s0; s < s1; ++s) {
                            sampler->start_pixel_sample(fx, fy, s);
                            const Vec2 jitter = sampler->next_2d();
                            const double u_lambda = sampler->next_1d();
                            const double lambda = sample_visible_wavelength(u_lambda);
                            const double pdf_lambda = visible_wavelength_pdf(lambda);
                            const Ray ray = camera->generate_ray(Vec2(fx + jitter.x, fy + jitter.y));
                            const double L = sanitize(integrator.li(ray, scene, *sampler, lambda), counters);
                            if (L > 0 && pdf_lambda > 0) sum += radiance_to_xyz(L, lambda, pdf_lambda);
                        }
                        result.film.add_sum(x, y, sum, s1 - s0);
                    }
                }
                if (bar) bar->add(timed ? 0 : (s1 - s0) * uint64_t(t.x1 - t.x0) * uint64_t(t.y1 - t.y0));
            });
        });
        if (!pass_complete) break;
        done_spp = s1;
        if (bar && timed) bar->update();
    }
    if (bar) bar->finish();

    result.seconds = elapsed();
    result.spp_completed = done_spp;
    uint64_t total = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) total += result.film.samples(x, y);
    result.spp_mean = double(total) / double(std::max(1, w * h));
    result.interrupted = cancel && cancel->load() && (timed || done_spp < uint64_t(opt.spp));
    result.counters = total_counters();
    return result;
}

}  // namespace snell
