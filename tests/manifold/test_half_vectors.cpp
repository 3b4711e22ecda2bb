// Alg. 1 line 3 (Sec. 3.2) per vertex slot: a chain's target half vectors depend on the shape
// sequence and the slots' uniform pairs alone, not on where on the shapes the seed landed, and
// slot i is always the (i+1)-th pair the sampler gives.
#include <gtest/gtest.h>

#include "bsdf/dielectric.h"
#include "bsdf/roughdielectric.h"
#include "manifold/chain_fixture.h"
#include "manifold/half_vectors.h"

using namespace snell;
using namespace snell::test;

namespace {

// Counts the pairs it hands out: pair j is (j + 0.25, j + 0.5) / 16.
class CountingSampler final : public Sampler {
public:
    void start_pixel_sample(int, int, uint64_t) override {}
    double next_1d() override { return 0.5; }
    Vec2 next_2d() override {
        const double j = double(pairs++);
        return {(j + 0.25) / 16, (j + 0.5) / 16};
    }
    std::unique_ptr<Sampler> clone() const override { return std::make_unique<CountingSampler>(*this); }
    int pairs = 0;
};

ManifoldVertex with_bsdf(ManifoldVertex v, const BSDF& bsdf) {
    v.bsdf = &bsdf;
    return v;
}

}  // namespace

TEST(HalfVectors, TargetsDependOnSlotsNotOnSeedPosition) {
    const Sphere sphere(Vec3(0, 0, 0), 1.0);
    const RoughDielectricBSDF rough(MicrofacetDistribution(MicrofacetDistribution::Type::Beckmann, 0.2),
                                    Spectrum::constant(1.5), Spectrum::constant(1.0));
    const DielectricBSDF smooth(Spectrum::constant(1.5), Spectrum::constant(1.0));
    // Two seeds of the chain (smooth, rough, rough) at different places on the sphere.
    std::vector<ManifoldVertex> a = {with_bsdf(vertex_on(sphere, Vec3(0.1, 0, -1), 1.5), smooth),
                                     with_bsdf(vertex_on(sphere, Vec3(0.3, 0.2, 1), 1.5), rough),
                                     with_bsdf(vertex_on(sphere, Vec3(-1, 0.1, 0), 1.5), rough)};
    std::vector<ManifoldVertex> b = {with_bsdf(vertex_on(sphere, Vec3(-0.4, 0.5, -1), 1.5), smooth),
                                     with_bsdf(vertex_on(sphere, Vec3(0.2, -0.6, 1), 1.5), rough),
                                     with_bsdf(vertex_on(sphere, Vec3(0.3, 1, 0.2), 1.5), rough)};
    CountingSampler sampler;
    HalfVectorDraws draws(sampler);
    set_half_vectors(a, draws);
    EXPECT_EQ(sampler.pairs, 3);  // slots 0..2, slot 0 drawn though its vertex is smooth
    set_half_vectors(b, draws);
    EXPECT_EQ(sampler.pairs, 3);  // the same pairs again
    EXPECT_EQ(a[0].h_target, Vec2(0, 0));
    for (size_t i = 1; i < 3; ++i) {
        EXPECT_EQ(a[i].h_target, b[i].h_target) << "slot " << i;
        // The target is the microfacet normal sampled from slot i's pair, read in (s, t, n).
        const Vec3 m = rough.microfacet()->sample_m(Vec2((i + 0.25) / 16, (i + 0.5) / 16));
        EXPECT_EQ(a[i].h_target, Vec2(m.x, m.y)) << "slot " << i;
    }
}
