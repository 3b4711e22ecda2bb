#include "manifold/half_vectors.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"

namespace snell {

HalfVectorDraws HalfVectorDraws::of_unit_slopes(std::vector<Vec2> slopes) {
    HalfVectorDraws d;
    d.m_slopes = std::move(slopes);
    return d;
}

HalfVectorDraws HalfVectorDraws::of_pairs(std::initializer_list<Vec2> pairs) {
    assert(pairs.size() <= size_t(kMaxSlots));
    HalfVectorDraws d;
    d.m_given_pairs = true;
    for (const Vec2& u : pairs) d.m_u[size_t(d.m_drawn++)] = u;
    return d;
}

Vec2 HalfVectorDraws::unit_slope(int i, int type) {
    if (!m_sampler && !m_given_pairs) return size_t(i) < m_slopes.size() ? m_slopes[size_t(i)] : Vec2(0, 0);
    const Vec3 m = MicrofacetDistribution(MicrofacetDistribution::Type(type), 1.0, 1.0).sample_m(slot(i));
    return Vec2(m.x / m.z, m.y / m.z);
}

Vec2 HalfVectorDraws::slot(int i) {
    assert(i >= 0 && i < kMaxSlots && (m_sampler || (m_given_pairs && i < m_drawn)));
    while (m_drawn <= i) m_u[size_t(m_drawn++)] = m_sampler->next_2d();
    return m_u[size_t(i)];
}

namespace {
std::pair<double, double> alphas_at(const ManifoldVertex& v) {
    const auto d = v.bsdf->microfacet(BSDFContext{}.at(v.si));
    return {d->alpha_u(), d->alpha_v()};
}
}  // namespace

Vec2 target_from_unit_slope(const ManifoldVertex& v, const Vec2& unit_slope) {
    const auto [au, av] = alphas_at(v);
    const Vec3 m = normalize(Vec3(au * unit_slope.x, av * unit_slope.y, 1.0));  // (s, t, n) components
    return Vec2(m.x, m.y);
}

Vec2 unit_slope_of(const ManifoldVertex& v, const Vec2& h) {
    const auto [au, av] = alphas_at(v);
    const double cos_m = std::sqrt(std::max(0.0, 1 - h.x * h.x - h.y * h.y));
    if (!(cos_m > 0)) return Vec2(kInfinity, kInfinity);
    return Vec2(h.x / (cos_m * au), h.y / (cos_m * av));
}

Vec2 target_half_vector(ManifoldVertex& v, int i, HalfVectorDraws& draws) {
    const auto d = v.bsdf->microfacet(BSDFContext{}.at(v.si));
    if (!d) return Vec2(0, 0);
    v.unit_slope = draws.unit_slope(i, int(d->type()));
    v.has_unit_slope = true;
    return target_from_unit_slope(v, v.unit_slope);
}

void set_half_vectors(std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws) {
    for (size_t i = 0; i < chain.size(); ++i) chain[i].h_target = target_half_vector(chain[i], int(i), draws);
}

}  // namespace snell
