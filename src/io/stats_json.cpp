#include "io/stats_json.h"

#include "io/atomic_file.h"

#include <fstream>
#include <stdexcept>

namespace snell {

void RenderReport::set_counters(const StatTotals& t) {
    // By name: the counters are declared by the code that counts them (render/camera_sample.h,
    // scene/scene.h), above this library.
    paths = t.get("render.paths");
    rays = t.get("scene.rays");
    shadow_rays = t.get("scene.shadow_rays");
    discarded_nan = t.get("render.discarded_nan");
    discarded_inf = t.get("render.discarded_inf");
    discarded_negative = t.get("render.discarded_negative");
    counters = nlohmann::json::object();
    for (const StatInfo& s : registered_stats()) {
        if (s.kind == StatKind::Moments) {
            const Moments m = t.moments(s);
            counters[s.name] = {
                {"count", m.count}, {"mean", m.mean()}, {"relative_variance", m.relative_variance()}, {"max", m.max}};
            continue;
        }
        std::vector<uint64_t> v = t.values(s);
        if (s.kind != StatKind::Histogram) {
            counters[s.name] = v[0];
            continue;
        }
        while (!v.empty() && v.back() == 0) v.pop_back();
        counters[s.name] = v;
    }
}

double RenderReport::paths_per_second() const { return seconds > 0 ? double(paths) / seconds : 0.0; }

double RenderReport::rays_per_second() const { return seconds > 0 ? double(rays + shadow_rays) / seconds : 0.0; }

void to_json(nlohmann::json& j, const RenderReport& r) {
    j = nlohmann::json{
        {"scene", r.scene},
        {"integrator", r.integrator},
        {"width", r.width},
        {"height", r.height},
        {"spp_requested", r.spp_requested},
        {"spp_reached", r.spp_reached},
        {"spp_mean", r.spp_mean},
        {"seconds", r.seconds},
        {"time_limit", r.time_limit},
        {"interrupted", r.interrupted},
        {"threads", r.threads},
        {"ranks", r.ranks},
        {"seed", r.seed},
        {"paths", r.paths},
        {"rays", r.rays},
        {"shadow_rays", r.shadow_rays},
        {"paths_per_second", r.paths_per_second()},
        {"rays_per_second", r.rays_per_second()},
        {"discarded",
         {{"nan", r.discarded_nan},
          {"inf", r.discarded_inf},
          {"negative", r.discarded_negative},
          {"beyond_float32", r.beyond_float},
          {"saturated", r.saturated}}},
        {"dominance",
         {{"pixels", r.pixels},
          {"dominated", r.pixels_dominated},
          {"outliers", r.pixels_outlier},
          {"max_share", r.max_sample_share},
          {"clamped", r.pixels_clamped},
          {"clamped_share", r.clamped_share},
          {"spread_share", r.spread_share},
          {"spread_radius", r.spread_radius},
          {"spread_dropped", r.spread_dropped},
          {"by_technique", r.dominated_by_technique}}},
        {"extra", r.extra},
        {"counters", r.counters},
    };
}

void from_json(const nlohmann::json& j, RenderReport& r) {
    auto get = [&](const char* key, auto& field) {
        if (auto it = j.find(key); it != j.end()) it->get_to(field);
    };
    get("scene", r.scene);
    get("integrator", r.integrator);
    get("width", r.width);
    get("height", r.height);
    get("spp_requested", r.spp_requested);
    get("spp_reached", r.spp_reached);
    get("seconds", r.seconds);
    get("spp_mean", r.spp_mean);
    get("time_limit", r.time_limit);
    get("interrupted", r.interrupted);
    get("threads", r.threads);
    get("ranks", r.ranks);
    get("seed", r.seed);
    get("paths", r.paths);
    get("rays", r.rays);
    get("shadow_rays", r.shadow_rays);
    if (auto d = j.find("discarded"); d != j.end()) {
        if (auto it = d->find("nan"); it != d->end()) it->get_to(r.discarded_nan);
        if (auto it = d->find("inf"); it != d->end()) it->get_to(r.discarded_inf);
        if (auto it = d->find("negative"); it != d->end()) it->get_to(r.discarded_negative);
        if (auto it = d->find("beyond_float32"); it != d->end()) it->get_to(r.beyond_float);
        if (auto it = d->find("saturated"); it != d->end()) it->get_to(r.saturated);
    }
    if (auto d = j.find("dominance"); d != j.end()) {
        if (auto it = d->find("pixels"); it != d->end()) it->get_to(r.pixels);
        if (auto it = d->find("dominated"); it != d->end()) it->get_to(r.pixels_dominated);
        if (auto it = d->find("max_share"); it != d->end()) it->get_to(r.max_sample_share);
        if (auto it = d->find("outliers"); it != d->end()) it->get_to(r.pixels_outlier);
        if (auto it = d->find("clamped"); it != d->end()) it->get_to(r.pixels_clamped);
        if (auto it = d->find("clamped_share"); it != d->end()) it->get_to(r.clamped_share);
        if (auto it = d->find("spread_share"); it != d->end()) it->get_to(r.spread_share);
        if (auto it = d->find("spread_radius"); it != d->end()) it->get_to(r.spread_radius);
        if (auto it = d->find("spread_dropped"); it != d->end()) it->get_to(r.spread_dropped);
        if (auto it = d->find("by_technique"); it != d->end()) it->get_to(r.dominated_by_technique);
    }
    if (auto it = j.find("extra"); it != j.end()) r.extra = *it;
    if (auto it = j.find("counters"); it != j.end()) r.counters = *it;
}

void write_stats_json(const std::string& path, const RenderReport& report) {
    try {
        write_file_atomically(path, nlohmann::json(report).dump(2) + "\n");
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot write stats JSON '" + path + "': " + e.what());
    }
}

}  // namespace snell
