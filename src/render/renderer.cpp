#include "render/renderer.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/progress.h"
#include "core/sampler.h"
#include "render/camera_sample.h"
#include "scene/scene.h"

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
// (The shift is taken only below 5: a shift by 64 or more, reached past 976 spp, is undefined.)
uint64_t pass_size(int pass) { return pass < 1 ? 1 : pass >= 5 ? 16 : uint64_t(1) << (pass - 1); }

}  // namespace

RenderResult render_tiles(const Scene& scene, SampleTracer& tracer, int spectral_samples, const FilmSpec& spec,
                          const RenderOptions& opt, const std::atomic<bool>* cancel) {
    using Clock = std::chrono::steady_clock;
    const Camera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");
    const auto start = Clock::now();
    const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const bool timed = opt.time_limit > 0;
    const int w = spec.out_width(), h = spec.out_height();
    const std::vector<Tile> tiles = make_tiles(w, h, std::max(1, opt.tile_size));

    RenderResult result;
    result.film = Film(w, h);
    reset_stats();

    const int threads = opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    tbb::task_arena arena(threads);
    const std::unique_ptr<Sampler> prototype = create_sampler(opt.sampler, std::max(1, opt.spp), opt.seed);
    const Filter& filter = spec.pixel_filter();

    std::unique_ptr<ProgressBar> bar;
    if (opt.progress)
        bar.reset(timed ? new ProgressBar(ProgressBar::for_time("render", opt.time_limit))
                        : new ProgressBar("render", uint64_t(opt.spp) * uint64_t(w) * uint64_t(h)));

    const auto stop_requested = [&] {
        return (cancel && cancel->load(std::memory_order_relaxed)) || (timed && elapsed() >= opt.time_limit);
    };

    // Splats may land on any pixel: each tile collects its own, and they are added to the film
    // in tile order after every group of tiles, so the image does not depend on scheduling.
    // Groups bound the memory the buffers take; without splats one group holds every tile.
    const bool splatting = tracer.splats();
    // Techniques count only for a tracer that names them (an ERPT or PSSMLT sample may come from
    // an inner path tracer that noted one).
    const bool named_techniques = !tracer.technique_names().empty();
    const size_t group = splatting ? std::max<size_t>(64, size_t(threads) * 8) : tiles.size();
    std::vector<SplatList> tile_splats(splatting ? std::min(group, tiles.size()) : 0);
    const auto merge_splats = [&](size_t n) {
        for (size_t k = 0; k < n; ++k) {
            for (const FilmSplat& sp : tile_splats[k]) {
                // One count per invalid splat; XYZ of a non-negative radiance is non-negative.
                const double c = sanitize(sp.xyz.x + sp.xyz.y + sp.xyz.z);
                if (!(c > 0 && sp.xyz.x >= 0 && sp.xyz.y >= 0 && sp.xyz.z >= 0)) continue;
                const Vec2 p(sp.raster.x - spec.crop_x, sp.raster.y - spec.crop_y);  // output window
                if (sp.binned) {
                    const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
                    if (x >= 0 && y >= 0 && x < w && y < h) result.film.add_splat(x, y, sp.xyz, sp.layer);
                    continue;
                }
                // The pixels whose filter covers the splat estimate their filtered integral.
                for_each_pixel_in_support(filter, p, w, h, [&](int x, int y, double wt) {
                    result.film.add_splat(x, y, sp.xyz * wt, sp.layer);
                });
            }
            tile_splats[k].clear();
        }
    };

    uint64_t done_spp = 0;
    for (int pass = 0; !stop_requested(); ++pass) {
        // Splats need whole passes: a chain's deposits stay near its seed (ERPT), so a pass cut
        // short would brighten the tiles it reached against the film-wide normalisation. Such
        // a pass is dropped (unless it is the only one), and equal-time renders use passes of
        // one sample so that little time is lost.
        uint64_t n = splatting && timed ? 1 : pass_size(pass);
        std::optional<Film> before_pass;
        if (splatting && done_spp > 0) before_pass = result.film;
        if (!timed) {
            if (done_spp >= uint64_t(opt.spp)) break;
            n = std::min<uint64_t>(n, uint64_t(opt.spp) - done_spp);
        }
        const uint64_t s0 = done_spp, s1 = done_spp + n;
        std::atomic<bool> pass_complete{true};
        for (size_t g0 = 0; g0 < tiles.size() && pass_complete; g0 += group) {
            const size_t g1 = std::min(tiles.size(), g0 + group);
            arena.execute([&] {
                tbb::parallel_for(g0, g1, [&](size_t ti) {
                    if (stop_requested()) {
                        pass_complete = false;
                        return;
                    }
                    const Tile& t = tiles[ti];
                    auto sampler = prototype->clone();
                    SplatList dummy;
                    SplatList& splats = splatting ? tile_splats[ti - g0] : dummy;
                    for (int y = t.y0; y < t.y1; ++y) {
                        if (y > t.y0 && cancel && cancel->load(std::memory_order_relaxed)) {
                            pass_complete = false;
                            return;
                        }
                        for (int x = t.x0; x < t.x1; ++x) {
                            const int fx = x + spec.crop_x, fy = y + spec.crop_y;  // full-film pixel
                            Vec3 sum, largest;
                            int largest_technique = -1;
                            for (uint64_t s = s0; s < s1; ++s) {
                                sampler->start_pixel_sample(fx, fy, s);
                                // Filter importance sampling: the film position around the
                                // pixel centre, with density proportional to the filter.
                                const FilterSample fs = filter.sample(sampler->next_2d());
                                const Vec2 centre(fx + 0.5, fy + 0.5);
                                const Vec2 raster = centre + fs.offset;
                                const Vec2 u_lambda = sampler->next_2d();
                                const TracedSample ts = trace_camera_sample(scene, *camera, tracer, spectral_samples,
                                                                            centre, raster, u_lambda, *sampler, splats);
                                const Vec3 xyz = ts.xyz * fs.weight;
                                sum += xyz;
                                if (xyz.y > largest.y) {
                                    largest = xyz;
                                    largest_technique = named_techniques ? ts.technique : -1;
                                }
                            }
                            result.film.add_sum(x, y, sum, s1 - s0, largest, largest_technique);
                        }
                    }
                    if (bar) bar->add(timed ? 0 : (s1 - s0) * uint64_t(t.x1 - t.x0) * uint64_t(t.y1 - t.y0));
                });
            });
            // Splats of rows cut short by Ctrl-C are kept: the samples they came from were
            // taken, and the scale below counts samples, not passes.
            if (splatting) merge_splats(g1 - g0);
        }
        if (!pass_complete) {
            if (before_pass) result.film = std::move(*before_pass);
            break;
        }
        done_spp = s1;
        tracer.end_pass(done_spp);
        if (bar && timed) bar->update();
    }
    if (bar) bar->finish();

    result.seconds = elapsed();
    result.spp_completed = done_spp;
    uint64_t total = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) total += result.film.samples(x, y);
    result.spp_mean = double(total) / double(std::max(1, w * h));
    // Splat estimators divide by the camera samples each pixel received (total / pixels).
    result.film.set_splat_scale(total > 0 ? double(w) * double(h) / double(total) : 0.0);
    result.interrupted = cancel && cancel->load() && (timed || done_spp < uint64_t(opt.spp));
    result.film.set_max_sample_share(tracer.max_sample_share(), tracer.clamp_spread());
    result.dominance = pixel_dominance(result.film);
    result.counters = stat_totals();
    result.layer_names = tracer.layer_names();
    result.technique_names = tracer.technique_names();
    return result;
}

}  // namespace snell
