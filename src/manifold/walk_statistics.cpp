#include "manifold/walk_statistics.h"

#include <cstdio>
#include <utility>

#include "manifold/walk_counters.h"

namespace snell {

namespace {
namespace wc = walk_counters;
double ratio(uint64_t a, uint64_t b) { return b ? double(a) / double(b) : 0.0; }
}  // namespace

bool has_mnee_stats(const StatTotals& t) { return t[wc::walks_started] > 0 || t[wc::pdf_walks] > 0; }

nlohmann::json mnee_stats_json(const StatTotals& t) {
    nlohmann::json j;
    j["walks_started"] = t[wc::walks_started];
    j["walks_converged"] = t[wc::walks_converged];
    j["success_rate"] = ratio(t[wc::walks_converged], t[wc::walks_started]);
    j["mean_iterations_success"] = ratio(t[wc::walk_iterations_success], t[wc::walks_converged]);
    j["walk_seconds"] = t.seconds(wc::walk_time);
    j["failures"] = {{"no_convergence", t[wc::walk_fail_no_convergence]},
                     {"singular", t[wc::walk_fail_singular]},
                     {"projection", t[wc::walk_fail_projection]},
                     {"wrong_scattering", t[wc::walk_fail_scattering]},
                     {"occluded", t[wc::walk_fail_occluded]}};
    j["seeds"] = {{"occluded", t[wc::seeds_occluded]},
                  {"too_many_vertices", t[wc::seeds_too_many]},
                  {"culled", t[wc::seeds_culled]}};
    // Every walk by how it ended (each walk in exactly one bin): Alg. 1 and Alg. 2 separately.
    for (const auto& [key, hist] : {std::pair{"alg1", &wc::walk_end_alg1}, std::pair{"alg2", &wc::walk_end_alg2}}) {
        const std::vector<uint64_t> ends = t.bins(*hist);
        nlohmann::json e = nlohmann::json::object();
        for (uint32_t i = 0; i < uint32_t(wc::WalkEnd::Count) && i < ends.size(); ++i)
            e[wc::walk_end_name(wc::WalkEnd(i))] = ends[i];
        j["walk_ends"][key] = e;
    }
    j["geometry_clamped"] = t[wc::geometry_clamped];
    // solutions=all or unbiased: how surface seeds ended, and the distinct solutions per solve.
    const std::vector<uint64_t> seed_ends = t.bins(wc::surface_seed_end);
    const char* seed_end_names[] = {"ok", "missed_caster", "total_internal_reflection", "too_many"};
    for (size_t i = 0; i < 4 && i < seed_ends.size(); ++i) j["surface_seeds"][seed_end_names[i]] = seed_ends[i];
    j["solutions_per_connection"] = t.bins(wc::solutions_per_connection);
    // solutions=unbiased: trials per solution (the mean estimates E[1/p] over found solutions).
    j["trials_per_solution"] = {{"estimates", t[wc::bernoulli_loops]},
                                {"mean", ratio(t[wc::bernoulli_trials], t[wc::bernoulli_loops])},
                                {"capped", t[wc::bernoulli_capped]}};
    j["pdf_walks"] = t[wc::pdf_walks];
    j["pdf_walks_found"] = t[wc::pdf_walks_found];
    // Histogram of iterations of successful walks; the last bin collects the rest.
    const std::vector<uint64_t> bins = t.bins(wc::iteration_histogram);
    size_t last = 0;
    for (size_t i = 0; i < bins.size(); ++i)
        if (bins[i]) last = i;
    nlohmann::json h = nlohmann::json::array();
    for (size_t i = 0; i <= last; ++i) h.push_back(bins[i]);
    j["iteration_histogram"] = h;
    return j;
}

std::string mnee_stats_text(const StatTotals& t) {
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "  mnee: %llu walks, %.1f%% converged, %.2f iterations per success, %.2f s in walks; failures: "
                  "no convergence %llu, singular %llu, projection %llu, wrong scattering %llu, occluded %llu; "
                  "pdf walks %llu (%.1f%% found)\n",
                  (unsigned long long)t[wc::walks_started], 100 * ratio(t[wc::walks_converged], t[wc::walks_started]),
                  ratio(t[wc::walk_iterations_success], t[wc::walks_converged]), t.seconds(wc::walk_time),
                  (unsigned long long)t[wc::walk_fail_no_convergence], (unsigned long long)t[wc::walk_fail_singular],
                  (unsigned long long)t[wc::walk_fail_projection], (unsigned long long)t[wc::walk_fail_scattering],
                  (unsigned long long)t[wc::walk_fail_occluded], (unsigned long long)t[wc::pdf_walks],
                  100 * ratio(t[wc::pdf_walks_found], t[wc::pdf_walks]));
    return buf;
}

}  // namespace snell
