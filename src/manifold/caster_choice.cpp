#include "manifold/caster_choice.h"

#include <algorithm>
#include <cmath>

#include "geometry/shape.h"
#include "manifold/seed_path.h"
#include "scene/scene.h"

namespace snell {

CasterChoice::CasterChoice(const Scene& scene, const Vec3& xb, double lambda, const Shape* only) {
    if (only) {
        m_first = only;
        return;
    }
    const std::vector<const Shape*>& all = scene.manifold_casters();
    const std::vector<BoundingSphere>& bounds = scene.manifold_caster_bounds();
    // The solid angle of caster i's bounding sphere seen from x_b, 4 pi from inside it.
    const auto solid_angle = [&](size_t i) {
        const double d2 = length_squared(bounds[i].center - xb), r2 = bounds[i].radius * bounds[i].radius;
        return d2 > r2 ? 2 * kPi * r2 / d2 / (1 + std::sqrt(1 - r2 / d2)) : 4 * kPi;
    };
    size_t first = 0;
    double total = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        if (!is_manifold_interface(all[i]->bsdf(), lambda)) continue;
        if (!m_first) {
            m_first = all[i];
            first = i;
            continue;
        }
        if (m_casters.empty()) {  // a second caster: the choice needs the list and the weights
            m_casters.push_back(m_first);
            m_cdf.push_back(solid_angle(first));
            total = m_cdf.back();
        }
        m_casters.push_back(all[i]);
        m_cdf.push_back(solid_angle(i));
        total += m_cdf.back();
    }
    if (m_casters.empty()) return;
    // The weights become the cumulative probabilities in place.
    const double n = double(m_casters.size());
    const bool by_angle = total > 0 && std::isfinite(total);
    double sum = 0;
    for (double& w : m_cdf) {
        sum += (1 - kSolidAngleShare) / n + (by_angle ? kSolidAngleShare * w / total : kSolidAngleShare / n);
        w = sum;
    }
    m_cdf.back() = 1;
}

const Shape& CasterChoice::pick(PCG32& rng) const {
    if (m_casters.empty()) return *m_first;
    const double u = rng.next_double();
    const size_t i = size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin());
    return *m_casters[std::min(i, m_casters.size() - 1)];
}

double CasterChoice::probability(size_t i) const {
    if (m_casters.empty()) return i == 0 && m_first ? 1.0 : 0.0;
    return m_cdf[i] - (i > 0 ? m_cdf[i - 1] : 0.0);
}

double CasterChoice::probability_of(const Shape& caster) const {
    for (size_t i = 0; i < size(); ++i)
        if (&(*this)[i] == &caster) return probability(i);
    return 0.0;
}

}  // namespace snell
