#include "bsdf/principledthin.h"

#include <cmath>

#include "bsdf/fresnel.h"
#include "bsdf/principled_helpers.h"
#include "core/warp.h"

namespace snell {

using namespace principled;

struct PrincipledThinBSDF::Local {
    double roughness, spec_trans, diff_trans, eta;
    double p[4];  ///< lobe probabilities: specular reflection, specular transmission, diffuse R, T
    MicrofacetDistribution reflect{MicrofacetDistribution::Type::GGX, 0.1};
    MicrofacetDistribution transmit{MicrofacetDistribution::Type::GGX, 0.1};
};

PrincipledThinBSDF::Local PrincipledThinBSDF::at(const BSDFContext& ctx) const {
    Local l;
    l.roughness = m_p.roughness.eval(ctx);
    l.spec_trans = m_p.spec_trans_on ? m_p.spec_trans.eval(ctx) : 0.0;
    l.diff_trans = m_p.diff_trans_on ? m_p.diff_trans.eval(ctx) / 2 : 0.0;  // [0, 2] -> [0, 1]
    l.eta = m_p.eta.eval(ctx);
    const double aniso = m_p.anisotropic_on ? m_p.anisotropic.eval(ctx) : 0.0;
    const auto [ax, ay] = ggx_alphas(l.roughness, aniso);
    l.reflect = MicrofacetDistribution(MicrofacetDistribution::Type::GGX, ax, ay, true);
    // Burley 2015, Fig. 15: the transmitted lobe's roughness scaled by the IOR.
    const auto [tx, ty] = ggx_alphas((0.65 * l.eta - 0.35) * l.roughness, aniso);
    l.transmit = MicrofacetDistribution(MicrofacetDistribution::Type::GGX, tx, ty, true);
    l.p[0] = m_p.spec_trans_on ? l.spec_trans * m_p.spec_refl_srate / 2 : 0.0;
    l.p[1] = m_p.spec_trans_on ? l.spec_trans * m_p.spec_trans_srate / 2 : 0.0;
    l.p[2] = m_p.diff_refl_srate * (1 - l.spec_trans) * (1 - l.diff_trans);
    l.p[3] = m_p.diff_trans_on ? m_p.diff_trans_srate * (1 - l.spec_trans) * l.diff_trans : 0.0;
    const double total = l.p[0] + l.p[1] + l.p[2] + l.p[3];
    for (double& q : l.p) q = total > 0 ? q / total : 0.0;
    return l;
}

// The sheet is symmetric: turn it so that wo is in front. The transmitted specular direction is
// the reflected one carried through the sheet, so both specular lobes share the half vector of wo
// and wi with wi mirrored to the front.
SampledSpectrum PrincipledThinBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return {};
    const double s = wo.z > 0 ? 1.0 : -1.0;
    return eval_front(ctx, at(ctx), wo * s, wi * s);
}

SampledSpectrum PrincipledThinBSDF::eval_front(const BSDFContext& ctx, const Local& l, const Vec3& wo,
                                               const Vec3& wi) const {
    const bool reflect = wi.z > 0;
    const Vec3 wi_up(wi.x, wi.y, std::abs(wi.z));
    const Vec3 h = normalize(wo + wi_up);
    const double cos_o = wo.z, cos_i = std::abs(wi.z);
    const SampledSpectrum base = m_p.base_color->eval(ctx.point(), ctx.wl);
    SampledSpectrum f(0.0);
    if (m_p.spec_trans_on && l.spec_trans > 0) {
        const double F = fresnel_dielectric(dot(wo, h), l.eta).R;
        if (reflect && compatible(h, wo, wi, true)) {
            const double D = l.reflect.D(h), G = l.reflect.G(wo, wi, h);
            // Mitsuba's thin Fresnel: the dielectric's, blended by spec_tint towards a Schlick
            // term with F0 tinted by the base colour's hue.
            const double spec_tint = m_p.spec_tint.eval(ctx);
            const double lum = spec_tint > 0 ? m_p.base_color->eval_float(ctx.point()) : 1.0;
            for (int k = 0; k < kSpectrumSamples; ++k) {
                double Ft = F;
                if (spec_tint > 0) {
                    const double tint = lum > 0 ? base[k] / lum : 1.0;
                    Ft = (1 - spec_tint) * F + spec_tint * schlick(tint * schlick_r0(l.eta), dot(wo, h), l.eta);
                }
                f[k] += l.spec_trans * Ft * D * G / (4 * cos_o * cos_i);
            }
        }
        // Masking of the transmitted light where it left the microfacet: along the mirror
        // direction wi_up, on the front. (Mitsuba masks the direction carried through the sheet,
        // which is not reciprocal: up to 6 % apart both ways round; the reciprocal form keeps
        // bdpt and path in agreement.)
        if (!reflect && compatible(h, wo, wi_up, true)) {
            const double D = l.transmit.D(h), G = l.transmit.G(wo, wi_up, h);
            f += base * (l.spec_trans * (1 - F) * D * G / (4 * cos_o * cos_i));
        }
    }
    if (reflect && l.spec_trans < 1 && l.diff_trans < 1) {
        const double cos_d = dot(h, wi);
        const double w = (1 - l.spec_trans) * (1 - l.diff_trans);
        f += base * (w * kInvPi * diffuse_shape(cos_o, cos_i, cos_d, l.roughness, m_p.flatness.eval(ctx)));
        const double sheen = m_p.sheen.eval(ctx);
        if (sheen > 0) {
            const double Fd = schlick_weight(std::abs(cos_d));
            const double sheen_tint = m_p.sheen_tint.eval(ctx);
            const double lum = m_p.base_color->eval_float(ctx.point());
            for (int k = 0; k < kSpectrumSamples; ++k) {
                const double tint = lum > 0 ? base[k] / lum : 1.0;
                f[k] += sheen * w * Fd * (1 - sheen_tint + tint * sheen_tint);
            }
        }
    }
    if (!reflect && l.spec_trans < 1 && l.diff_trans > 0) f += base * ((1 - l.spec_trans) * l.diff_trans * kInvPi);
    return f;
}

double PrincipledThinBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0;
    const double s = wo.z > 0 ? 1.0 : -1.0;
    return pdf_front(at(ctx), wo * s, wi * s);
}

double PrincipledThinBSDF::pdf_front(const Local& l, const Vec3& wo, const Vec3& wi) const {
    const bool reflect = wi.z > 0;
    double pdf = 0;
    if (m_p.spec_trans_on) {
        const Vec3 wi_up(wi.x, wi.y, std::abs(wi.z));
        const Vec3 h = normalize(wo + wi_up);
        const double dh = 1.0 / (4 * std::abs(dot(wi_up, h)));  // |dh/dwi| of the mirror
        if (reflect && compatible(h, wo, wi, true)) pdf += l.p[0] * l.reflect.pdf(wo, h) * dh;
        if (!reflect && compatible(h, wo, wi_up, true)) pdf += l.p[1] * l.transmit.pdf(wo, h) * dh;
    }
    if (reflect)
        pdf += l.p[2] * warp::square_to_cosine_hemisphere_pdf(wi);
    else
        pdf += l.p[3] * warp::square_to_cosine_hemisphere_pdf(-wi);
    return pdf;
}

std::optional<BSDFSample> PrincipledThinBSDF::sample(const BSDFContext& ctx, const Vec3& wo_in, double uc,
                                                     const Vec2& u) const {
    if (wo_in.z == 0) return std::nullopt;
    const double s = wo_in.z > 0 ? 1.0 : -1.0;
    const Vec3 wo = wo_in * s;
    const Local l = at(ctx);
    BSDFSample b;
    Vec3 wi;
    if (uc < l.p[0]) {
        const auto [m, pm] = l.reflect.sample(wo, u);
        if (!(pm > 0)) return std::nullopt;
        wi = snell::reflect(wo, m);
        if (!(wi.z > 0) || !compatible(m, wo, wi, true)) return std::nullopt;
        b.lobe = kReflection | kGlossy;
    } else if (uc < l.p[0] + l.p[1]) {
        const auto [m, pm] = l.transmit.sample(wo, u);
        if (!(pm > 0)) return std::nullopt;
        const Vec3 wi_up = snell::reflect(wo, m);
        if (!(wi_up.z > 0) || !compatible(m, wo, wi_up, true)) return std::nullopt;
        wi = Vec3(wi_up.x, wi_up.y, -wi_up.z);  // through the sheet, unbent
        b.lobe = kTransmission | kGlossy;
    } else if (uc < l.p[0] + l.p[1] + l.p[2]) {
        wi = warp::square_to_cosine_hemisphere(u);
        b.lobe = kReflection | kDiffuse;
    } else {
        wi = -warp::square_to_cosine_hemisphere(u);
        b.lobe = kTransmission | kDiffuse;
    }
    if (wi.z == 0) return std::nullopt;
    b.pdf = pdf_front(l, wo, wi);
    if (!(b.pdf > 0)) return std::nullopt;
    b.weight = eval_front(ctx, l, wo, wi) * (std::abs(wi.z) / b.pdf);
    b.wi = wi * s;
    return b;
}

}  // namespace snell
