#pragma once
// Mitsuba 3's `principled` BSDF: the Disney model (Burley 2012, "Physically Based Shading at
// Disney"; Burley 2015, "Extending the Disney BRDF to a BSDF with Integrated Subsurface
// Scattering") with Mitsuba's choice of lobes, weights and sampling, so that scenes render as
// they do there:
//   - diffuse with retro-reflection, blended towards Hanrahan-Krueger "fake subsurface" by
//     `flatness`, weight (1 - metallic)(1 - spec_trans), front side only;
//   - sheen (Schlick weight of the half angle, tinted by `sheen_tint`);
//   - main specular reflection: GGX (roughness^2, stretched by `anisotropic`) with the
//     "principled" Fresnel: the dielectric's exact Fresnel, a Schlick part tinted towards the
//     base colour by `spec_tint`, and a metallic Schlick part with F0 = base colour;
//   - specular transmission: rough dielectric GGX (Walter et al. 2007) tinted by
//     sqrt(base colour), weight (1 - metallic) spec_trans;
//   - clearcoat: GTR1 with alpha from 0.1 to 0.001 as `clearcoat_gloss` goes from 0 to 1,
//     Schlick F0 = 0.04, Smith GGX shadowing of alpha 0.25, weight clearcoat / 4.
// From inside (wo below) only the dielectric's reflection and transmission remain. Lobes are
// chosen with Mitsuba's probabilities (sampling rates; the split of the specular group into
// reflection and transmission by the Fresnel term at the sampled microfacet), and pdf() is that
// mixture's density, so sample() is consistent with pdf() (chi-square test).
#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"
#include "bsdf/param.h"

namespace snell {

class PrincipledBSDF final : public BSDF {
public:
    struct Params {
        TextureRef base_color;  ///< colour (0.5)
        FloatParam roughness = 0.5, anisotropic = 0.0, metallic = 0.0, spec_trans = 0.0, spec_tint = 0.0, sheen = 0.0,
                   sheen_tint = 0.0, flatness = 0.0, clearcoat = 0.0, clearcoat_gloss = 0.0;
        double eta = 1.5;  ///< interior over exterior IOR (from `specular` when `eta` is not given)
        double spec_srate = 1, clearcoat_srate = 1, diffuse_srate = 1;             ///< lobe sampling rates
        bool anisotropic_on = false, spec_trans_on = false, clearcoat_on = false;  ///< lobes present
    };
    explicit PrincipledBSDF(Params p) : m_p(std::move(p)) {}

    SampledSpectrum eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    double pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    std::optional<BSDFSample> sample(const BSDFContext& ctx, const Vec3& wo, double uc, const Vec2& u) const override;
    uint32_t flags() const override {
        return kReflection | kDiffuse | kGlossy | (m_p.spec_trans_on ? kTransmission : 0u);
    }
    double eta(double /*lambda*/) const override { return m_p.spec_trans_on ? m_p.eta : 1.0; }

    /// Mitsuba's eta for a `specular` value: F0 = 0.08 specular = ((eta - 1) / (eta + 1))^2.
    static double eta_from_specular(double specular) { return 2.0 / (1.0 - std::sqrt(0.08 * specular)) - 1.0; }

private:
    /// The parameters read at ctx's point, and the quantities every method needs.
    struct Local;
    Local at(const BSDFContext& ctx) const;
    /// eval() and pdf() with the parameters already read (sample() reads them once).
    SampledSpectrum eval_at(const BSDFContext& ctx, const Local& l, const Vec3& wo, const Vec3& wi) const;
    double pdf_at(const Local& l, const Vec3& wo, const Vec3& wi) const;
    /// Probabilities of the diffuse, clearcoat, specular reflection and transmission lobes for
    /// a Fresnel reflectance F at the microfacet (normalised to sum 1).
    void lobe_probabilities(const Local& l, bool front, double F, double p[4]) const;

    Params m_p;
};

}  // namespace snell
