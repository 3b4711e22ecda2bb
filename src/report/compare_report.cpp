#include "report/compare_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace snell {

std::vector<size_t> CompareReport::order_by_psnr() const {
    std::vector<size_t> idx(integrators.size());
    std::iota(idx.begin(), idx.end(), 0);
    auto psnr = [&](size_t i) {
        return integrators[i].regions.empty() ? -INFINITY : integrators[i].regions[0].metrics.psnr;
    };
    std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
        const bool ra = integrators[a].ranked(), rb = integrators[b].ranked();
        return ra != rb ? ra : ra && psnr(a) > psnr(b);
    });
    return idx;
}

size_t CompareReport::ranked_count() const {
    return size_t(std::count_if(integrators.begin(), integrators.end(), [](const auto& it) { return it.ranked(); }));
}

namespace {
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
nlohmann::json crop_json(const Crop& c) { return {{"x", c.x}, {"y", c.y}, {"w", c.w}, {"h", c.h}}; }
}  // namespace

nlohmann::json metrics_json(const ImageMetrics& m) {
    return {{"rel_mse", number(m.rel_mse)},
            {"mse", number(m.mse)},
            {"rmse", number(m.rmse)},
            {"psnr", number(m.psnr)},
            {"smape", number(m.smape)},
            {"mean", number(m.mean)},
            {"median_rel_error", number(m.median_rel_error)},
            {"median_rel_error_rgb", number(m.median_rel_error_rgb)},
            {"mean_reference", number(m.mean_reference)},
            {"pixels", m.pixels}};
}

nlohmann::json report_json(const CompareReport& r) {
    nlohmann::json j;
    j["scene"] = r.scene;
    j["defines"] = r.defines;
    j["width"] = r.width;
    j["height"] = r.height;
    j["film"] = {{"width", r.film_width}, {"height", r.film_height}};
    j["window"] = crop_json({r.window_x, r.window_y, r.width, r.height});
    j["time_budget"] = r.time_budget;
    j["threads"] = r.threads;
    j["seed"] = r.seed;
    j["exposure"] = r.exposure;
    j["error_max"] = r.error_max;
    j["crops"] = nlohmann::json::array();
    for (size_t i = 0; i < r.crops.size(); ++i) {
        // In the film's coordinates, as given on the command line.
        nlohmann::json c = crop_json(r.in_film(r.crops[i]));
        if (i < r.crop_scales.size()) c["scale"] = r.crop_scales[i];
        j["crops"].push_back(c);
    }

    const ReferenceInfo& ref = r.reference;
    nlohmann::json jr = {{"source", ref.source},
                         {"image_exr", ref.image_exr},
                         {"image_png", ref.image_png},
                         {"crop_pngs", ref.crop_pngs}};
    if (ref.source == "file")
        jr["file"] = ref.file;
    else {
        jr["integrator"] = ref.integrator;
        jr["spp"] = ref.spp;
        jr["time_limit"] = ref.time_limit;
        jr["stats"] = ref.stats;
    }
    j["reference"] = jr;

    const std::vector<size_t> order = r.order_by_psnr();
    std::vector<int> rank(r.integrators.size());
    for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = int(k) + 1;
    j["integrators"] = nlohmann::json::array();
    for (size_t i = 0; i < r.integrators.size(); ++i) {
        const IntegratorResult& it = r.integrators[i];
        nlohmann::json ji;
        ji["name"] = it.name;
        ji["type"] = it.type;
        ji["biased"] = it.biased;
        ji["rank"] = it.ranked() ? nlohmann::json(rank[i]) : nlohmann::json(nullptr);
        if (!it.ranked()) ji["unranked"] = it.unranked;
        ji["seconds"] = it.stats.seconds;
        ji["spp_reached"] = it.stats.spp_reached;
        ji["spp_mean"] = it.stats.spp_mean;
        ji["paths_per_second"] = it.stats.paths_per_second();
        ji["metrics"] = nlohmann::json::array();
        for (const RegionMetrics& m : it.regions) {
            nlohmann::json jm = metrics_json(m.metrics);
            jm["region"] = m.region;
            jm["crop"] = crop_json(r.in_film(m.crop));
            ji["metrics"].push_back(jm);
        }
        ji["convergence"] = nlohmann::json::array();
        for (const ConvergencePoint& p : it.convergence) {
            nlohmann::json jp = metrics_json(p.metrics);
            jp["time_limit"] = p.time_limit;
            jp["seconds"] = p.seconds;
            jp["spp_mean"] = p.spp_mean;
            ji["convergence"].push_back(jp);
        }
        if (it.stats.extra.contains("mnee")) ji["mnee"] = it.stats.extra["mnee"];
        ji["stats"] = it.stats;
        ji["image_exr"] = it.image_exr;
        ji["image_png"] = it.image_png;
        ji["error_png"] = it.error_png;
        ji["crop_pngs"] = it.crop_pngs;
        j["integrators"].push_back(ji);
    }
    j["order_by_psnr"] = nlohmann::json::array();
    for (size_t k : order)
        if (r.integrators[k].ranked()) j["order_by_psnr"].push_back(r.integrators[k].name);
    return j;
}

}  // namespace snell
