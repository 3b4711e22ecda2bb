#pragma once
#include <atomic>
#include <cstdint>

#include "camera/camera.h"
#include "camera/film.h"
#include "core/stats.h"
#include "render/render_team.h"
#include "render/sample_tracer.h"
#include "sampler/factory.h"

namespace snell {

class Scene;

struct RenderOptions {
    int spp = 16;           ///< samples per pixel (spp mode)
    double time_limit = 0;  ///< > 0: render until this many seconds have passed (equal-time mode)
    int threads = 0;        ///< 0: all hardware threads
    uint64_t seed = 0;      ///< sampler seed; the image is a pure function of (scene, seed, spp)
    SamplerSpec sampler;  ///< pixel sampler (the scene's <sampler> type); built with create_sampler(sampler, spp, seed)
    bool progress = true;  ///< progress bar on a terminal
    int tile_size = 16;
    bool debug_layers = false;    ///< integrators fill their debug layers (BDPT: per-strategy images)
    bool progress_lines = false;  ///< progress as machine-readable lines on stdout (render farms)
    /// Where the render keeps its fraction done (null: nowhere), for a caller that shows progress
    /// its own way (the Python module's callback, python/src/render_call.cpp).
    std::atomic<double>* progress_fraction = nullptr;
    /// The part of the frame to render (issue 27): a crop of the output window (empty: all of
    /// it) and the sample indices [sample_begin, sample_end) of each of its pixels (sample_end
    /// 0: spp). A full render is the exact sum of renders of any split of its pixels and samples.
    PixelRect crop;
    uint64_t sample_begin = 0, sample_end = 0;
    /// The processes rendering the frame together (null: process_team(), an MPI job's or this
    /// process alone). Only rank 0's result holds the whole film.
    RenderTeam* team = nullptr;
};

struct RenderResult {
    Film film{1, 1};
    double seconds = 0;
    uint64_t spp_completed = 0;  ///< samples every pixel received (complete passes)
    double spp_mean = 0;         ///< mean samples per pixel, partial passes included (of the crop)
    uint64_t saturated = 0;      ///< sample values beyond the film's exact range, saturated (ExactSum)
    bool interrupted = false;    ///< cancelled (Ctrl-C) before the requested spp
    /// Every registered statistic (core/stats.h), summed over the threads of the render.
    StatTotals counters;
    std::vector<std::string> layer_names;      ///< names of the film's debug layers 1, 2, ...
    PixelDominance dominance;                  ///< camera samples only (splats are not a pixel's samples)
    std::vector<std::string> technique_names;  ///< of dominance.dominated_by_technique's indices
    TeamTimes team;                            ///< where an MPI job's time went (rank 0)
};

/// The shared render loop of per-pixel-sample estimators: progressive passes over tiles with
/// TBB, the tiles of each pass handed out by the team (threads of one process, or MPI ranks).
/// Every pixel sample draws from its own random stream (seed, pixel, index) of the options'
/// sampler, its film position from the pixel's reconstruction filter (importance sampled), then
/// `spectral_samples` wavelengths; pixel sums are exact (ExactSum), so the result depends on
/// neither the thread count, nor the ranks, nor how the frame is split into crops and sample
/// ranges. Samples that are NaN, infinite or negative are counted and replaced by zero so that
/// nothing invalid reaches the film. The outlier clamp (the tracer's max_sample_share) is a
/// post-process of the reduced film (finish_film).
RenderResult render_tiles(const Scene& scene, SampleTracer& tracer, int spectral_samples, const FilmSpec& film,
                          const RenderOptions& options, const std::atomic<bool>* cancel = nullptr);

/// The post-process of a finished film (after the reduction over ranks, or a merge of partial
/// films): the splat scale from the camera samples the film holds and the outlier clamp.
void finish_film(Film& film, double max_sample_share, int clamp_spread);

}  // namespace snell
