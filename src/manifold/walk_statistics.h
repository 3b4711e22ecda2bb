#pragma once
// Manifold-walk statistics (paper Table 1): walks started and converged, success rate, mean
// iterations of successful walks, histogram of iteration counts, time in the walk, failures by kind.
// The counts are manifold/walk_counters.h's, read from a snapshot of the statistics registry.
#include <nlohmann/json.hpp>

#include <string>

#include "core/stats.h"

namespace snell {

/// True when the snapshot holds MNEE work (walks of Alg. 1 or Alg. 2).
bool has_mnee_stats(const StatTotals& t);
nlohmann::json mnee_stats_json(const StatTotals& t);
std::string mnee_stats_text(const StatTotals& t);

}  // namespace snell
