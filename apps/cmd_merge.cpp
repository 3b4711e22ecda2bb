// `snell merge part*.exr -o frame.exr`: the partial films of farm tasks (`snell render --crop
// ... --sample-range ...`) added into the frame one render writes (docs/distributed.md).
#include <cstdio>
#include <filesystem>

#include "app_common.h"
#include "commands.h"
#include "output_files.h"
#include "render/partial_film.h"

namespace fs = std::filesystem;

namespace snell {

int cmd_merge(const std::vector<std::string>& parts, std::string out, double exposure, std::string stats_path,
              bool quiet, bool make_dirs) {
    double coverage = 0;
    const PartialFilm merged = merge_partial_films(parts, &coverage);
    const OutputFiles files = output_files(out, stats_path, "merged.exr", make_dirs);
    const fs::path &out_path = files.exr, &png_path = files.png;
    stats_path = files.stats.string();

    const Image img = film_to_image(merged.film);
    if (!out_path.empty()) write_exr(out_path.string(), img);
    write_png(png_path.string(), img, exposure);
    // The report of the merged film: what the film itself says (the parts' counters stay in
    // their own stats files).
    RenderResult r;
    r.film = merged.film;
    r.dominance = pixel_dominance(merged.film);
    r.technique_names = merged.info.technique_names;
    uint64_t least = UINT64_MAX, total = 0;
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) {
            least = std::min(least, r.film.samples(x, y));
            total += r.film.samples(x, y);
        }
    r.spp_completed = least == UINT64_MAX ? 0 : least;
    r.spp_mean = double(total) / double(std::max(1, r.film.width() * r.film.height()));
    RenderReport rep =
        make_report("merge of " + std::to_string(parts.size()) + " partial films", merged.info.integrator,
                    merged.info.width, merged.info.height, r, merged.info.spp, 0, 0, merged.info.seed);
    rep.beyond_float = r.film.values_beyond_float();
    rep.extra["merge"] = {{"parts", parts}, {"coverage", coverage}, {"scene_hash", merged.info.scene_hash}};
    write_stats_json(stats_path, rep);
    if (coverage < 1 - 1e-12)
        std::fprintf(stderr, "snell: warning: the parts hold %.4g %% of the frame's pixel samples\n", 100 * coverage);
    if (!quiet)
        std::fprintf(stderr, "snell: merged %zu partial films (%s, %dx%d, %llu spp)\n  wrote %s%s%s, %s\n",
                     parts.size(), merged.info.integrator.c_str(), merged.info.width, merged.info.height,
                     (unsigned long long)merged.info.spp, out_path.c_str(), out_path.empty() ? "" : ", ",
                     png_path.c_str(), stats_path.c_str());
    return kExitOk;
}

}  // namespace snell
