#include "manifold/half_vectors.h"

#include <cassert>

#include "bsdf/bsdf.h"
#include "bsdf/microfacet.h"

namespace snell {

Vec2 HalfVectorDraws::slot(int i) {
    assert(i >= 0 && i < kMaxSlots);
    while (m_drawn <= i) m_u[size_t(m_drawn++)] = m_sampler->next_2d();
    return m_u[size_t(i)];
}

Vec2 target_half_vector(const ManifoldVertex& v, int i, HalfVectorDraws& draws) {
    const MicrofacetDistribution* d = v.bsdf->microfacet();
    if (!d) return Vec2(0, 0);
    const Vec3 m = d->sample_m(draws.slot(i));  // (s, t, n) components
    return Vec2(m.x, m.y);
}

void set_half_vectors(std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws) {
    for (size_t i = 0; i < chain.size(); ++i) chain[i].h_target = target_half_vector(chain[i], int(i), draws);
}

}  // namespace snell
