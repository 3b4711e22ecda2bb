#include "report/html_report.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "report/false_colour.h"
#include "report/svg_plot.h"

namespace snell {

namespace {

std::string fmt(const char* f, double v) {
    if (!std::isfinite(v)) return v > 0 ? "&infin;" : (v < 0 ? "&minus;&infin;" : "n/a");
    char buf[64];
    std::snprintf(buf, sizeof(buf), f, v);
    return buf;
}

std::string esc(const std::string& s) { return xml_escape(s); }

const char* k_css = R"(
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; background: #fafafa; }
h1 { font-size: 1.4em; margin-bottom: 0.2em; } h2 { font-size: 1.15em; margin-top: 1.6em; }
.meta { color: #555; font-size: 0.9em; }
.row { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
figure { margin: 0; background: white; padding: 6px; border: 1px solid #ddd; }
figcaption { font-size: 0.85em; text-align: center; margin-top: 4px; }
figcaption b { display: block; font-size: 1.05em; }
img { display: block; image-rendering: pixelated; image-rendering: crisp-edges; }
.frame { position: relative; }
.cropbox { position: absolute; border: 2px solid #ff2d2d; box-sizing: border-box; }
.cropbox span { position: absolute; top: -1.3em; left: 0; color: #ff2d2d; font-size: 0.75em; font-weight: bold; }
table { border-collapse: collapse; background: white; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; }
th { background: #eee; } td.name, th.name { text-align: left; }
tr.best td { background: #eef7ee; }
.colourbar { width: 256px; height: 14px; border: 1px solid #999; }
.cbar-labels { width: 258px; display: flex; justify-content: space-between; font-size: 0.8em; }
)";

// CSS gradient through the viridis samples (the colour bar of the error maps).
std::string viridis_gradient() {
    std::string g = "linear-gradient(to right";
    for (int i = 0; i <= 8; ++i) {
        const Rgb8 c = viridis(i / 8.0);
        g += ", rgb(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
    }
    return g + ")";
}

// Displayed width of a full image: small renders are enlarged (pixelated) to stay legible.
int display_width(int w) { return w >= 256 ? w : w * std::max(1, 320 / std::max(1, w)); }

std::string figure(const std::string& src, const std::string& alt, int width, const std::string& caption,
                   const std::string& overlay = "") {
    std::string s = "<figure><div class=\"frame\"><img src=\"" + esc(src) + "\" alt=\"" + esc(alt) + "\" width=\"" +
                    std::to_string(width) + "\">" + overlay + "</div>";
    s += "<figcaption>" + caption + "</figcaption></figure>\n";
    return s;
}

}  // namespace

std::string html_report(const CompareReport& r) {
    const std::vector<size_t> order = r.order_by_psnr();
    const int dw = display_width(r.width);
    std::string h;
    h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    h += "<title>snell compare: " + esc(r.scene) + "</title>\n<style>" + std::string(k_css) +
         "</style>\n</head>\n<body>\n";

    // Header: what was compared and how.
    h += "<h1>Equal-time comparison: " + esc(r.scene) + "</h1>\n<p class=\"meta\">";
    h += std::to_string(r.width) + "&times;" + std::to_string(r.height) + " pixels";
    if (r.windowed())
        h += " (the reference's window at x=" + std::to_string(r.window_x) + ", y=" + std::to_string(r.window_y) +
             " of the " + std::to_string(r.film_width) + "&times;" + std::to_string(r.film_height) + " film)";
    h += ", " + fmt("%g", r.time_budget) + " s per integrator, " + std::to_string(r.threads) + " threads, seed " +
         std::to_string(r.seed) + ", PNG exposure " + fmt("%+g", r.exposure) + " stops";
    for (const std::string& d : r.defines) h += ", -D " + esc(d);
    h += ".<br>Reference: ";
    if (r.reference.source == "file")
        h += "file " + esc(r.reference.file);
    else {
        h += esc(r.reference.integrator) + " rendered with ";
        h += r.reference.spp > 0 ? std::to_string(r.reference.spp) + " spp" : fmt("%g", r.reference.time_limit) + " s";
        h += " (" + fmt("%.1f", r.reference.stats.seconds) + " s)";
    }
    h += ".</p>\n";

    // Images side by side, reference first, then by PSNR (the paper's Fig. 5 layout).
    std::string overlay;
    for (size_t i = 0; i < r.crops.size(); ++i) {
        const Crop& c = r.crops[i];
        overlay += "<div class=\"cropbox\" style=\"left:" + fmt("%.3f", 100.0 * c.x / r.width) +
                   "%;top:" + fmt("%.3f", 100.0 * c.y / r.height) + "%;width:" + fmt("%.3f", 100.0 * c.w / r.width) +
                   "%;height:" + fmt("%.3f", 100.0 * c.h / r.height) + "%\"><span>" + std::to_string(i + 1) +
                   "</span></div>";
    }
    h += "<h2>Images (sorted by PSNR, best first)</h2>\n<div id=\"images\" class=\"row\">\n";
    h += figure(r.reference.image_png, "reference", dw, "<b>reference</b>", overlay);
    for (size_t k : order) {
        const IntegratorResult& it = r.integrators[k];
        const ImageMetrics& m = it.regions.at(0).metrics;
        h += figure(it.image_png, it.name, dw,
                    "<b>" + esc(it.name) + "</b>" + (it.ranked() ? "" : "not ranked: " + esc(it.unranked) + "; ") +
                        "PSNR " + fmt("%.2f", m.psnr) + " dB, relMSE " + fmt("%.4g", m.rel_mse) + ", " +
                        std::to_string(it.stats.spp_reached) + " spp");
    }
    h += "</div>\n";

    // Crops, enlarged with nearest-neighbour scaling.
    if (!r.crops.empty()) {
        h += "<h2>Crops (enlarged, nearest neighbour)</h2>\n<div id=\"crops\">\n";
        for (size_t c = 0; c < r.crops.size(); ++c) {
            const Crop& cr = r.crops[c];
            const int scale = c < r.crop_scales.size() ? r.crop_scales[c] : 1;
            h += "<p class=\"meta\">Crop " + std::to_string(c + 1) + ": x=" + std::to_string(r.in_film(cr).x) +
                 ", y=" + std::to_string(r.in_film(cr).y) + ", " + std::to_string(cr.w) + "&times;" +
                 std::to_string(cr.h) + " pixels, shown " + std::to_string(scale) +
                 "&times;</p>\n<div class=\"row\">\n";
            h += figure(r.reference.crop_pngs.at(c), "reference crop " + std::to_string(c + 1), cr.w * scale,
                        "<b>reference</b>");
            for (size_t k : order) {
                const IntegratorResult& it = r.integrators[k];
                const ImageMetrics& m = it.regions.at(c + 1).metrics;
                h += figure(
                    it.crop_pngs.at(c), it.name + " crop " + std::to_string(c + 1), cr.w * scale,
                    "<b>" + esc(it.name) + "</b>PSNR " + fmt("%.2f", m.psnr) + " dB, relMSE " + fmt("%.4g", m.rel_mse));
            }
            h += "</div>\n";
        }
        h += "</div>\n";
    }

    // False-colour relative error.
    h +=
        "<h2>Relative error</h2>\n<p class=\"meta\">Per pixel sqrt(mean over RGB of (a&minus;r)&sup2;/(r&sup2;+0.01)), "
        "viridis colour map from 0 (dark purple) to " +
        fmt("%g", r.error_max) + " or more (yellow).</p>\n";
    h += "<div class=\"colourbar\" style=\"background:" + viridis_gradient() + "\"></div>\n";
    h += "<div class=\"cbar-labels\"><span>0</span><span>" + fmt("%g", r.error_max / 2) + "</span><span>&ge;" +
         fmt("%g", r.error_max) + "</span></div>\n";
    h += "<div id=\"errors\" class=\"row\">\n";
    for (size_t k : order) {
        const IntegratorResult& it = r.integrators[k];
        h += figure(it.error_png, it.name + " relative error", dw, "<b>" + esc(it.name) + "</b>");
    }
    h += "</div>\n";

    // Metrics table.
    h += "<h2>Metrics</h2>\n<table id=\"metrics\">\n<thead><tr><th>rank</th><th class=\"name\">integrator</th>"
         "<th class=\"name\">region</th><th>relMSE</th><th>RMSE</th><th>PSNR [dB]</th><th>SMAPE</th><th>spp</th>"
         "<th>spp (mean)</th><th>time [s]</th><th>paths/s</th></tr></thead>\n<tbody>\n";
    for (size_t rank = 0; rank < order.size(); ++rank) {
        const IntegratorResult& it = r.integrators[order[rank]];
        for (size_t g = 0; g < it.regions.size(); ++g) {
            const ImageMetrics& m = it.regions[g].metrics;
            const std::string place = it.ranked() ? std::to_string(rank + 1) : "&ndash;";
            const std::string name = esc(it.name) + (it.ranked() ? "" : " (not ranked: " + esc(it.unranked) + ")");
            h += std::string("<tr") + (rank == 0 && it.ranked() ? " class=\"best\"" : "") + "><td>" + place +
                 "</td><td class=\"name\">" + name + "</td><td class=\"name\">" + esc(it.regions[g].region) +
                 "</td><td>" + fmt("%.4g", m.rel_mse) + "</td><td>" + fmt("%.4g", m.rmse) + "</td><td>" +
                 fmt("%.2f", m.psnr) + "</td><td>" + fmt("%.4g", m.smape) + "</td><td>" +
                 std::to_string(it.stats.spp_reached) + "</td><td>" + fmt("%.1f", it.stats.spp_mean) + "</td><td>" +
                 fmt("%.2f", it.stats.seconds) + "</td><td>" + fmt("%.3g", it.stats.paths_per_second()) +
                 "</td></tr>\n";
        }
    }
    h += "</tbody>\n</table>\n";

    // Manifold-walk statistics (paper Table 1 quantities) for the integrators that walk.
    bool any_mnee = false;
    for (const IntegratorResult& it : r.integrators) any_mnee |= it.stats.extra.contains("mnee");
    if (any_mnee) {
        h += "<h2>Manifold walk statistics</h2>\n<table id=\"mnee-stats\">\n<thead><tr><th "
             "class=\"name\">integrator</th>"
             "<th class=\"name\">statistic</th><th>value</th></tr></thead>\n<tbody>\n";
        for (size_t k : order) {
            const IntegratorResult& it = r.integrators[k];
            if (!it.stats.extra.contains("mnee")) continue;
            auto row = [&](const std::string& key, const nlohmann::json& v) {
                const std::string val = v.is_number_float() ? fmt("%.6g", v.get<double>()) : esc(v.dump());
                h += "<tr><td class=\"name\">" + esc(it.name) + "</td><td class=\"name\">" + esc(key) + "</td><td>" +
                     val + "</td></tr>\n";
            };
            // Scalars, and one level of grouped counts ("failures.occluded"); the iteration
            // histogram stays in report.json.
            for (const auto& [key, v] : it.stats.extra["mnee"].items()) {
                if (v.is_object()) {
                    for (const auto& [sub, w] : v.items())
                        if (w.is_primitive()) row(key + "." + sub, w);
                } else if (v.is_primitive()) {
                    row(key, v);
                }
            }
        }
        h += "</tbody>\n</table>\n";
    }

    // Convergence plot.
    LogLogPlot plot;
    plot.title = "relMSE against render time";
    plot.x_label = "render time [s]";
    plot.y_label = "relMSE (whole image)";
    for (size_t k : order) {
        const IntegratorResult& it = r.integrators[k];
        PlotSeries s{it.name, {}, {}};
        for (const ConvergencePoint& p : it.convergence) {
            s.x.push_back(p.seconds);
            s.y.push_back(p.metrics.rel_mse);
        }
        plot.series.push_back(s);
    }
    h += "<h2>Convergence</h2>\n<div id=\"convergence\">\n" + render_svg(plot) + "</div>\n";
    h += "<p class=\"meta\">Every number is also in <a href=\"report.json\">report.json</a>.</p>\n</body>\n</html>\n";
    return h;
}

void write_html_report(const std::string& path, const CompareReport& r) {
    const std::string page = html_report(r);
    std::ofstream out(path, std::ios::binary);
    if (!out || !out.write(page.data(), std::streamsize(page.size())))
        throw std::runtime_error("cannot write '" + path + "'");
}

}  // namespace snell
