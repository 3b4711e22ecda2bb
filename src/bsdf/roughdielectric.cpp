#include "bsdf/roughdielectric.h"

#include "bsdf/fresnel.h"

namespace snell {

RoughDielectricBSDF::RoughDielectricBSDF(MicrofacetParam distribution, Spectrum int_ior, Spectrum ext_ior,
                                         SpectrumParam specular_reflectance, SpectrumParam specular_transmittance,
                                         std::optional<Spectrum> sigma_a)
    : m_distr(distribution),
      m_int_ior(std::move(int_ior)),
      m_ext_ior(std::move(ext_ior)),
      m_specular_reflectance(std::move(specular_reflectance)),
      m_specular_transmittance(std::move(specular_transmittance)),
      m_sigma_a(std::move(sigma_a)) {}

bool RoughDielectricBSDF::half_vector(double eta, const Vec3& wo, const Vec3& wi, Vec3& m) const {
    const bool reflect = wo.z * wi.z > 0;
    // eta_it: IOR on wi's side over wo's side (Walter et al. Eq. 16: h_t = -(eta_o wo + eta_i wi)).
    const double eta_it = wo.z > 0 ? eta : 1.0 / eta;
    const Vec3 h = reflect ? wo + wi : wo + wi * eta_it;
    const double l2 = length_squared(h);
    if (!(l2 > 0)) return false;
    m = h / std::sqrt(l2);
    if (m.z < 0) m = -m;
    return m.z > 0;
}

SampledSpectrum RoughDielectricBSDF::eval(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z == 0 || wi.z == 0) return {};
    const bool reflection = wo.z * wi.z > 0;
    SampledSpectrum f;
    const MicrofacetDistribution distr = m_distr.eval(ctx);
    if (!dispersive()) {
        f = SampledSpectrum(eval_scalar(distr, eta(ctx.hero()), ctx.mode, wo, wi));
    } else {
        // Each wavelength has its own half vector for the same pair of directions.
        for (int i = 0; i < kSpectrumSamples; ++i) f[i] = eval_scalar(distr, eta(ctx.wl[i]), ctx.mode, wo, wi);
    }
    return f * (reflection ? m_specular_reflectance : m_specular_transmittance).eval(ctx);
}

double RoughDielectricBSDF::eval_scalar(const MicrofacetDistribution& distr, double eta, TransportMode mode,
                                        const Vec3& wo, const Vec3& wi) const {
    const double cos_o = wo.z, cos_i = wi.z;
    Vec3 m;
    if (!half_vector(eta, wo, wi, m)) return 0;
    // Both directions must see the microfacet from their own side of the macro surface.
    if (dot(wo, m) * cos_o <= 0 || dot(wi, m) * cos_i <= 0) return 0;
    const double D = distr.D(m);
    if (D == 0) return 0;
    const double G = distr.G(wo, wi, m);
    const double F = fresnel_dielectric(dot(wo, m), eta).R;
    if (cos_o * cos_i > 0) {
        // Walter et al. Eq. 20.
        return F * D * G / (4 * std::abs(cos_o * cos_i));
    }
    // Walter et al. Eq. 21.
    const double eta_it = cos_o > 0 ? eta : 1.0 / eta;
    const double denom = dot(wo, m) + eta_it * dot(wi, m);
    const double value =
        std::abs(dot(wo, m) * dot(wi, m) / (cos_o * cos_i)) * sqr(eta_it) * (1 - F) * D * G / sqr(denom);
    const double scale = mode == TransportMode::Radiance ? 1.0 / sqr(eta_it) : 1.0;
    return value * scale;
}

double RoughDielectricBSDF::pdf(const BSDFContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const double cos_o = wo.z, cos_i = wi.z;
    if (cos_o == 0 || cos_i == 0) return 0;
    const double eta = this->eta(ctx.hero());
    Vec3 m;
    if (!half_vector(eta, wo, wi, m)) return 0;
    if (dot(wo, m) * cos_o <= 0 || dot(wi, m) * cos_i <= 0) return 0;
    const bool reflect = cos_o * cos_i > 0;
    // Jacobian of the map m -> wi (Walter et al. Eqs. 14 and 17).
    double dm_dwi;
    if (reflect) {
        dm_dwi = 1.0 / (4 * std::abs(dot(wi, m)));
    } else {
        const double eta_it = cos_o > 0 ? eta : 1.0 / eta;
        dm_dwi = sqr(eta_it) * std::abs(dot(wi, m)) / sqr(dot(wo, m) + eta_it * dot(wi, m));
    }
    // The microfacet sampler always sees wo from above.
    const Vec3 wo_up = cos_o > 0 ? wo : -wo;
    const double pm = m_distr.eval(ctx).pdf(wo_up, m);
    const double F = fresnel_dielectric(dot(wo, m), eta).R;
    return pm * (reflect ? F : 1 - F) * dm_dwi;
}

std::optional<BSDFSample> RoughDielectricBSDF::sample(const BSDFContext& ctx, const Vec3& wo, double uc,
                                                      const Vec2& u) const {
    if (wo.z == 0) return std::nullopt;
    const double eta = this->eta(ctx.hero());
    const Vec3 wo_up = wo.z > 0 ? wo : -wo;
    const MicrofacetDistribution distr = m_distr.eval(ctx);
    const auto [m, pm] = distr.sample(wo_up, u);
    if (!(pm > 0)) return std::nullopt;
    const DielectricFresnel f = fresnel_dielectric(dot(wo, m), eta);
    BSDFSample s;
    if (uc < f.R) {
        s.wi = reflect(wo, m);
        s.lobe = kReflection | kGlossy;
        s.eta = 1;
        if (s.wi.z * wo.z <= 0) return std::nullopt;  // reflected below the macro surface
    } else {
        s.wi = refract(wo, m, f.cos_t, f.eta_ti);
        s.lobe = kTransmission | kGlossy;
        s.eta = f.eta_it;
        if (s.wi.z * wo.z >= 0) return std::nullopt;  // refracted to the wrong side
        // The refracted direction depends on the wavelength: keep the hero alone (pbrt-v4
        // does the same; the others' f/pdf would have a heavy tail at small roughness).
        s.hero_only = dispersive();
    }
    // The closed forms of pdf() and eval() at the sampled microfacet m, without finding m again
    // from (wo, wi): the BSDF is sampled at every rough-glass vertex, and evaluating both cost
    // half of sample(). With c = |wi.m| / (|wo.m + eta_it wi.m|^2) eta_it^2 for refraction
    // (Walter et al. Eq. 17) and 1 / (4 |wi.m|) for reflection (Eq. 14):
    //   pdf = p(m) (F or 1 - F) c,   f |cos_i| / pdf = D G |wo.m| / (|cos_o| p(m)) (times the
    // radiance scale 1 / eta_it^2 for refraction; reflection has |wi.m| = |wo.m|).
    // Both are the hero's: m is the hero's half vector for (wo, wi).
    const double cos_o = wo.z, wo_m = dot(wo, m), wi_m = dot(s.wi, m);
    if (wo_m * cos_o <= 0 || wi_m * s.wi.z <= 0) return std::nullopt;
    const bool reflected = s.lobe & kReflection;
    const double eta_it = cos_o > 0 ? eta : 1.0 / eta;
    const double c = reflected ? 1.0 / (4 * std::abs(wi_m)) : sqr(eta_it) * std::abs(wi_m) / sqr(wo_m + eta_it * wi_m);
    s.pdf = pm * (reflected ? f.R : 1 - f.R) * c;
    if (!(s.pdf > 0)) return std::nullopt;
    if (!dispersive() || s.hero_only) {
        double w = distr.D(m) * distr.G(wo, s.wi, m) * std::abs(wo_m) / (std::abs(cos_o) * pm);
        if (!reflected && ctx.mode == TransportMode::Radiance) w /= sqr(eta_it);
        if (s.hero_only) {
            s.weight[0] = w * m_specular_transmittance.eval(ctx)[0];
        } else {
            s.weight = w * (reflected ? m_specular_reflectance : m_specular_transmittance).eval(ctx);
        }
        return s;
    }
    // A dispersive reflection: one direction for every wavelength, each with its own Fresnel
    // factor (and, through eta, its own half vector for refraction, which eval() handles).
    s.weight = eval(ctx, wo, s.wi);
    s.weight *= std::abs(s.wi.z) / s.pdf;
    return s;
}

}  // namespace snell
