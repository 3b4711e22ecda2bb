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
//
// Mitsuba 3's two corrections, on by default as there:
//  - flip_invalid_normals: where the viewing direction wo lies behind the perturbed normal, the
//    normal is mirrored about the surface's (its x and y negated; Schuessler et al. 2017 flip
//    the shading normal so), so that grazing views do not turn black;
//  - use_shadowing_function: the light-side value is attenuated by Estevez et al.'s (Ray Tracing
//    Gems, 2019) microfacet shadowing term G = 2 / (1 + sqrt(1 + a^2 tan^2 theta_i)) with
//    a^2 = min(tan^2 theta_n / 8, 1) for the perturbed normal n, which smooths the terminator.
#include <memory>

#include "bsdf/bsdf.h"
#include "core/frame.h"

namespace snell {

class PerturbedFrameBSDF : public BSDF {
public:
    struct Options {
        bool flip_invalid_normals = true;
        bool shadowing = true;
    };
    PerturbedFrameBSDF(std::shared_ptr<const BSDF> nested, Options opt) : m_nested(std::move(nested)), m_opt(opt) {}

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override { return m_nested->flags(); }

    /// The perturbed normal in local coordinates of the surface's shading frame (any length).
    virtual Vec3 local_normal(const BSDFContext& ctx) const = 0;
    /// The frame the nested BSDF sees for viewing direction wo (after the flip, if enabled).
    Frame local_frame(const BSDFContext& ctx, const Vec3& wo) const;
    /// Estevez et al.'s shadowing term for perturbed normal n and light-side direction wi (1 when
    /// the option is off).
    double shadowing(const Vec3& n, const Vec3& wi) const;

protected:
    /// A frame with normal n (local coordinates), its s following the surface's s (x) by
    /// Gram-Schmidt; the unperturbed frame when n is degenerate or below the surface.
    static Frame frame_from_normal(const Vec3& n);

    std::shared_ptr<const BSDF> m_nested;
    Options m_opt;
};

}  // namespace snell
