#pragma once
// Mitsuba 3's `principledthin`: the Disney BSDF for a thin sheet (Burley 2015, "Extending the
// Disney BRDF to a BSDF with Integrated Subsurface Scattering", Sec. 5): both sides alike (the
// sheet is symmetric), with
//   - diffuse reflection (retro-reflection, `flatness` towards fake subsurface) and sheen, weight
//     (1 - spec_trans)(1 - diff_trans / 2);
//   - diffuse transmission, Lambertian, weight (1 - spec_trans) diff_trans / 2 (diff_trans in
//     [0, 2], as in Burley's paper);
//   - specular reflection: GGX with the dielectric Fresnel of `eta`, tinted by `spec_tint`;
//   - specular transmission through the sheet without bending: the mirror direction carried to the
//     other side, GGX with roughness scaled by 0.65 eta - 0.35 (Burley 2015, Fig. 15), tinted by
//     the base colour, (1 - F) of the dielectric; masked along the mirror direction (reciprocal;
//     Mitsuba masks the carried one, which is not).
// Lobes are chosen with Mitsuba's probabilities and sampling rates; pdf() is that mixture.
#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"
#include "bsdf/param.h"

namespace snell {

class PrincipledThinBSDF final : public BSDF {
public:
    struct Params {
        TextureRef base_color;  ///< colour (0.5)
        FloatParam roughness = 0.5, anisotropic = 0.0, spec_trans = 0.0, spec_tint = 0.0, sheen = 0.0, sheen_tint = 0.0,
                   flatness = 0.0, diff_trans = 0.0, eta = 1.5;
        double spec_refl_srate = 1, spec_trans_srate = 1, diff_refl_srate = 1, diff_trans_srate = 1;
        bool anisotropic_on = false, spec_trans_on = false, diff_trans_on = false;  ///< lobes present
    };
    explicit PrincipledThinBSDF(Params p) : m_p(std::move(p)) {}

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override {
        return kReflection | kDiffuse | kGlossy | (m_p.spec_trans_on || m_p.diff_trans_on ? kTransmission : 0u);
    }

private:
    struct Local;
    Local at(const BSDFContext& ctx) const;
    /// eval() and pdf() for wo.z > 0 (the sheet turned so that wo is in front), parameters read.
    SampledSpectrum eval_front(const BSDFContext& ctx, const Local& l, const Vec3& wo, const Vec3& wi) const;
    double pdf_front(const Local& l, const Vec3& wo, const Vec3& wi) const;

    Params m_p;
};

}  // namespace snell
