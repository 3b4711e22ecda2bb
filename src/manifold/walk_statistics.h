#pragma once
// Manifold-walk statistics (paper Table 1): walks started and converged, success rate, mean
// iterations of successful walks, histogram of iteration counts, time in the walk, failures by kind.
#include <nlohmann/json.hpp>

#include <string>

#include "core/stats.h"

namespace snell {

nlohmann::json mnee_stats_json(const Counters& c);
std::string mnee_stats_text(const Counters& c);

}  // namespace snell
