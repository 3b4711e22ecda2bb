#include "render/renderer.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include "camera/outlier_clamp.h"
#include "core/progress.h"
#include "core/sampler.h"
#include "render/camera_sample.h"
#include "render/render_team.h"
#include "render/team_pass.h"
#include "scene/scene.h"

namespace snell {

namespace render_stats {
StatCounter saturated{"render.saturated", "sample values beyond the film's exact range (2^80), saturated"};
}  // namespace render_stats

namespace {

using Tile = PixelRect;

// The tiles of `r`, on the grid of `size` x `size` squares anchored at the window's corner (so
// that a crop's tiles are pieces of the full render's), clipped to r.
std::vector<Tile> make_tiles(const PixelRect& r, int size) {
    std::vector<Tile> tiles;
    if (r.empty()) return tiles;
    for (int ty = r.y0 / size * size; ty < r.y1; ty += size)
        for (int tx = r.x0 / size * size; tx < r.x1; tx += size)
            tiles.push_back(
                {std::max(tx, r.x0), std::max(ty, r.y0), std::min(r.x1, tx + size), std::min(r.y1, ty + size)});
    return tiles;
}

// Pass sizes 1, 1, 2, 4, 8, 16, 16, ...: early passes give quick previews and a fine-grained
// equal-time cut-off; later ones amortise scheduling. Fixed, and by absolute sample index, so
// a sample range renders the same passes (and a learning tracer learns at the same sample).
// (The shift is taken only below 5: a shift by 64 or more, reached past 976 spp, is undefined.)
uint64_t pass_size(int pass) { return pass < 1 ? 1 : pass >= 5 ? 16 : uint64_t(1) << (pass - 1); }

}  // namespace

void finish_film(Film& film, double max_sample_share, int clamp_spread) {
    const int w = film.width(), h = film.height();
    uint64_t total = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) total += film.samples(x, y);
    // Splat estimators divide by the camera samples each pixel received (total / pixels).
    film.set_splat_scale(total > 0 ? double(w) * double(h) / double(total) : 0.0);
    apply_outlier_clamp(film, max_sample_share, clamp_spread);
}

RenderResult render_tiles(const Scene& scene, SampleTracer& tracer, int spectral_samples, const FilmSpec& spec,
                          const RenderOptions& opt, const std::atomic<bool>* cancel) {
    const Camera* camera = scene.camera();
    if (!camera) throw std::runtime_error("scene has no sensor");
    RenderTeam& team = render_team(opt);
    const RenderStop stopping(opt, cancel);
    const bool timed = opt.time_limit > 0;
    const int w = spec.out_width(), h = spec.out_height();
    const PixelRect window{0, 0, w, h};
    const PixelRect crop = opt.crop.empty() ? window : opt.crop;
    if (!(crop.x0 >= 0 && crop.y0 >= 0 && crop.x1 <= w && crop.y1 <= h) || crop.empty())
        throw std::runtime_error("crop " + std::to_string(crop.x0) + "," + std::to_string(crop.y0) + "," +
                                 std::to_string(crop.width()) + "," + std::to_string(crop.height()) +
                                 " is not inside the " + std::to_string(w) + "x" + std::to_string(h) + " film");
    // The samples of each pixel this render adds: [first, last).
    const uint64_t first = opt.sample_begin;
    const uint64_t last = timed ? UINT64_MAX : opt.sample_end > 0 ? opt.sample_end : uint64_t(std::max(0, opt.spp));
    if (first >= last) throw std::runtime_error("empty sample range");
    const int tile_size = std::max(1, opt.tile_size);
    const std::vector<Tile> tiles = make_tiles(crop, tile_size);
    // A learning tracer's pilot covers the pixels its choices for the crop depend on.
    PixelRect pilot = crop;
    tracer.pilot_window(pilot.x0, pilot.y0, pilot.x1, pilot.y1);
    std::vector<Tile> pilot_tiles = make_tiles(pilot, tile_size);
    for (const PixelRect& extra : tracer.pilot_extra(pilot))
        for (const Tile& t : make_tiles(extra, tile_size)) pilot_tiles.push_back(t);

    RenderResult result;
    result.film = Film(w, h);
    reset_stats();

    const int threads = render_threads(opt);
    tbb::task_arena arena(threads);
    const std::unique_ptr<Sampler> prototype = create_sampler(opt.sampler, std::max(1, opt.spp), opt.seed);
    const Filter& filter = spec.pixel_filter();

    const std::unique_ptr<ProgressBar> bar =
        render_progress(opt, team, "render",
                        uint64_t(std::min(last, uint64_t(std::max(0, opt.spp))) - std::min(first, last)) *
                            uint64_t(crop.width()) * uint64_t(crop.height()));

    const auto stop_requested = [&] { return stopping.requested(); };

    // Splats may land on any pixel: each tile collects its own, and they are added to the film
    // after every group of tiles (exactly, so in any order). Groups bound the memory the buffers
    // take; without splats one group holds every tile.
    const bool splatting = tracer.splats();
    // Techniques count only for a tracer that names them (an ERPT or PSSMLT sample may come from
    // an inner path tracer that noted one).
    const bool named_techniques = !tracer.technique_names().empty();
    const size_t group = splatting ? std::max<size_t>(64, size_t(threads) * 8) : SIZE_MAX;
    const auto merge_splats = [&](SplatList& list) {
        for (const FilmSplat& sp : list) {
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
            for_each_pixel_in_support(
                filter, p, w, h, [&](int x, int y, double wt) { result.film.add_splat(x, y, sp.xyz * wt, sp.layer); });
        }
        list.clear();
    };

    // One tile's samples [s0, s1) of every pixel; those of crop pixels in [first, last) go to
    // the film. False when Ctrl-C cut it short.
    const auto render_tile = [&](const Tile& t, uint64_t s0, uint64_t s1, SplatList& splats) {
        auto sampler = prototype->clone();
        for (int y = t.y0; y < t.y1; ++y) {
            if (y > t.y0 && stopping.cancelled()) return false;
            for (int x = t.x0; x < t.x1; ++x) {
                const int fx = x + spec.crop_x, fy = y + spec.crop_y;  // full-film pixel
                const bool keep = crop.contains(x, y);
                PixelSamples px;
                for (uint64_t s = s0; s < s1; ++s) {
                    sampler->start_pixel_sample(fx, fy, s);
                    // Filter importance sampling: the film position around the pixel centre,
                    // with density proportional to the filter.
                    const FilterSample fs = filter.sample(sampler->next_2d());
                    const Vec2 centre(fx + 0.5, fy + 0.5);
                    const Vec2 raster = centre + fs.offset;
                    const Vec2 u_lambda = sampler->next_2d();
                    const bool counted = keep && s >= first && s < last;
                    SplatList unused;
                    const TracedSample ts = trace_camera_sample(scene, *camera, tracer, spectral_samples, centre,
                                                                raster, u_lambda, *sampler, counted ? splats : unused);
                    if (!counted) continue;  // a pilot sample outside the range: learning only
                    if (!px.add(ts.xyz * fs.weight, named_techniques ? ts.technique : -1)) ++render_stats::saturated;
                }
                if (px.count) result.film.add_samples(x, y, px);
            }
        }
        if (bar) {
            const uint64_t a = std::max(s0, first), b = std::min(s1, last);
            const uint64_t n =
                b > a ? (b - a) * uint64_t(std::max(0, t.width())) * uint64_t(std::max(0, t.height())) : 0;
            bar->add(timed ? 0 : n * uint64_t(team.size()));  // MPI: rank 0's share, scaled
        }
        return true;
    };

    uint64_t done = 0;  // every pixel holds its samples [0, done) (of those this render takes)
    bool stop = false;
    for (int pass = 0; !stop; ++pass) {
        // Splats need whole passes: a chain's deposits stay near its seed (ERPT), so a pass cut
        // short would brighten the tiles it reached against the film-wide normalisation. Such
        // a pass is dropped (unless it is the only one), and equal-time renders use passes of
        // one sample so that little time is lost.
        const uint64_t s0 = done;
        uint64_t s1 = s0 + (splatting && timed ? 1 : pass_size(pass));
        if (s0 >= last) break;
        s1 = std::min(s1, last);
        const bool learning = tracer.learning();
        if (!learning && s1 <= first) {  // before this render's samples: nothing to learn either
            done = s1;
            continue;
        }
        // An MPI job of a fixed sample count needs no barrier between the passes after the
        // learning ones: the film adds exactly, in any order. Its remaining passes run as one,
        // items of 16 samples of one tile handed out chunk by chunk, so the ranks wait for one
        // another once, at the end, instead of at every pass (docs/distributed.md, "Scaling": that
        // wait is the model's load imbalance, half the dearest tile-pass per thread and pass).
        // Not for splatting tracers (a cut pass of theirs is dropped whole) nor in one process,
        // where a cut render keeps exactly the passes it finished (partial films rely on that).
        const bool one_run = team.size() > 1 && !timed && !splatting && !learning && first == 0;
        if (one_run) s1 = last;
        const uint64_t r0 = learning ? s0 : std::max(s0, first);
        std::optional<Film> before_pass;
        if (splatting && done > first) before_pass = result.film;
        bool complete = true;
        if (learning) {
            std::atomic<bool> cut{false};
            // The pilot: tile t is rank t mod N's in every pass, so that each pixel's pilot record
            // is written by one process, in sample order, as in a one-process render.
            std::vector<size_t> mine;
            for (size_t t = size_t(team.rank()); t < pilot_tiles.size(); t += size_t(team.size())) mine.push_back(t);
            for (size_t g0 = 0; g0 < mine.size() && !cut; g0 += std::min(group, mine.size())) {
                const size_t g1 = std::min(mine.size(), g0 + std::min(group, mine.size()));
                std::vector<SplatList> lists(g1 - g0);
                arena.execute([&] {
                    tbb::parallel_for(g0, g1, [&](size_t k) {
                        if (stop_requested() || !render_tile(pilot_tiles[mine[k]], r0, s1, lists[k - g0])) cut = true;
                    });
                });
                for (SplatList& l : lists) merge_splats(l);
            }
            complete = !team.any(cut);
            stop = team.any(stop_requested());
        } else if (one_run) {
            const uint64_t chunk = 16, chunks = (s1 - s0 + chunk - 1) / chunk;
            std::vector<std::mutex> tile_locks(tiles.size());  // a tile's chunks on one thread at a time
            const PassOutcome o = run_team_pass(team, arena, threads, int64_t(tiles.size() * chunks), stop_requested,
                                                group, [&](int64_t item, int) {
                                                    const size_t t = size_t(item) % tiles.size();
                                                    const uint64_t a = s0 + uint64_t(item) / tiles.size() * chunk;
                                                    const std::lock_guard<std::mutex> lock(tile_locks[t]);
                                                    SplatList none;
                                                    return render_tile(tiles[t], a, std::min(s1, a + chunk), none);
                                                });
            stop = o.stop;
            complete = o.complete;
        } else {
            std::vector<SplatList> lists(splatting ? size_t(threads) : 0);
            const PassOutcome o = run_team_pass(
                team, arena, threads, int64_t(tiles.size()), stop_requested, group,
                [&](int64_t t, int slot) {
                    SplatList dummy;
                    return render_tile(tiles[size_t(t)], r0, s1, splatting ? lists[size_t(slot)] : dummy);
                },
                [&] {
                    for (SplatList& l : lists) merge_splats(l);
                });
            stop = o.stop;
            complete = o.complete;
        }
        if (!complete) {
            if (before_pass) result.film = std::move(*before_pass);
            break;
        }
        // MNEE's pilot: every rank's records, summed, before the tracer learns from them.
        if (learning && team.size() > 1 && s1 >= tracer.pilot_samples()) {
            std::vector<double> state = tracer.pilot_state();
            team.sum_exactly(state);
            tracer.set_pilot_state(state);
        }
        done = s1;
        tracer.end_pass(done);
        if (bar && timed) bar->update();
    }
    if (bar) bar->finish();

    result.counters = stat_totals();
    team.reduce(result.film, result.counters);
    result.team = team.times();
    result.seconds = stopping.elapsed();
    result.spp_completed = done > first ? done - first : 0;
    uint64_t total = 0;
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x) total += result.film.samples(x, y);
    result.spp_mean = double(total) / double(std::max(1, crop.width() * crop.height()));
    result.interrupted = cancel && cancel->load() && (timed || done < last);
    if (team.rank() == 0) {
        finish_film(result.film, tracer.max_sample_share(), tracer.clamp_spread());
        result.dominance = pixel_dominance(result.film);
    }
    result.saturated = result.counters[render_stats::saturated];
    result.layer_names = tracer.layer_names();
    result.technique_names = tracer.technique_names();
    return result;
}

}  // namespace snell
