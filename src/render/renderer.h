#pragma once
#include <atomic>
#include <cstdint>

#include "camera/camera.h"
#include "camera/film.h"
#include "core/stats.h"
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
    bool debug_layers = false;  ///< integrators fill their debug layers (BDPT: per-strategy images)
};

struct RenderResult {
    Film film{1, 1};
    double seconds = 0;
    uint64_t spp_completed = 0;  ///< samples every pixel received (complete passes)
    double spp_mean = 0;         ///< mean samples per pixel, partial passes included
    bool interrupted = false;    ///< cancelled (Ctrl-C) before the requested spp
    /// Every registered statistic (core/stats.h), summed over the threads of the render.
    StatTotals counters;
    std::vector<std::string> layer_names;      ///< names of the film's debug layers 1, 2, ...
    PixelDominance dominance;                  ///< camera samples only (splats are not a pixel's samples)
    std::vector<std::string> technique_names;  ///< of dominance.dominated_by_technique's indices
};

/// The shared render loop of per-pixel-sample estimators: progressive passes over tiles with
/// TBB. Every pixel sample draws from its own random stream (seed, pixel, index) of the
/// options' sampler, its film position from the pixel's reconstruction filter (importance
/// sampled), then `spectral_samples` wavelengths; pixel sums are accumulated in a fixed order,
/// so the result does not depend on the thread count. Samples that are NaN, infinite or
/// negative are counted and replaced by zero so that nothing invalid reaches the film.
RenderResult render_tiles(const Scene& scene, SampleTracer& tracer, int spectral_samples, const FilmSpec& film,
                          const RenderOptions& options, const std::atomic<bool>* cancel = nullptr);

}  // namespace snell
