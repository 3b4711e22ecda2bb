#pragma once
// The human-readable side of `snell compare`: one static HTML page (inline CSS, no scripts, no
// network) that opens from disk and shows images, crops, error maps, the metrics table and the
// convergence plot.
#include <string>

#include "report/compare_report.h"

namespace snell {

/// The complete page for `r`. Images are referenced by the relative paths stored in `r`, so
/// the page must sit in the report folder. Element ids tests can rely on: "images",
/// "crops", "errors", "metrics" (the <table>), "mnee-stats", "convergence" (holds the <svg>).
std::string html_report(const CompareReport& r);

/// Writes html_report(r) to `path`; throws std::runtime_error naming the path on failure.
void write_html_report(const std::string& path, const CompareReport& r);

}  // namespace snell
