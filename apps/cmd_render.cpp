// `snell render SCENE -o out.exr [--spp N | --time S] [-D name=value]...` (docs/rendering.md),
// in one process or as one rank of an MPI job, whole or as a farm task's partial film
// (docs/distributed.md).
#include <algorithm>
#include <cctype>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "app_common.h"
#include "commands.h"
#include "integrators/integrator.h"
#include "io/stats_json.h"
#include "manifold/walk_statistics.h"
#include "output_files.h"
#include "render/partial_film.h"
#include "render/renderer.h"
#include "render/team_pass.h"
#include "scene/scene.h"

namespace fs = std::filesystem;

namespace snell {

namespace {

// --crop x,y,w,h in the film's output window.
PixelRect parse_task_crop(const std::string& text) {
    long long v[4];
    char tail = 0;
    if (std::sscanf(text.c_str(), "%lld,%lld,%lld,%lld%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4 || v[0] < 0 ||
        v[1] < 0 || v[2] <= 0 || v[3] <= 0 || v[0] + v[2] > INT32_MAX || v[1] + v[3] > INT32_MAX)
        throw std::runtime_error("--crop must be x,y,w,h (pixels; x, y >= 0, w, h > 0), got '" + text + "'");
    return {int(v[0]), int(v[1]), int(v[0] + v[2]), int(v[1] + v[3])};
}

// --sample-range a:b: sample indices a ... b-1 of every pixel.
std::pair<uint64_t, uint64_t> parse_sample_range(const std::string& text) {
    unsigned long long a = 0, b = 0;
    char tail = 0;
    if (text.empty() || text[0] == '-' || std::sscanf(text.c_str(), "%llu:%llu%c", &a, &b, &tail) != 2 || !(a < b))
        throw std::runtime_error("--sample-range must be a:b with 0 <= a < b (sample indices a ... b-1), got '" + text +
                                 "'");
    return {a, b};
}

// The scene hash of partial films: the scene's bytes (the file, or the built-in's text), the
// defines, and what else changes the image without being in the file.
std::string scene_hash(const std::string& scene_arg, const Defines& defines, const LoadedScene& ls) {
    std::string bytes;
    if (std::FILE* f = std::fopen(scene_arg.c_str(), "rb")) {
        char buf[65536];
        size_t n;
        while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) bytes.append(buf, n);
        std::fclose(f);
    } else {
        bytes = scene_arg;
    }
    for (const auto& [k, v] : defines) bytes += "\n-D " + k + "=" + v;
    bytes += "\nsampler " + ls.sampler.type + " film " + std::to_string(ls.film.out_width()) + "x" +
             std::to_string(ls.film.out_height()) + "+" + std::to_string(ls.film.crop_x) + "," +
             std::to_string(ls.film.crop_y);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)fnv1a(bytes));
    return hex;
}

}  // namespace

std::string output_name(const std::string& out, const std::optional<std::string>& frame) {
    const size_t pct = out.find('%');
    if (pct == std::string::npos) return out;
    size_t i = pct + 1;
    int width = 0;
    bool zero = false;
    if (i < out.size() && out[i] == '0') zero = true, ++i;
    while (i < out.size() && std::isdigit((unsigned char)out[i]) && width < 100) width = width * 10 + (out[i++] - '0');
    if (i >= out.size() || out[i] != 'd' || out.find('%', i) != std::string::npos)
        throw std::runtime_error("-o " + out + ": the only pattern an output name may hold is one %d or %0Nd");
    if (!frame) throw std::runtime_error("-o " + out + " holds a frame pattern: give the frame with -D frame=N");
    char* end = nullptr;
    const long long n = std::strtoll(frame->c_str(), &end, 10);
    if (frame->empty() || *end != '\0' || n < 0)
        throw std::runtime_error("-D frame=" + *frame + ": a frame is a non-negative integer");
    std::string digits = std::to_string(n);
    if (int(digits.size()) < width) digits.insert(0, size_t(width) - digits.size(), zero ? '0' : ' ');
    return out.substr(0, pct) + digits + out.substr(i + 1);
}

int cmd_render(const RenderCommandOptions& o) {
    const std::string& scene_arg = o.scene;
    const int spp = o.spp, threads = o.threads;
    double time_limit = o.time_limit;
    const bool quiet = o.quiet, strategies = o.strategies;
    const double exposure = o.exposure;
    std::string stats_path = o.stats_path;
    const Defines defines = parse_defines(o.defines);
    RenderTeam& team = process_team();
    const bool lead = team.rank() == 0;  // rank 0 writes and reports
    std::vector<std::string> search_paths;
    for (const std::string& item : o.search_paths) {
        size_t start = 0;
        while (start <= item.size()) {
            const size_t end = std::min(item.find(';', start), item.size());
            if (end > start) search_paths.push_back(item.substr(start, end - start));
            start = end + 1;
        }
    }
    const auto frame = defines.count("frame") ? std::optional<std::string>(defines.at("frame")) : std::nullopt;
    std::string out = output_name(o.out, frame);
    const bool partial = !o.crop.empty() || !o.sample_range.empty();
    if (partial && team.size() > 1)
        throw std::runtime_error(
            "--crop and --sample-range are farm tasks of one process each; under MPI the ranks "
            "split the frame themselves");
    LoadedScene ls = load_scene_arg(scene_arg, defines, search_paths);
    const Integrator* integ = ls.integrator.get();
    if (!integ) throw std::runtime_error(scene_arg + ": the scene declares no <integrator>");

    RenderOptions opt;
    opt.spp = spp > 0 ? spp : ls.spp;
    // The scene's own time budget (Mitsuba's integrator `timeout`) unless --spp or --time is given.
    if (time_limit <= 0 && spp <= 0) time_limit = ls.time_limit;
    opt.time_limit = time_limit;
    opt.threads = threads;
    const uint64_t seed = o.seed ? *o.seed : ls.seed;  // --seed overrides the scene's <sampler> seed
    opt.seed = seed;
    opt.sampler = ls.sampler;
    opt.progress = !quiet && o.progress == "bar";
    opt.progress_lines = o.progress == "lines";
    opt.debug_layers = strategies;
    if (!o.crop.empty()) opt.crop = parse_task_crop(o.crop);
    if (!o.sample_range.empty()) {
        if (time_limit > 0) throw std::runtime_error("--sample-range needs a sample count, not a time budget");
        std::tie(opt.sample_begin, opt.sample_end) = parse_sample_range(o.sample_range);
        if (opt.sample_end > uint64_t(opt.spp))
            throw std::runtime_error("--sample-range " + o.sample_range + " reaches past the render's " +
                                     std::to_string(opt.spp) + " spp (set them with --spp)");
    }
    if (partial && time_limit > 0)
        throw std::runtime_error("a partial film (--crop, --sample-range) needs a sample count, not a time budget");

    const OutputFiles files = output_files(out, stats_path, "out.exr", o.make_dirs, partial);
    const fs::path& out_path = files.exr;
    const fs::path& png_path = files.png;
    stats_path = files.stats.string();

    std::signal(SIGINT, on_sigint);
    std::signal(SIGTERM, on_sigint);  // mpirun and farm managers stop a job with SIGTERM
    const int nthreads = render_threads(opt);
    char budget_buf[64];
    if (time_limit > 0)
        std::snprintf(budget_buf, sizeof(budget_buf), "%g s", time_limit);
    else
        std::snprintf(budget_buf, sizeof(budget_buf), "%d spp", opt.spp);
    const std::string budget = budget_buf;
    if (!quiet && lead)
        std::fprintf(stderr, "snell: %s, integrator %s, %dx%d, %s, %d threads%s\n", ls.path.c_str(),
                     integ->name().c_str(), ls.film.out_width(), ls.film.out_height(), budget.c_str(), nthreads,
                     team.size() > 1 ? (" x " + std::to_string(team.size()) + " ranks").c_str() : "");
    const RenderResult r = render(*ls.scene, *integ, ls.film, opt, &g_cancel);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (!lead) return r.interrupted ? kExitInterrupted : kExitOk;

    if (partial) {
        PartialFilmInfo info;
        info.scene_hash = scene_hash(scene_arg, defines, ls);
        info.integrator = integ->name();
        info.seed = seed;
        info.width = ls.film.out_width();
        info.height = ls.film.out_height();
        info.spp = uint64_t(opt.spp);
        info.spectral_samples = integ->spectral_samples();
        info.max_sample_share = r.film.max_sample_share();
        info.clamp_spread = r.film.spread_radius();
        info.technique_names = r.technique_names;
        info.layer_names = r.layer_names;
        info.crop = opt.crop.empty() ? PixelRect{0, 0, info.width, info.height} : opt.crop;
        info.sample_begin = opt.sample_begin;
        info.sample_end = opt.sample_end > 0 ? opt.sample_end : info.spp;
        if (r.interrupted) info.sample_end = info.sample_begin + r.spp_completed;  // what every pixel holds
        if (info.sample_end > info.sample_begin) write_partial_film(out_path.string(), r.film, info);
        RenderReport rep =
            make_report(ls.path, integ->name(), info.width, info.height, r, uint64_t(opt.spp), 0, nthreads, seed);
        write_stats_json(stats_path, rep);
        if (!quiet || r.interrupted)
            std::fprintf(stderr,
                         "snell: %s%.2f s; partial film of pixels %d,%d,%d,%d, samples %llu:%llu\n  wrote %s, %s\n",
                         r.interrupted ? "INTERRUPTED after " : "", r.seconds, info.crop.x0, info.crop.y0,
                         info.crop.width(), info.crop.height(), (unsigned long long)info.sample_begin,
                         (unsigned long long)info.sample_end, out_path.c_str(), stats_path.c_str());
        return r.interrupted ? kExitInterrupted : kExitOk;
    }

    const Image img = film_to_image(r.film);
    if (!out_path.empty()) write_exr(out_path.string(), img);
    write_png(png_path.string(), img, exposure);
    if (strategies) {
        const std::vector<std::string>& layers = r.layer_names;
        if (layers.empty() && !quiet)
            std::fprintf(stderr, "snell: --strategies: integrator %s has no per-strategy images\n",
                         integ->name().c_str());
        for (size_t k = 0; k < layers.size(); ++k) {
            write_exr(files.stem().string() + "_" + layers[k] + ".exr", film_to_image(r.film, int(k) + 1));
        }
        if (!layers.empty() && !quiet)
            std::fprintf(stderr, "snell: wrote %zu strategy images %s_<d_s_t>.exr\n", layers.size(),
                         files.stem().c_str());
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
                     "negative %llu; beyond float32 %llu\n  wrote %s%s%s, %s\n",
                     r.interrupted ? "INTERRUPTED after " : "", r.seconds, (unsigned long long)r.spp_completed,
                     r.spp_mean, double(rep.paths) / s, double(rep.rays + rep.shadow_rays) / s,
                     (unsigned long long)rep.discarded_nan, (unsigned long long)rep.discarded_inf,
                     (unsigned long long)rep.discarded_negative, (unsigned long long)rep.beyond_float, out_path.c_str(),
                     out_path.empty() ? "" : ", ", png_path.c_str(), stats_path.c_str());
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
    return r.interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace snell
