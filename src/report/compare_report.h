#pragma once
// Everything `snell compare` measured, in one structure: written as report.json and rendered as
// report.html. Image paths are relative to the report folder so the folder can be moved.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/stats_json.h"
#include "report/image_metrics.h"

namespace snell {

/// Metrics of one image region against the reference.
struct RegionMetrics {
    std::string region;  ///< "image" or "crop x,y,w,h"
    Crop crop;           ///< w == 0 for the whole image
    ImageMetrics metrics;
};

/// One point of a convergence curve: a render stopped at `time_limit` seconds.
struct ConvergencePoint {
    double time_limit = 0;  ///< budget asked for (s)
    double seconds = 0;     ///< time actually rendered (s)
    double spp_mean = 0;    ///< mean samples per pixel reached
    ImageMetrics metrics;   ///< whole image against the reference
};

/// One technique of the comparison.
struct IntegratorResult {
    std::string name;                             ///< as given on the command line, e.g. "mnee-biased"
    std::string type;                             ///< integrator type it was built as, e.g. "mnee"
    bool biased = false;                          ///< mnee's biased outlier removal switched on
    RenderReport stats;                           ///< the equal-time render (MNEE walk statistics under extra["mnee"])
    std::vector<RegionMetrics> regions;           ///< [0] is the whole image, then the crops in order
    std::vector<ConvergencePoint> convergence;    ///< increasing time; the last is the equal-time render
    std::string image_exr, image_png, error_png;  ///< relative to the report folder
    std::vector<std::string> crop_pngs;           ///< enlarged crops, one per crop
    /// Why the result is shown but not ranked ("interrupted after 0.3 s", "drew no sample"); empty
    /// when it ran its whole budget and every pixel holds a sample (issue 30: `--time 1e-300` and
    /// Ctrl-C ranked integrators that drew nothing).
    std::string unranked;
    bool ranked() const { return unranked.empty(); }
};

/// Where the reference came from.
struct ReferenceInfo {
    std::string source;      ///< "file" (--reference) or "render"
    std::string file;        ///< the --reference path, if any
    std::string integrator;  ///< reference integrator when rendered
    uint64_t spp = 0;        ///< --reference-spp (0: time-limited)
    double time_limit = 0;   ///< --reference-time (0: spp mode)
    RenderReport stats;      ///< when rendered
    std::string image_exr, image_png;
    std::vector<std::string> crop_pngs;
};

struct CompareReport {
    std::string scene;
    std::vector<std::string> defines;  ///< -D name=value as given
    /// The scored window: the whole film, or with a reference rendered on a crop of the film
    /// (--reference-offset) that crop, at (window_x, window_y) of the film. Every image, error map
    /// and metric of the report covers the window; `crops` are in its coordinates.
    int width = 0, height = 0;
    int window_x = 0, window_y = 0;
    int film_width = 0, film_height = 0;  ///< the rendered film (0: the window is the film)
    /// Whether the report covers a window of the film rather than all of it.
    bool windowed() const { return film_width > 0 && (width != film_width || height != film_height); }
    /// A rectangle of the window in the film's coordinates (Crop{}, the whole window, as it is).
    Crop in_film(const Crop& c) const { return c.w > 0 ? Crop{c.x + window_x, c.y + window_y, c.w, c.h} : c; }
    double time_budget = 0;  ///< equal-time budget per integrator (s)
    int threads = 0;
    uint64_t seed = 0;
    double exposure = 0;   ///< PNG exposure in stops
    double error_max = 1;  ///< relative error shown as the top of the false-colour map
    std::vector<Crop> crops;
    std::vector<int> crop_scales;  ///< enlargement factor of each crop's PNGs
    ReferenceInfo reference;
    std::vector<IntegratorResult> integrators;  ///< in command-line order

    /// Indices into `integrators`: the ranked ones by whole-image PSNR, best (highest) first (ties
    /// keep order), then the unranked ones in command-line order.
    std::vector<size_t> order_by_psnr() const;
    /// How many results are ranked (the first ones of order_by_psnr()).
    size_t ranked_count() const;
};

/// JSON of the metrics (non-finite PSNR, e.g. identical images, becomes null).
nlohmann::json metrics_json(const ImageMetrics& m);
/// Every number of the report; integrators carry "rank" (1 = best PSNR; null, with "unranked"
/// saying why, for a result that is not ranked).
nlohmann::json report_json(const CompareReport& r);

}  // namespace snell
