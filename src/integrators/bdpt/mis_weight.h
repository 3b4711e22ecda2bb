#pragma once
// BDPT's multiple importance sampling weights (power heuristic over every strategy of a path).
#include <vector>

#include "integrators/bdpt/vertex.h"

namespace snell::bdpt {

// Power-heuristic weight of strategy (s, t) among all strategies s' + t' = s + t with t' >= 1
// (Veach's thesis, Sec. 10.2): the ratios of each alternative's density to this one's follow
// from per-vertex forward and reverse densities, recomputed around the connection.
double mis_weight(const Scene& scene, const SceneDisk& disk, const std::vector<Vertex>& cam,
                  const std::vector<Vertex>& lig, int s, int t, const SampledWavelengths& wl);

}  // namespace snell::bdpt
