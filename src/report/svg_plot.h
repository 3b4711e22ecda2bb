#pragma once
// A log-log line plot as inline SVG (convergence of error against render time), so a report
// needs neither scripts nor a plotting library to show it.
#include <string>
#include <vector>

namespace snell {

/// One polyline: points (x[i], y[i]); points with a non-positive or non-finite coordinate
/// cannot be shown on log axes and are skipped.
struct PlotSeries {
    std::string name;
    std::vector<double> x, y;
};

struct LogLogPlot {
    std::string title;
    std::string x_label;  ///< e.g. "render time [s]"
    std::string y_label;  ///< e.g. "relMSE"
    std::vector<PlotSeries> series;
    int width = 640, height = 400;  ///< SVG size in CSS pixels
};

/// The plot as a standalone <svg> element: both axes logarithmic over the decades that cover
/// the data, ticks and grid lines at powers of ten, axis labels, one coloured polyline with
/// point markers per series, and a legend. Text is XML-escaped.
std::string render_svg(const LogLogPlot& plot);

/// `text` with & < > " ' replaced by entities (for SVG and HTML).
std::string xml_escape(const std::string& text);

/// A distinct colour ("#rrggbb") for series `index` (Okabe-Ito palette, colour-blind safe).
std::string series_colour(size_t index);

}  // namespace snell
