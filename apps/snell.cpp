// The `snell` command: `snell render SCENE -o out.exr [--spp N | --time S] [-D name=value]...`.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <thread>

#include "builtin_scenes.h"
#include "camera/film.h"
#include "core/props.h"
#include "geometry/scene.h"
#include "integrators/integrator.h"
#include "io/image.h"
#include "io/image_metrics.h"
#include "io/scene_loader.h"
#include "io/stats_json.h"
#include "manifold/walk_statistics.h"
#include "render/renderer.h"

namespace fs = std::filesystem;
using namespace snell;

namespace {

std::atomic<bool> g_cancel{false};

// First Ctrl-C: stop rendering and write what we have. Second: leave at once.
extern "C" void on_sigint(int) {
    if (g_cancel.exchange(true)) std::_Exit(130);
}

LoadedScene load(const std::string& scene_arg, const Defines& defines) {
    const std::string prefix = "builtin:";
    if (scene_arg.rfind(prefix, 0) == 0) {
        const std::string name = scene_arg.substr(prefix.size());
        const std::string* xml = builtin_scene(name);
        if (!xml) {
            std::string known;
            for (auto& n : builtin_scene_names()) known += " builtin:" + n;
            throw std::runtime_error("unknown built-in scene '" + scene_arg + "' (known:" + known + ")");
        }
        return load_scene_string(*xml, scene_arg, fs::current_path().string(), defines);
    }
    return load_scene_file(scene_arg, defines);
}

Defines parse_defines(const std::vector<std::string>& items) {
    Defines d;
    for (const std::string& it : items) {
        const auto eq = it.find('=');
        if (eq == std::string::npos || eq == 0)
            throw CLI::ValidationError("-D", "expected name=value, got '" + it + "'");
        d[it.substr(0, eq)] = it.substr(eq + 1);
    }
    return d;
}

Image film_to_image(const Film& film) {
    Image img;
    img.width = film.width();
    img.height = film.height();
    img.rgb = film.to_linear_srgb();
    return img;
}

int cmd_render(const std::string& scene_arg, std::string out, int spp, double time_limit, int threads,
               std::optional<uint64_t> seed_arg, double exposure, std::string stats_path, bool quiet,
               const std::vector<std::string>& define_items) {
    const Defines defines = parse_defines(define_items);
    LoadedScene ls = load(scene_arg, defines);
    const Integrator* integ = ls.scene->integrator().get();
    if (!integ) throw std::runtime_error(scene_arg + ": the scene declares no <integrator>");

    RenderOptions opt;
    opt.spp = spp > 0 ? spp : ls.spp;
    opt.time_limit = time_limit;
    opt.threads = threads;
    const uint64_t seed = seed_arg ? *seed_arg : ls.seed;  // --seed overrides the scene's <sampler> seed
    opt.seed = seed;
    opt.progress = !quiet;

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
    if (time_limit > 0) std::snprintf(budget_buf, sizeof(budget_buf), "%g s", time_limit);
    else std::snprintf(budget_buf, sizeof(budget_buf), "%d spp", opt.spp);
    const std::string budget = budget_buf;
    if (!quiet)
        std::fprintf(stderr, "snell: %s, integrator %s, %dx%d, %s, %d threads\n", ls.path.c_str(), integ->name().c_str(),
                     ls.film.out_width(), ls.film.out_height(),
                     budget.c_str(),
                     nthreads);
    const RenderResult r = render(*ls.scene, *integ, ls.film, opt, &g_cancel);
    std::signal(SIGINT, SIG_DFL);

    const Image img = film_to_image(r.film);
    write_exr(out_path.string(), img);
    write_png(png_path.string(), img, exposure);

    RenderReport rep;
    rep.scene = ls.path;
    rep.integrator = integ->name();
    rep.width = ls.film.out_width();
    rep.height = ls.film.out_height();
    rep.spp_requested = time_limit > 0 ? 0 : opt.spp;
    rep.spp_reached = r.spp_completed;
    rep.spp_mean = r.spp_mean;
    rep.seconds = r.seconds;
    rep.time_limit = time_limit;
    rep.threads = nthreads;
    rep.seed = seed;
    rep.interrupted = r.interrupted;
    rep.paths = r.counters.paths;
    rep.rays = r.counters.rays;
    rep.shadow_rays = r.counters.shadow_rays;
    rep.discarded_nan = r.counters.discarded_nan;
    rep.discarded_inf = r.counters.discarded_inf;
    rep.discarded_negative = r.counters.discarded_negative;
    const Counters& c = r.counters;
    if (c.walks_started > 0 || c.pdf_walks > 0) {
        rep.extra["mnee"] = mnee_stats_json(c);
        if (!quiet) std::fprintf(stderr, "%s", mnee_stats_text(c).c_str());
    }
    write_stats_json(stats_path, rep);

    const double s = std::max(r.seconds, 1e-9);
    if (!quiet || r.interrupted)
        std::fprintf(stderr,
                 "snell: %s%.2f s, %llu spp (mean %.1f), %.3g paths/s, %.3g rays/s; discarded NaN %llu, Inf %llu, "
                 "negative %llu\n  wrote %s, %s, %s\n",
                 r.interrupted ? "INTERRUPTED after " : "", r.seconds, (unsigned long long)r.spp_completed,
                 r.spp_mean, r.counters.paths / s, (r.counters.rays + r.counters.shadow_rays) / s,
                 (unsigned long long)r.counters.discarded_nan, (unsigned long long)r.counters.discarded_inf,
                 (unsigned long long)r.counters.discarded_negative, out_path.c_str(), png_path.c_str(),
                 stats_path.c_str());
    return r.interrupted ? 130 : 0;
}

// `snell diff a.exr b.exr [--crop x,y,w,h]...`: metrics of a against the reference b.
int cmd_diff(const std::string& a_path, const std::string& b_path, const std::vector<std::string>& crops, bool json) {
    const Image a = read_exr(a_path), b = read_exr(b_path);
    std::vector<std::pair<std::string, Crop>> regions = {{"image", Crop{}}};
    for (const std::string& c : crops) regions.push_back({"crop " + c, parse_crop(c)});
    nlohmann::json out = nlohmann::json::array();
    for (const auto& [name, crop] : regions) {
        const ImageMetrics m = compare_images(a, b, crop);
        if (json) {
            out.push_back({{"region", name}, {"rel_mse", m.rel_mse}, {"rmse", m.rmse}, {"psnr", m.psnr},
                           {"smape", m.smape}, {"mean", m.mean}, {"mean_reference", m.mean_reference}});
        } else {
            std::printf("%-24s relMSE %.6g  RMSE %.6g  PSNR %.3f dB  SMAPE %.6g  mean %.6g (reference %.6g)\n",
                        name.c_str(), m.rel_mse, m.rmse, m.psnr, m.smape, m.mean, m.mean_reference);
        }
    }
    if (json) std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"snell: a spectral renderer for caustics through refractive interfaces (MNEE)"};
    app.require_subcommand(1);

    CLI::App* render_cmd = app.add_subcommand("render", "render a Mitsuba-style XML scene (or builtin:droplet)");
    std::string scene_arg, out, stats_path;
    int spp = 0, threads = 0;
    double time_limit = 0, exposure = 0;
    uint64_t seed = 0;
    bool quiet = false;
    std::vector<std::string> defines;
    render_cmd->add_option("scene", scene_arg, "scene file, or builtin:droplet")->required();
    render_cmd->add_option("-o,--output", out, "output EXR (a PNG and a stats JSON are written beside it)");
    auto* spp_opt = render_cmd->add_option("--spp", spp, "samples per pixel (default: the scene's sample_count)")
                        ->check(CLI::PositiveNumber);
    render_cmd->add_option("--time", time_limit, "render for this many seconds instead (equal-time comparisons)")
        ->check(CLI::PositiveNumber)
        ->excludes(spp_opt);
    render_cmd->add_option("-t,--threads", threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
    auto* seed_opt = render_cmd->add_option("--seed", seed, "sampler seed (default: the scene's <sampler> seed, else 0)");
    render_cmd->add_option("--exposure", exposure, "PNG exposure in stops");
    render_cmd->add_option("--stats", stats_path, "stats JSON path (default: beside the EXR)");
    render_cmd->add_option("-D,--define", defines, "override a scene <default>: -D name=value")->allow_extra_args(false);
    render_cmd->add_flag("-q,--quiet", quiet, "no progress bar or summary");

    CLI::App* diff_cmd = app.add_subcommand("diff", "error metrics of an image against a reference (both EXR)");
    std::string diff_a, diff_b;
    std::vector<std::string> diff_crops;
    bool diff_json = false;
    diff_cmd->add_option("image", diff_a, "image to evaluate")->required();
    diff_cmd->add_option("reference", diff_b, "reference image")->required();
    diff_cmd->add_option("--crop", diff_crops, "also report the rectangle x,y,w,h (repeatable)");
    diff_cmd->add_flag("--json", diff_json, "print JSON instead of text");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        if (diff_cmd->parsed()) return cmd_diff(diff_a, diff_b, diff_crops, diff_json);
        if (render_cmd->parsed())
            return cmd_render(scene_arg, out, spp, time_limit, threads,
                              seed_opt->count() ? std::optional<uint64_t>(seed) : std::nullopt, exposure,
                              stats_path, quiet, defines);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "snell: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
