#pragma once
// Machine-readable summary of one render, written beside the image so that experiments can
// be tabulated (time, sample counts, throughput, discarded samples, technique statistics).
#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/stats.h"

namespace snell {

/// What a render did. Times are wall-clock seconds; counts are totals over all threads.
struct RenderReport {
    std::string scene;       ///< scene file path as given on the command line
    std::string integrator;  ///< integrator name, e.g. "path", "mnee"
    int width = 0, height = 0;
    uint64_t spp_requested = 0;  ///< samples per pixel asked for (0: time-limited render)
    uint64_t spp_reached = 0;    ///< samples per pixel every pixel actually received
    double spp_mean = 0;         ///< mean samples per pixel, partial passes included
    double seconds = 0;          ///< wall-clock render time, scene loading excluded
    double time_limit = 0;       ///< --time budget in seconds (0: spp mode)
    bool interrupted = false;    ///< stopped by Ctrl-C before completion
    int threads = 0;
    uint64_t seed = 0;
    uint64_t paths = 0;               ///< camera paths traced
    uint64_t rays = 0;                ///< closest-hit queries
    uint64_t shadow_rays = 0;         ///< any-hit (visibility) queries
    uint64_t discarded_nan = 0;       ///< samples dropped as NaN
    uint64_t discarded_inf = 0;       ///< samples dropped as infinite
    uint64_t discarded_negative = 0;  ///< samples dropped as negative
    uint64_t beyond_float = 0;        ///< image values beyond float32's range, written as its largest
    uint64_t saturated = 0;           ///< sample values beyond the film's exact range (2^80), saturated
    int ranks = 1;                    ///< MPI ranks that rendered the frame (1: one process)
    /// Pixel dominance (render/renderer.h PixelDominance), written under "dominance": pixels
    /// with a positive sum, those where one sample carries more than half of it, and the
    /// largest such share; with an outlier clamp (max_sample_share), the pixels it scaled
    /// down and the share of the luminance it took from them; with its spread, the share of
    /// the luminance spread back over neighbours and the widest disc (pixels) used.
    uint64_t pixels = 0, pixels_dominated = 0, pixels_outlier = 0, pixels_clamped = 0;
    double max_sample_share = 0, clamped_share = 0, spread_share = 0;
    int spread_radius = 0;
    uint64_t spread_dropped = 0;
    /// Dominated pixels by the technique that delivered their largest sample (integrators that
    /// name their techniques: the path-tracing family, pt, path, nee, direct, mnee; empty for
    /// the others); "dominance.by_technique".
    std::map<std::string, uint64_t> dominated_by_technique;
    /// Free-form technique statistics (e.g. MNEE walk outcomes); written under "extra".
    nlohmann::json extra = nlohmann::json::object();
    /// Every registered statistic by name (core/stats.h): a count, nanoseconds, a histogram's
    /// bins as an array (trailing empty bins left out), or moments as {count, mean,
    /// relative_variance, max}; written under "counters".
    nlohmann::json counters = nlohmann::json::object();

    /// Copies the ray/path/discard counts ("render.paths", "scene.rays", ...) and every
    /// registered statistic (into `counters`) from a snapshot of the statistics registry.
    void set_counters(const StatTotals& t);
    /// Camera paths per wall-clock second (0 when no time was measured).
    double paths_per_second() const;
    /// All ray queries (closest-hit plus shadow) per wall-clock second (0 when no time).
    double rays_per_second() const;
};

/// JSON object with every field above plus the derived "paths_per_second" and
/// "rays_per_second" (found by nlohmann via ADL: `nlohmann::json j = report;`).
void to_json(nlohmann::json& j, const RenderReport& r);
/// Inverse of to_json; derived rates are ignored, missing keys keep their defaults.
void from_json(const nlohmann::json& j, RenderReport& r);

/// Writes the report as indented JSON; throws std::runtime_error naming the path on failure.
void write_stats_json(const std::string& path, const RenderReport& report);

}  // namespace snell
