#pragma once
// Partial films (issue 27): what a farm task renders (`snell render --crop ... --sample-range
// ...`) and `snell merge` adds into the frame one render would have written. A partial film is
// an EXR: R, G, B hold the task's own estimate, for a look; the `snell.*` channels hold the
// film's exact sums (ExactSum's 192 bits as six 32-bit channels each), the sample counts, each
// pixel's largest sample and its technique; the `snell.partial` header attribute (JSON) says
// what render it is a part of. Merging adds the exact sums, so crops and sample ranges merge
// into the single render's film bit for bit, in any order.
#include <cstdint>
#include <string>
#include <vector>

#include "camera/film.h"
#include "render/render_team.h"

namespace snell {

/// What identifies the render a partial film belongs to, and which part of it it holds.
struct PartialFilmInfo {
    // The render: partial films merge only when all of these agree.
    std::string scene_hash;  ///< of the scene file's bytes, the defines and the film's settings
    std::string integrator;
    uint64_t seed = 0;
    int width = 0, height = 0;  ///< the film's output window
    uint64_t spp = 0;           ///< the full render's samples per pixel
    int spectral_samples = 0;
    double max_sample_share = 0;  ///< the outlier clamp, applied after the merge
    int clamp_spread = 0;
    std::vector<std::string> technique_names, layer_names;
    // The part.
    PixelRect crop;
    uint64_t sample_begin = 0, sample_end = 0;
};

struct PartialFilm {
    Film film{1, 1};
    PartialFilmInfo info;
};

/// Writes `film` (its accumulated values; no clamp) as a partial film EXR. Throws on I/O errors.
void write_partial_film(const std::string& path, const Film& film, const PartialFilmInfo& info);
/// Reads a partial film; throws std::runtime_error naming the file when it is not one.
PartialFilm read_partial_film(const std::string& path);

/// Adds partial films into one. Refuses (std::runtime_error naming both files) films of
/// different renders (scene, integrator, seed, size, spp, settings) and films whose parts
/// overlap (a pixel's sample taken twice). `coverage` is set to the share of the frame's
/// pixel samples the parts hold (1: the whole frame). The result's clamp is applied (finish_film).
PartialFilm merge_partial_films(const std::vector<std::string>& paths, double* coverage = nullptr);

/// FNV-1a over bytes: the scene hash of partial films.
uint64_t fnv1a(const std::string& bytes, uint64_t h = 1469598103934665603ull);

}  // namespace snell
