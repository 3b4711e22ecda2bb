#include "bsdf/principled.h"

#include <algorithm>
#include <cmath>

#include "bsdf/fresnel.h"
#include "bsdf/principled_helpers.h"
#include "core/warp.h"

namespace snell {

using namespace principled;

namespace {

/// Burley's GTR1 ("Berry") distribution of the clearcoat, normalised in projected area.
struct GTR1 {
    double alpha;
    double D(const Vec3& m) const {
        const double a2 = alpha * alpha;
        const double d = (a2 - 1) / (kPi * std::log(a2) * (1 + (a2 - 1) * m.z * m.z));
        return d * m.z > 1e-20 ? d : 0.0;
    }
    double pdf(const Vec3& m) const { return m.z < 0 ? 0.0 : m.z * D(m); }
    Vec3 sample(const Vec2& u) const {
        const double a2 = alpha * alpha, phi = 2 * kPi * u.x;
        const double cos2 = (1 - std::pow(a2, 1 - u.y)) / (1 - a2);
        const double sin_t = std::sqrt(std::max(0.0, 1 - cos2)), cos_t = std::sqrt(std::max(0.0, cos2));
        return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
    }
};

/// Smith's GGX masking of direction v for a fixed alpha (the clearcoat's 0.25).
double smith_ggx1(const Vec3& v, const Vec3& m, double alpha) {
    if (dot(v, m) * v.z <= 0) return 0;
    if (v.z == 1.0) return 1;
    const double c2 = v.z * v.z, tan2 = (1 - c2) / c2;
    return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

}  // namespace

struct PrincipledBSDF::Local {
    double roughness, metallic, spec_trans, clearcoat, brdf, bsdf;
    MicrofacetDistribution distr{MicrofacetDistribution::Type::GGX, 0.1};
    GTR1 cc{0.1};
};

PrincipledBSDF::Local PrincipledBSDF::at(const BSDFContext& ctx) const {
    Local l;
    l.roughness = m_p.roughness.eval(ctx);
    l.metallic = m_p.metallic.eval(ctx);
    l.spec_trans = m_p.spec_trans_on ? m_p.spec_trans.eval(ctx) : 0.0;
    l.clearcoat = m_p.clearcoat_on ? m_p.clearcoat.eval(ctx) : 0.0;
    l.brdf = (1 - l.metallic) * (1 - l.spec_trans);
    l.bsdf = (1 - l.metallic) * l.spec_trans;
    const auto [ax, ay] = ggx_alphas(l.roughness, m_p.anisotropic_on ? m_p.anisotropic.eval(ctx) : 0.0);
    l.distr = MicrofacetDistribution(MicrofacetDistribution::Type::GGX, ax, ay, true);
    if (m_p.clearcoat_on) {
        const double g = m_p.clearcoat_gloss.eval(ctx);
        l.cc = GTR1{0.1 * (1 - g) + 0.001 * g};
    }
    return l;
}

void PrincipledBSDF::lobe_probabilities(const Local& l, bool front, double F, double p[4]) const {
    // 0 diffuse, 1 clearcoat, 2 specular reflection, 3 specular transmission.
    if (front) {
        p[0] = l.brdf * m_p.diffuse_srate;
        p[1] = m_p.clearcoat_on ? 0.25 * l.clearcoat * m_p.clearcoat_srate : 0.0;
        p[2] = m_p.spec_srate * (1 - l.bsdf * (1 - F));
        p[3] = m_p.spec_trans_on ? m_p.spec_srate * l.bsdf * (1 - F) : 0.0;
    } else {
        p[0] = p[1] = 0;
        p[2] = F;
        p[3] = m_p.spec_trans_on ? 1 - F : 0.0;
    }
    const double total = p[0] + p[1] + p[2] + p[3];
    for (int k = 0; k < 4; ++k) p[k] = total > 0 ? p[k] / total : 0.0;
}

SampledSpectrum PrincipledBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return {};
    return eval_at(ctx, at(ctx), wo, wi);
}

SampledSpectrum PrincipledBSDF::eval_at(const BSDFContext& ctx, const Local& l, const Vec3& wo, const Vec3& wi) const {
    const bool front = wo.z > 0, reflect = wo.z * wi.z > 0;
    const double eta_path = front ? m_p.eta : 1.0 / m_p.eta;
    Vec3 h = normalize(wo + wi * (reflect ? 1.0 : eta_path));
    if (h.z < 0) h = -h;
    const DielectricFresnel fr = fresnel_dielectric(dot(wo, h), m_p.eta);
    const double F = fr.R;
    const double cos_o = std::abs(wo.z), cos_i = std::abs(wi.z);
    const SampledSpectrum base = m_p.base_color->eval(ctx.point(), ctx.wl);
    const double D = l.distr.D(h), G = l.distr.G(wo, wi, h);
    SampledSpectrum f(0.0);

    if (reflect && compatible(h, wo, wi, true) && F > 0) {
        // The principled Fresnel: dielectric, spec-tinted Schlick and metallic Schlick parts.
        SampledSpectrum Fp;
        if (front) {
            const double spec_tint = m_p.spec_tint.eval(ctx);
            const double lum = m_p.base_color->eval_float(ctx.point());
            const double eta_it = dot(wo, h) >= 0 ? m_p.eta : 1.0 / m_p.eta;
            for (int k = 0; k < kSpectrumSamples; ++k) {
                const double tint = lum > 0 ? base[k] / lum : 1.0;
                Fp[k] = (1 - l.metallic) * (1 - spec_tint) * F + l.metallic * schlick(base[k], dot(wo, h), m_p.eta) +
                        (1 - l.metallic) * spec_tint * schlick(tint * schlick_r0(eta_it), dot(wo, h), m_p.eta);
            }
        } else {
            Fp = SampledSpectrum(l.bsdf * F);
        }
        f += Fp * (D * G / (4 * cos_o * cos_i));
    }
    if (!reflect && m_p.spec_trans_on && l.bsdf > 0 && compatible(h, wo, wi, false) && F < 1) {
        // Walter et al. 2007, Eq. 21, with the radiance scaling in Radiance mode.
        const double scale = ctx.mode == TransportMode::Radiance ? 1.0 / (eta_path * eta_path) : 1.0;
        const double v = std::abs(scale * (1 - F) * D * G * eta_path * eta_path * dot(wo, h) * dot(wi, h) /
                                  (wo.z * sqr(dot(wo, h) + eta_path * dot(wi, h))));
        for (int k = 0; k < kSpectrumSamples; ++k) f[k] += std::sqrt(std::max(0.0, base[k])) * l.bsdf * v / cos_i;
    }
    if (reflect && front && l.clearcoat > 0 && compatible(h, wo, wi, true)) {
        // Mitsuba's clearcoat value: clearcoat / 4 * F D G (times the light's cosine there).
        const double Fcc = schlick(0.04, dot(wo, h), m_p.eta);
        const double Gcc = smith_ggx1(wo, h, 0.25) * smith_ggx1(wi, h, 0.25);
        f += SampledSpectrum(0.25 * l.clearcoat * Fcc * l.cc.D(h) * Gcc);
    }
    if (reflect && front) {
        const double cos_d = dot(h, wi);
        if (l.brdf > 0)
            f += base * (l.brdf * kInvPi * diffuse_shape(cos_o, cos_i, cos_d, l.roughness, m_p.flatness.eval(ctx)));
        const double sheen = m_p.sheen.eval(ctx);
        if (sheen > 0 && l.metallic < 1) {
            const double Fd = schlick_weight(std::abs(cos_d));
            const double sheen_tint = m_p.sheen_tint.eval(ctx);
            const double lum = m_p.base_color->eval_float(ctx.point());
            for (int k = 0; k < kSpectrumSamples; ++k) {
                const double tint = lum > 0 ? base[k] / lum : 1.0;
                f[k] += sheen * (1 - l.metallic) * Fd * (1 - sheen_tint + tint * sheen_tint);
            }
        }
    }
    return f;
}

double PrincipledBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return 0;
    return pdf_at(at(ctx), wo, wi);
}

double PrincipledBSDF::pdf_at(const Local& l, const Vec3& wo, const Vec3& wi) const {
    const bool front = wo.z > 0, reflect = wo.z * wi.z > 0;
    const double eta_path = front ? m_p.eta : 1.0 / m_p.eta;
    Vec3 h = normalize(wo + wi * (reflect ? 1.0 : eta_path));
    if (h.z < 0) h = -h;
    double p[4];
    lobe_probabilities(l, front, fresnel_dielectric(dot(wo, h), m_p.eta).R, p);
    // |dh/dwi|: Walter et al. Eqs. 14 and 17.
    const double dh = reflect ? 1.0 / (4 * std::abs(dot(wi, h)))
                              : eta_path * eta_path * std::abs(dot(wi, h)) / sqr(dot(wo, h) + eta_path * dot(wi, h));
    const Vec3 wo_up = front ? wo : -wo;
    double pdf = 0;
    if (reflect) {
        if (compatible(h, wo, wi, true)) {
            pdf += p[2] * l.distr.pdf(wo_up, h) * dh;
            if (p[1] > 0) pdf += p[1] * l.cc.pdf(h) * dh;
        }
        if (front) pdf += p[0] * warp::square_to_cosine_hemisphere_pdf(wi);
    } else if (p[3] > 0 && compatible(h, wo, wi, false)) {
        pdf += p[3] * l.distr.pdf(wo_up, h) * dh;
    }
    return pdf;
}

std::optional<BSDFSample> PrincipledBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                                 const Vec2& u) const {
    if (wo.z == 0) return std::nullopt;
    const Local l = at(ctx);
    const bool front = wo.z > 0;
    if (!front && !(l.bsdf > 0 && m_p.spec_trans_on)) return std::nullopt;
    const Vec3 wo_up = front ? wo : -wo;
    const auto [m, pm] = l.distr.sample(wo_up, u);
    if (!(pm > 0)) return std::nullopt;
    const DielectricFresnel fr = fresnel_dielectric(dot(wo, m), m_p.eta);
    double p[4];
    lobe_probabilities(l, front, fr.R, p);
    BSDFSample s;
    if (uc < p[0]) {
        s.wi = warp::square_to_cosine_hemisphere(u);
        s.lobe = kReflection | kDiffuse;
    } else if (uc < p[0] + p[1]) {
        const Vec3 mc = l.cc.sample(u);
        s.wi = reflect(wo, mc);
        s.lobe = kReflection | kGlossy;
        if (s.wi.z * wo.z <= 0 || !compatible(mc, wo, s.wi, true)) return std::nullopt;
    } else if (uc < p[0] + p[1] + p[3]) {
        s.wi = refract(wo, m, fr.cos_t, fr.eta_ti);
        s.lobe = kTransmission | kGlossy;
        s.eta = fr.eta_it;
        if (s.wi.z * wo.z >= 0 || !compatible(m, wo, s.wi, false)) return std::nullopt;
    } else {
        s.wi = reflect(wo, m);
        s.lobe = kReflection | kGlossy;
        if (s.wi.z * wo.z <= 0 || !compatible(m, wo, s.wi, true)) return std::nullopt;
    }
    if (s.wi.z == 0) return std::nullopt;
    // The parameters read once for the sample, its density and its value.
    s.pdf = pdf_at(l, wo, s.wi);
    if (!(s.pdf > 0)) return std::nullopt;
    s.weight = eval_at(ctx, l, wo, s.wi) * (std::abs(s.wi.z) / s.pdf);
    return s;
}

}  // namespace snell
