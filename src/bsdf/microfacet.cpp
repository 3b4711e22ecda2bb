#include "bsdf/microfacet.h"

#include <cassert>
#include <cmath>

namespace snell {

MicrofacetDistribution::MicrofacetDistribution(Type type, double alpha_u, double alpha_v, bool sample_visible)
    : m_type(type),
      // Very small roughness makes D overflow; Mitsuba clamps the same way.
      m_alpha_u(std::max(alpha_u, 1e-4)),
      m_alpha_v(std::max(alpha_v, 1e-4)),
      m_sample_visible(sample_visible) {}

double MicrofacetDistribution::D(const Vec3& m) const {
    if (m.z <= 0) return 0;
    const double z2 = m.z * m.z;
    const double xu = m.x / m_alpha_u, yv = m.y / m_alpha_v;
    const double slope2 = xu * xu + yv * yv;  // tan^2(theta_m) / alpha^2, times cos^2
    double d;
    if (m_type == Type::Beckmann) {
        d = std::exp(-slope2 / z2) / (kPi * m_alpha_u * m_alpha_v * z2 * z2);
    } else {
        d = 1.0 / (kPi * m_alpha_u * m_alpha_v * sqr(slope2 + z2));
    }
    // Guard the far tail against underflow turning into NaN in products.
    return std::isfinite(d) && d > 1e-300 ? d : 0.0;
}

double MicrofacetDistribution::projected_alpha(const Vec3& w) const {
    if (is_isotropic()) return m_alpha_u;
    const double r2 = w.x * w.x + w.y * w.y;
    if (r2 <= 0) return m_alpha_u;
    return std::sqrt((w.x * w.x * m_alpha_u * m_alpha_u + w.y * w.y * m_alpha_v * m_alpha_v) / r2);
}

double MicrofacetDistribution::lambda(const Vec3& w) const {
    const double z2 = w.z * w.z, s2 = std::max(0.0, 1 - z2);
    if (s2 <= 0) return 0;
    if (z2 <= 0) return kInfinity;
    const double alpha_tan = projected_alpha(w) * std::sqrt(s2 / z2);
    if (m_type == Type::Beckmann) {
        // Exact Beckmann Lambda; erfc avoids cancellation for large a.
        const double a = 1.0 / alpha_tan;
        return 0.5 * (-std::erfc(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
    }
    return 0.5 * (std::sqrt(1 + alpha_tan * alpha_tan) - 1);
}

double MicrofacetDistribution::G1(const Vec3& w, const Vec3& m) const {
    // chi+: the microfacet must face w on the same side as the macro surface does.
    if (dot(w, m) * w.z <= 0) return 0;
    return 1.0 / (1.0 + lambda(w));
}

double MicrofacetDistribution::G(const Vec3& wo, const Vec3& wi, const Vec3& m) const { return G1(wo, m) * G1(wi, m); }

Vec3 MicrofacetDistribution::sample_m(const Vec2& u) const {
    // Azimuth: uniform for isotropic; for anisotropy the stretched-ellipse azimuth, and the
    // effective alpha along it.
    double phi = 2 * kPi * u.y, alpha2;
    if (is_isotropic()) {
        alpha2 = m_alpha_u * m_alpha_u;
    } else {
        phi = std::atan2(m_alpha_v * std::sin(phi), m_alpha_u * std::cos(phi));
        const double c = std::cos(phi), s = std::sin(phi);
        alpha2 = 1.0 / (c * c / (m_alpha_u * m_alpha_u) + s * s / (m_alpha_v * m_alpha_v));
    }
    // Invert the marginal CDF of tan^2(theta_m).
    double tan2;
    if (m_type == Type::Beckmann)
        tan2 = -alpha2 * std::log1p(-u.x);
    else
        tan2 = alpha2 * u.x / (1 - u.x);
    const double cos_t = 1.0 / std::sqrt(1 + tan2);
    const double sin_t = safe_sqrt(1 - cos_t * cos_t);
    return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

double MicrofacetDistribution::pdf_m(const Vec3& m) const { return D(m) * std::max(0.0, m.z); }

Vec3 MicrofacetDistribution::sample_visible_m(const Vec3& wo, const Vec2& u) const {
    if (m_type != Type::GGX) return sample_m(u);
    // Heitz 2018, "Sampling the GGX distribution of visible normals": stretch to the
    // hemisphere configuration, sample the projected half disk, unstretch.
    const Vec3 vh = normalize(Vec3(m_alpha_u * wo.x, m_alpha_v * wo.y, wo.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0 ? Vec3(-vh.y, vh.x, 0) / std::sqrt(lensq) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(vh, t1);
    const double r = std::sqrt(u.x), phi = 2 * kPi * u.y;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1 + vh.z);
    p2 = (1 - s) * safe_sqrt(1 - p1 * p1) + s * p2;
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1 - p1 * p1 - p2 * p2);
    return normalize(Vec3(m_alpha_u * nh.x, m_alpha_v * nh.y, std::max(1e-12, nh.z)));
}

double MicrofacetDistribution::pdf_visible_m(const Vec3& wo, const Vec3& m) const {
    if (m_type != Type::GGX) return pdf_m(m);
    if (wo.z <= 0) return 0;
    return G1(wo, m) * std::max(0.0, dot(wo, m)) * D(m) / wo.z;
}

std::pair<Vec3, double> MicrofacetDistribution::sample(const Vec3& wo, const Vec2& u) const {
    if (m_sample_visible) {
        const Vec3 m = sample_visible_m(wo, u);
        return {m, pdf_visible_m(wo, m)};
    }
    const Vec3 m = sample_m(u);
    return {m, pdf_m(m)};
}

double MicrofacetDistribution::pdf(const Vec3& wo, const Vec3& m) const {
    return m_sample_visible ? pdf_visible_m(wo, m) : pdf_m(m);
}

}  // namespace snell
