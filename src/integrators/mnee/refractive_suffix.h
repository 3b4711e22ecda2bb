#pragma once
// What `mnee` remembers about a camera path beyond the path tracer, for the MIS weights of
// Alg. 2: the refractive suffix since the last vertex that connects to lights.
#include <array>

#include "core/medium_stack.h"
#include "geometry/interaction.h"
#include "manifold/mnee_settings.h"

namespace snell {

/// The refractive suffix of a path: the last vertex x_b that can connect to lights by MNEE
/// (non-delta, not a refractive interface) and the refractive vertices x_1..x_k sampled
/// after it, with the BSDF-sampling density of x_1..x_k in area measure (deltas of specular
/// vertices factored out in half-vector measure, paper Sec. 3.3 "Specular Case").
struct RefractiveSuffix {
    static constexpr int kMaxVertices = kMaxChainVertices;
    bool has_xb = false;  ///< x_b exists and everything since is a refractive interface
    SurfaceInteraction xb;
    MediumStack xb_media;  ///< medium at x_b
    int k = 0;             ///< vertices recorded after x_b
    std::array<SurfaceInteraction, kMaxVertices> chain;
    std::array<bool, kMaxVertices> specular{};
    bool transmissions_only = true;  ///< all recorded vertices refract (MNEE can only produce those)
    double p_prefix = 1;             ///< area density of BSDF sampling x_1..x_k given x_b
    double q_last = 0;               ///< density of the last sampled direction (solid angle, deltas factored)

    /// A new x_b, reached in `media` and left by a direction of density q: the suffix starts
    /// empty. Only the fields read before they are written are reset (the chain is ~5 KB).
    void start(const SurfaceInteraction& x, const MediumStack& media, double q) {
        has_xb = true;
        xb = x;
        xb_media = media;
        k = 0;
        transmissions_only = true;
        p_prefix = 1;
        q_last = q;
    }
};

}  // namespace snell
