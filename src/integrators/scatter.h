#pragma once
// The bookkeeping every random walk does at a scattering vertex, shared by the path tracer's
// loop and bdpt's subpaths: the throughput update, the hero-wavelength switch at a dispersive
// refraction, the medium change at an interface, and Russian roulette.
#include <algorithm>

#include "bsdf/bsdf.h"
#include "core/medium_stack.h"
#include "core/sampled_spectrum.h"
#include "geometry/interaction.h"

namespace snell {

/// What a walk carries from vertex to vertex besides its position.
struct Throughput {
    SampledSpectrum beta{1.0};  ///< path throughput: product of f |cos| / pdf (and 1 / q of roulette)
    /// Product of eta^2 over the refractions of radiance transport: refraction compresses
    /// radiance by 1 / eta^2 (Veach 1997, Sec. 5.2), which roulette must not read as absorption.
    double eta_scale = 1;
    /// A dispersive refraction was sampled: beta carries the hero wavelength alone, already
    /// scaled by SampledWavelengths::hero_only, so no later factor may scale it again.
    bool hero_only = false;

    /// Multiplies in a BSDF sample's weight (the sample was drawn in `mode`).
    void scatter(const BSDFSample& bs, const SampledWavelengths& wl, TransportMode mode) {
        beta *= bs.weight;
        if (bs.hero_only && !hero_only) {
            beta = wl.hero_only(beta);
            hero_only = true;
        }
        if (mode == TransportMode::Radiance && (bs.lobe & kTransmission) && bs.eta != 1.0) eta_scale *= sqr(bs.eta);
    }

    /// Russian roulette with survival probability min(0.95, max(beta) eta_scale) (pbrt-v4's
    /// rule). Returns false when the walk ends; a survivor's beta is divided by that probability,
    /// so the estimate stays unbiased.
    bool survives_roulette(double u) {
        const double q = std::min(0.95, beta.max_component() * eta_scale);
        if (!(u < q)) return false;
        beta /= q;
        return true;
    }
};

/// Whether a sampled transmission through `bsdf` enters or leaves an interior: a dielectric
/// with eta != 1, or an index-matched one that absorbs inside. A thin sheet (eta 1, no
/// interior) encloses nothing.
inline bool crosses_interior(const BSDF& bsdf, const BSDFSample& bs) {
    return (bs.lobe & kTransmission) && (bs.eta != 1.0 || bsdf.interior_absorption());
}

/// Pushes or pops the interior of `bsdf` on `media` for a transmission at `si`: entering when
/// si.wo lies on the side the geometric normal points to.
inline void cross_interface(MediumStack& media, const SurfaceInteraction& si, const BSDF& bsdf) {
    media.cross(bsdf.interior_absorption(), dot(si.wo, si.ng) > 0);
}

/// The medium a connection segment leaving `si` along world direction `d` lies in: the path's
/// own, or the one behind the interface when d crosses it (a rough dielectric connecting
/// through itself). `lambda` picks the interface's eta.
inline MediumStack medium_towards(const MediumStack& media, const SurfaceInteraction& si, const BSDF& bsdf,
                                  const Vec3& d, double lambda) {
    MediumStack m = media;
    if (dot(si.wo, si.ng) * dot(d, si.ng) < 0 && (bsdf.eta(lambda) != 1.0 || bsdf.interior_absorption()))
        cross_interface(m, si, bsdf);
    return m;
}

}  // namespace snell
