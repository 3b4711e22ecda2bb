#pragma once
// Base of Mitsuba's `normalmap` and `bumpmap`: the nested BSDF evaluated in a perturbed shading
// frame, given in the local coordinates of the surface's own frame and computed at the surface
// point the context carries. As in Mitsuba (and pbrt-v4, whose integrators then take the cosine
// with the perturbed normal), the value returned is the nested BSDF times the *perturbed* cosine
// of the light-side direction; in snell's convention (eval without cosine, the integrator
// multiplying by the surface's own cosine) eval() is nested * |cos'_i| / |cos_i|. A direction on
// the other side of the perturbed surface than of the real one gives 0 (Mitsuba's rule, for the
// light-side direction). Sampling is the nested BSDF's; a rotation keeps solid angle, so pdfs are
// the nested ones.
#include <memory>

#include "bsdf/bsdf.h"
#include "core/frame.h"

namespace snell {

class PerturbedFrameBSDF : public BSDF {
public:
    explicit PerturbedFrameBSDF(std::shared_ptr<const BSDF> nested) : m_nested(std::move(nested)) {}

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return m_nested->flags(); }

    /// The perturbed frame in local coordinates of the surface's shading frame.
    virtual Frame local_frame(const BSDFContext& ctx) const = 0;

protected:
    /// A frame with normal n (local coordinates), its s following the surface's s (x) by
    /// Gram-Schmidt; the unperturbed frame when n is degenerate or below the surface.
    static Frame frame_from_normal(const Vec3& n);

    std::shared_ptr<const BSDF> m_nested;
};

}  // namespace snell
