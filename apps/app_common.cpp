#include "app_common.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "builtin_scenes.h"
#include "manifold/walk_statistics.h"

namespace fs = std::filesystem;

namespace snell {

std::atomic<bool> g_cancel{false};

// First Ctrl-C: stop rendering and write what we have. Second: leave at once.
extern "C" void on_sigint(int) {
    if (g_cancel.exchange(true)) std::_Exit(130);
}

namespace {
// The XML text of "builtin:NAME", or nullptr when scene_arg names a file; unknown built-ins throw.
const std::string* builtin_xml(const std::string& scene_arg) {
    const std::string prefix = "builtin:";
    if (scene_arg.rfind(prefix, 0) != 0) return nullptr;
    const std::string name = scene_arg.substr(prefix.size());
    const std::string* xml = builtin_scene(name);
    if (!xml) {
        std::string known;
        for (auto& n : builtin_scene_names()) known += " builtin:" + n;
        throw std::runtime_error("unknown built-in scene '" + scene_arg + "' (known:" + known + ")");
    }
    return xml;
}
}  // namespace

LoadedScene load_scene_arg(const std::string& scene_arg, const Defines& defines,
                           const std::vector<std::string>& search_paths, bool print_notices) {
    LoadedScene ls = builtin_xml(scene_arg)
                         ? load_scene_string(*builtin_xml(scene_arg), scene_arg, fs::current_path().string(), defines)
                         : load_scene_file(scene_arg, defines, search_paths);
    if (print_notices)
        for (const std::string& n : ls.notices) std::fprintf(stderr, "snell: notice: %s\n", n.c_str());
    return ls;
}

std::shared_ptr<XmlObject> parse_scene_arg(const std::string& scene_arg, const Defines& defines) {
    if (const std::string* xml = builtin_xml(scene_arg))
        return parse_scene_xml_string(*xml, scene_arg, fs::current_path().string(), defines);
    return parse_scene_xml_file(scene_arg, defines);
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

RenderReport make_report(const std::string& scene, const std::string& integrator, int width, int height,
                         const RenderResult& r, uint64_t spp_requested, double time_limit, int threads, uint64_t seed) {
    RenderReport rep;
    rep.scene = scene;
    rep.integrator = integrator;
    rep.width = width;
    rep.height = height;
    rep.spp_requested = spp_requested;
    rep.spp_reached = r.spp_completed;
    rep.spp_mean = r.spp_mean;
    rep.seconds = r.seconds;
    rep.time_limit = time_limit;
    rep.threads = threads;
    rep.seed = seed;
    rep.interrupted = r.interrupted;
    rep.saturated = r.saturated;
    rep.ranks = process_team().size();
    rep.pixels = r.dominance.pixels;
    rep.pixels_dominated = r.dominance.dominated;
    rep.max_sample_share = r.dominance.max_share;
    rep.pixels_outlier = r.dominance.outliers;
    rep.pixels_clamped = r.dominance.clamped;
    rep.clamped_share = r.dominance.clamped_share;
    rep.spread_share = r.dominance.spread_share;
    rep.spread_radius = r.dominance.spread_radius;
    rep.spread_dropped = r.dominance.spread_dropped;
    for (size_t t = 0; t < r.dominance.dominated_by_technique.size(); ++t)
        if (r.dominance.dominated_by_technique[t] > 0)
            rep.dominated_by_technique[t < r.technique_names.size() ? r.technique_names[t]
                                                                    : "technique " + std::to_string(t)] =
                r.dominance.dominated_by_technique[t];
    rep.set_counters(r.counters);
    if (has_mnee_stats(r.counters)) rep.extra["mnee"] = mnee_stats_json(r.counters);
    if (r.team.ranks > 1)  // the scaling model's inputs (docs/distributed.md, "Scaling")
        rep.extra["mpi"] = {{"ranks", r.team.ranks},
                            {"tile_requests", r.team.requests},
                            {"dispatcher_service_s", r.team.service_seconds},
                            {"rank0_pass_end_wait_s", r.team.pass_end_seconds},
                            {"idle_s_all_ranks", r.team.idle_seconds},
                            {"reduce_s", r.team.reduce_seconds},
                            {"reduce_bytes_per_rank", r.team.reduce_bytes}};
    return rep;
}

Crop offset_window(const std::string& option, const std::string& xy, int w, int h) {
    Crop c{0, 0, w, h};
    char comma = 0;
    std::istringstream in(xy);
    if (!(in >> c.x >> comma >> c.y) || comma != ',' || !in.eof() || c.x < 0 || c.y < 0)
        throw std::runtime_error(option + " must be x,y (pixels, x, y >= 0), got '" + xy + "'");
    return c;
}

Image film_to_image(const Film& film, int layer) {
    Image img;
    img.width = film.width();
    img.height = film.height();
    img.rgb = film.to_linear_srgb(layer);
    return img;
}

}  // namespace snell
