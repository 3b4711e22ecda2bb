#include "manifold/caster_choice.h"

#include <algorithm>
#include <cmath>

#include "geometry/shape.h"
#include "manifold/seed_path.h"
#include "scene/scene.h"

namespace snell {

CasterChoice::CasterChoice(const Scene& scene, const Vec3& xb, double lambda, const Shape* only) {
    if (only) {
        m_casters.push_back(only);
        return;
    }
    const std::vector<const Shape*>& all = scene.manifold_casters();
    const std::vector<BoundingSphere>& bounds = scene.manifold_caster_bounds();
    std::vector<double> omega;
    double total = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        if (!is_manifold_interface(all[i]->bsdf(), lambda)) continue;
        m_casters.push_back(all[i]);
        // The solid angle of the bounding sphere seen from x_b, 4 pi from inside it.
        const double d2 = length_squared(bounds[i].center - xb), r2 = bounds[i].radius * bounds[i].radius;
        const double w = d2 > r2 ? 2 * kPi * r2 / d2 / (1 + std::sqrt(1 - r2 / d2)) : 4 * kPi;
        omega.push_back(w);
        total += w;
    }
    if (m_casters.size() < 2) return;
    const double n = double(m_casters.size());
    const bool by_angle = total > 0 && std::isfinite(total);
    double sum = 0;
    for (const double w : omega) {
        sum += (1 - kSolidAngleShare) / n + (by_angle ? kSolidAngleShare * w / total : kSolidAngleShare / n);
        m_cdf.push_back(sum);
    }
    m_cdf.back() = 1;
}

CasterChoice::CasterChoice(const Shape& caster) : m_casters{&caster} {}

const Shape& CasterChoice::pick(PCG32& rng) const {
    if (m_cdf.empty()) return *m_casters.front();
    const double u = rng.next_double();
    const size_t i = size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin());
    return *m_casters[std::min(i, m_casters.size() - 1)];
}

double CasterChoice::probability(size_t i) const {
    if (m_cdf.empty()) return i == 0 && !m_casters.empty() ? 1.0 : 0.0;
    return m_cdf[i] - (i > 0 ? m_cdf[i - 1] : 0.0);
}

}  // namespace snell
