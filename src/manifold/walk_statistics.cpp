#include "manifold/walk_statistics.h"

#include <cstdio>

namespace snell {

namespace {
double ratio(uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0.0; }
}  // namespace

nlohmann::json mnee_stats_json(const Counters& c) {
    nlohmann::json j;
    j["walks_started"] = c.walks_started;
    j["walks_converged"] = c.walks_converged;
    j["success_rate"] = ratio(c.walks_converged, c.walks_started);
    j["mean_iterations_success"] = ratio(c.walk_iterations_success, c.walks_converged);
    j["walk_seconds"] = double(c.walk_time_ns) * 1e-9;
    j["failures"] = {{"no_convergence", c.walk_fail_no_convergence},
                     {"singular", c.walk_fail_singular},
                     {"projection", c.walk_fail_projection},
                     {"wrong_scattering", c.walk_fail_scattering},
                     {"occluded", c.walk_fail_occluded}};
    j["seeds"] = {{"occluded", c.seeds_occluded}, {"too_many_vertices", c.seeds_too_many}, {"culled", c.seeds_culled}};
    j["pdf_walks"] = c.pdf_walks;
    j["pdf_walks_found"] = c.pdf_walks_found;
    // Histogram of iterations of successful walks; the last bin collects the rest.
    nlohmann::json h = nlohmann::json::array();
    int last = 0;
    for (int i = 0; i < Counters::kIterationBins; ++i)
        if (c.iteration_histogram[i]) last = i;
    for (int i = 0; i <= last; ++i) h.push_back(c.iteration_histogram[i]);
    j["iteration_histogram"] = h;
    return j;
}

std::string mnee_stats_text(const Counters& c) {
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "  mnee: %llu walks, %.1f%% converged, %.2f iterations per success, %.2f s in walks; failures: "
                  "no convergence %llu, singular %llu, projection %llu, wrong scattering %llu, occluded %llu; "
                  "pdf walks %llu (%.1f%% found)\n",
                  (unsigned long long)c.walks_started, 100 * ratio(c.walks_converged, c.walks_started),
                  ratio(c.walk_iterations_success, c.walks_converged), double(c.walk_time_ns) * 1e-9,
                  (unsigned long long)c.walk_fail_no_convergence, (unsigned long long)c.walk_fail_singular,
                  (unsigned long long)c.walk_fail_projection, (unsigned long long)c.walk_fail_scattering,
                  (unsigned long long)c.walk_fail_occluded, (unsigned long long)c.pdf_walks,
                  100 * ratio(c.pdf_walks_found, c.pdf_walks));
    return buf;
}

}  // namespace snell
