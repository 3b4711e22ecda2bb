#include "report/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace snell {

std::string xml_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string series_colour(size_t index) {
    static const char* palette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#F0E442", "#000000"};
    return palette[index % (sizeof(palette) / sizeof(palette[0]))];
}

namespace {

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), f, v);
    return buf;
}

bool plottable(double x, double y) { return std::isfinite(x) && std::isfinite(y) && x > 0 && y > 0; }

// Label of a power of ten: 0.01, 0.1, 1, 10, 100 written plainly, others as 1e-5.
std::string decade_label(int e) {
    if (e >= -2 && e <= 3) return fmt("%g", std::pow(10.0, e));
    return "1e" + std::to_string(e);
}

}  // namespace

std::string render_svg(const LogLogPlot& plot) {
    // Data range in decades (log10), padded to whole decades so ticks sit at the edges.
    double lx0 = std::numeric_limits<double>::infinity(), lx1 = -lx0, ly0 = lx0, ly1 = -lx0;
    for (const PlotSeries& s : plot.series)
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
            if (plottable(s.x[i], s.y[i])) {
                lx0 = std::min(lx0, std::log10(s.x[i]));
                lx1 = std::max(lx1, std::log10(s.x[i]));
                ly0 = std::min(ly0, std::log10(s.y[i]));
                ly1 = std::max(ly1, std::log10(s.y[i]));
            }
    if (!std::isfinite(lx0)) lx0 = 0, lx1 = 1, ly0 = 0, ly1 = 1;  // nothing to show: an empty frame
    lx0 = std::floor(lx0), lx1 = std::max(std::ceil(lx1), lx0 + 1);
    ly0 = std::floor(ly0), ly1 = std::max(std::ceil(ly1), ly0 + 1);

    const double W = plot.width, H = plot.height;
    const double left = 70, right = 150, top = 30, bottom = 50;  // the legend sits in the right margin
    const double pw = W - left - right, ph = H - top - bottom;
    auto px = [&](double x) { return left + (std::log10(x) - lx0) / (lx1 - lx0) * pw; };
    auto py = [&](double y) { return top + ph - (std::log10(y) - ly0) / (ly1 - ly0) * ph; };

    std::string s;
    s += "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"" + fmt("%g", W) + "\" height=\"" +
         fmt("%g", H) + "\" viewBox=\"0 0 " + fmt("%g", W) + " " + fmt("%g", H) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    s += "<title>" + xml_escape(plot.title) + "</title>\n";
    s += "<rect x=\"0\" y=\"0\" width=\"" + fmt("%g", W) + "\" height=\"" + fmt("%g", H) + "\" fill=\"white\"/>\n";
    s += "<text x=\"" + fmt("%g", left + pw / 2) + "\" y=\"18\" text-anchor=\"middle\" font-weight=\"bold\">" +
         xml_escape(plot.title) + "</text>\n";

    // Grid and tick labels at powers of ten.
    for (int e = int(lx0); e <= int(lx1); ++e) {
        const double x = left + (e - lx0) / (lx1 - lx0) * pw;
        s += "<line x1=\"" + fmt("%.1f", x) + "\" y1=\"" + fmt("%.1f", top) + "\" x2=\"" + fmt("%.1f", x) + "\" y2=\"" +
             fmt("%.1f", top + ph) + "\" stroke=\"#ddd\"/>\n";
        s += "<text x=\"" + fmt("%.1f", x) + "\" y=\"" + fmt("%.1f", top + ph + 16) + "\" text-anchor=\"middle\">" +
             decade_label(e) + "</text>\n";
    }
    for (int e = int(ly0); e <= int(ly1); ++e) {
        const double y = top + ph - (e - ly0) / (ly1 - ly0) * ph;
        s += "<line x1=\"" + fmt("%.1f", left) + "\" y1=\"" + fmt("%.1f", y) + "\" x2=\"" + fmt("%.1f", left + pw) +
             "\" y2=\"" + fmt("%.1f", y) + "\" stroke=\"#ddd\"/>\n";
        s += "<text x=\"" + fmt("%.1f", left - 6) + "\" y=\"" + fmt("%.1f", y + 4) + "\" text-anchor=\"end\">" +
             decade_label(e) + "</text>\n";
    }
    s += "<rect x=\"" + fmt("%g", left) + "\" y=\"" + fmt("%g", top) + "\" width=\"" + fmt("%g", pw) + "\" height=\"" +
         fmt("%g", ph) + "\" fill=\"none\" stroke=\"black\"/>\n";
    s += "<text class=\"xlabel\" x=\"" + fmt("%g", left + pw / 2) + "\" y=\"" + fmt("%g", H - 10) +
         "\" text-anchor=\"middle\">" + xml_escape(plot.x_label) + "</text>\n";
    s += "<text class=\"ylabel\" x=\"16\" y=\"" + fmt("%g", top + ph / 2) +
         "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " + fmt("%g", top + ph / 2) + ")\">" +
         xml_escape(plot.y_label) + "</text>\n";

    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries& ser = plot.series[k];
        const std::string colour = series_colour(k);
        std::string points, markers;
        for (size_t i = 0; i < std::min(ser.x.size(), ser.y.size()); ++i) {
            if (!plottable(ser.x[i], ser.y[i])) continue;
            const std::string X = fmt("%.1f", px(ser.x[i])), Y = fmt("%.1f", py(ser.y[i]));
            points += X + "," + Y + " ";
            markers += "<circle cx=\"" + X + "\" cy=\"" + Y + "\" r=\"3\" fill=\"" + colour + "\"/>\n";
        }
        s += "<polyline class=\"series\" data-name=\"" + xml_escape(ser.name) + "\" fill=\"none\" stroke=\"" + colour +
             "\" stroke-width=\"2\" points=\"" + points + "\"/>\n" + markers;
        const double ly = top + 10 + 18 * double(k);
        s += "<line x1=\"" + fmt("%g", left + pw + 12) + "\" y1=\"" + fmt("%g", ly) + "\" x2=\"" +
             fmt("%g", left + pw + 36) + "\" y2=\"" + fmt("%g", ly) + "\" stroke=\"" + colour +
             "\" stroke-width=\"2\"/>\n";
        s += "<text x=\"" + fmt("%g", left + pw + 42) + "\" y=\"" + fmt("%g", ly + 4) + "\">" + xml_escape(ser.name) +
             "</text>\n";
    }
    s += "</svg>\n";
    return s;
}

}  // namespace snell
