#pragma once
// User-facing settings of manifold next event estimation (scene-file names in parentheses).

#include "manifold/manifold_walk.h"

namespace snell {

struct MneeSettings {
    int max_vertices = 8;           ///< (max_vertices) refractive vertices collected on a seed path
    bool ignore_occluders = false;  ///< (ignore_occluders) walk through opaque blockers of the seed (Sec. 3.1)
    /// (cull_margin) a seed whose direction at x_b lies more than this far below the horizon
    /// (as -cos) is culled; > 0 keeps lights that are reachable only through the refracted
    /// path (Fig. 3). 1 disables culling.
    double cull_margin = 0.5;
    bool biased = false;  ///< (biased) outlier removal of Sec. 3.5
    /// (spectral_walks) through a dispersive chain every wavelength of the path solves its own
    /// chain from the same seed and light point, with its own contribution and density; false:
    /// the hero's solution alone, carrying the others' share (cheaper, colour noisier).
    bool spectral_walks = true;
    WalkSettings walk;  ///< (max_iterations, threshold, allow_error_increase, projection)
};

}  // namespace snell
