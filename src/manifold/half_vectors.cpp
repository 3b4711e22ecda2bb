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

void set_half_vectors(std::vector<ManifoldVertex>& chain, HalfVectorDraws& draws) {
    for (size_t i = 0; i < chain.size(); ++i) {
        ManifoldVertex& v = chain[i];
        const MicrofacetDistribution* d = v.bsdf->microfacet();
        if (!d) {
            v.h_target = Vec2(0, 0);
            continue;
        }
        const Vec3 m = d->sample_m(draws.slot(int(i)));  // (s, t, n) components
        v.h_target = Vec2(m.x, m.y);
    }
}

}  // namespace snell
