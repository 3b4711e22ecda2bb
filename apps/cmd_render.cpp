// `snell render SCENE -o out.exr [--spp N | --time S] [-D name=value]...` (docs/rendering.md).
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "app_common.h"
#include "commands.h"
#include "integrators/integrator.h"
#include "io/stats_json.h"
#include "manifold/walk_statistics.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace fs = std::filesystem;

namespace snell {

int cmd_render(const std::string& scene_arg, std::string out, int spp, double time_limit, int threads,
               std::optional<uint64_t> seed_arg, double exposure, std::string stats_path, bool quiet,
               const std::vector<std::string>& define_items, bool strategies,
               const std::vector<std::string>& search_path_items) {
    const Defines defines = parse_defines(define_items);
    std::vector<std::string> search_paths;
    for (const std::string& item : search_path_items) {
        size_t start = 0;
        while (start <= item.size()) {
            const size_t end = std::min(item.find(';', start), item.size());
            if (end > start) search_paths.push_back(item.substr(start, end - start));
            start = end + 1;
        }
    }
    LoadedScene ls = load_scene_arg(scene_arg, defines, search_paths);
    const Integrator* integ = ls.integrator.get();
    if (!integ) throw std::runtime_error(scene_arg + ": the scene declares no <integrator>");

    RenderOptions opt;
    opt.spp = spp > 0 ? spp : ls.spp;
    // The scene's own time budget (Mitsuba's integrator `timeout`) unless --spp or --time is given.
    if (time_limit <= 0 && spp <= 0) time_limit = ls.time_limit;
    opt.time_limit = time_limit;
    opt.threads = threads;
    const uint64_t seed = seed_arg ? *seed_arg : ls.seed;  // --seed overrides the scene's <sampler> seed
    opt.seed = seed;
    opt.sampler = ls.sampler;
    opt.progress = !quiet;
    opt.debug_layers = strategies;

    if (out.empty()) out = "out.exr";
    fs::path out_path(out);
    if (out_path.extension() != ".exr") out_path += ".exr";
    if (out_path.has_parent_path()) fs::create_directories(out_path.parent_path());
    fs::path png_path = out_path;
    png_path.replace_extension(".png");
    if (stats_path.empty()) {
        fs::path p = out_path;
        p.replace_extension(".json");
        stats_path = p.string();
    }

    std::signal(SIGINT, on_sigint);
    const int nthreads = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    char budget_buf[64];
    if (time_limit > 0)
        std::snprintf(budget_buf, sizeof(budget_buf), "%g s", time_limit);
    else
        std::snprintf(budget_buf, sizeof(budget_buf), "%d spp", opt.spp);
    const std::string budget = budget_buf;
    if (!quiet)
        std::fprintf(stderr, "snell: %s, integrator %s, %dx%d, %s, %d threads\n", ls.path.c_str(),
                     integ->name().c_str(), ls.film.out_width(), ls.film.out_height(), budget.c_str(), nthreads);
    const RenderResult r = render(*ls.scene, *integ, ls.film, opt, &g_cancel);
    std::signal(SIGINT, SIG_DFL);

    const Image img = film_to_image(r.film);
    write_exr(out_path.string(), img);
    write_png(png_path.string(), img, exposure);
    if (strategies) {
        const std::vector<std::string>& layers = r.layer_names;
        if (layers.empty() && !quiet)
            std::fprintf(stderr, "snell: --strategies: integrator %s has no per-strategy images\n",
                         integ->name().c_str());
        for (size_t k = 0; k < layers.size(); ++k) {
            fs::path p = out_path;
            p.replace_filename(out_path.stem().string() + "_" + layers[k] + ".exr");
            write_exr(p.string(), film_to_image(r.film, int(k) + 1));
        }
        if (!layers.empty() && !quiet)
            std::fprintf(stderr, "snell: wrote %zu strategy images %s_<d_s_t>.exr\n", layers.size(),
                         (out_path.parent_path() / out_path.stem()).c_str());
    }

    RenderReport rep = make_report(ls.path, integ->name(), ls.film.out_width(), ls.film.out_height(), r,
                                   time_limit > 0 ? 0 : uint64_t(opt.spp), time_limit, nthreads, seed);
    rep.beyond_float = r.film.values_beyond_float();
    if (!quiet && rep.extra.contains("mnee")) std::fprintf(stderr, "%s", mnee_stats_text(r.counters).c_str());
    write_stats_json(stats_path, rep);

    const double s = std::max(r.seconds, 1e-9);
    if (!quiet || r.interrupted)
        std::fprintf(stderr,
                     "snell: %s%.2f s, %llu spp (mean %.1f), %.3g paths/s, %.3g rays/s; discarded NaN %llu, Inf %llu, "
                     "negative %llu; beyond float32 %llu\n  wrote %s, %s, %s\n",
                     r.interrupted ? "INTERRUPTED after " : "", r.seconds, (unsigned long long)r.spp_completed,
                     r.spp_mean, double(rep.paths) / s, double(rep.rays + rep.shadow_rays) / s,
                     (unsigned long long)rep.discarded_nan, (unsigned long long)rep.discarded_inf,
                     (unsigned long long)rep.discarded_negative, (unsigned long long)rep.beyond_float, out_path.c_str(),
                     png_path.c_str(), stats_path.c_str());
    if (!quiet && r.film.max_sample_share() > 0) {
        if (r.film.spread_radius() > 0)
            std::fprintf(stderr,
                         "  outlier clamp (max_sample_share %.2g): %llu pixels, %.3g %% of the luminance spread over "
                         "neighbours (discs up to %d px; clamp_spread %d), %.3g %% removed (%llu pixels)\n",
                         r.film.max_sample_share(), (unsigned long long)rep.pixels_clamped, 100 * rep.spread_share,
                         rep.spread_radius, r.film.spread_radius(), 100 * (rep.clamped_share - rep.spread_share),
                         (unsigned long long)rep.spread_dropped);
        else
            std::fprintf(stderr,
                         "  outlier clamp (max_sample_share %.2g): %llu pixels, %.3g %% of the luminance removed\n",
                         r.film.max_sample_share(), (unsigned long long)rep.pixels_clamped, 100 * rep.clamped_share);
    }
    if (!quiet && !rep.dominated_by_technique.empty()) {
        std::string by;
        for (const auto& [name, n] : rep.dominated_by_technique)
            by += (by.empty() ? "" : ", ") + name + " " + std::to_string(n);
        std::fprintf(stderr, "  pixels dominated by one sample: %llu; by technique: %s\n",
                     (unsigned long long)rep.pixels_dominated, by.c_str());
    }
    return r.interrupted ? 130 : 0;
}

}  // namespace snell
