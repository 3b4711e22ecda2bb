#pragma once
// What the path tracer remembers about the path so far, for MIS weights of emitter hits.
#include <array>

#include "core/medium_stack.h"
#include "geometry/interaction.h"
#include "light/light.h"
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
};

struct PathState {
    int depth = 0;             ///< index of the current vertex (0: first hit; it ends segment depth + 1)
    bool prev_delta = true;    ///< the previous vertex was sampled from a delta lobe (or is the camera)
    double prev_bsdf_pdf = 0;  ///< solid-angle density of the last sampled direction
    LightSampleContext prev;   ///< previous vertex (for light pdfs of emitter hits)
    MediumStack media;         ///< interiors the path is in
    /// A dispersive refraction was sampled: the throughput carries the hero wavelength alone
    /// (already scaled by SampledWavelengths::hero_only), so no later factor may scale it again.
    bool hero_only = false;
    /// The path throughput at the current vertex, for derived integrators' hooks that weigh
    /// what a technique contributes (MNEE's ConnectionAllocation pilot).
    SampledSpectrum beta;
    /// beta times the emitted radiance of the emitter hit that emitter_hit_weight() is weighing.
    SampledSpectrum emitter_value;
};

}  // namespace snell
