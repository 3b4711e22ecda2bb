// Alg. 1 line 3 (Sec. 3.2) per vertex slot: a chain's target half vectors depend on the shape
// sequence and the slots' uniform pairs alone, not on where on the shapes the seed landed, and
// slot i is always the (i+1)-th pair the sampler gives.
#include <gtest/gtest.h>

#include "bsdf/dielectric.h"
#include "bsdf/roughdielectric.h"
#include "manifold/chain_fixture.h"
#include "manifold/half_vectors.h"
#include "texture/checkerboard.h"
#include "texture/constant.h"

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
        const Vec3 m = rough.microfacet(BSDFContext{})->sample_m(Vec2((i + 0.25) / 16, (i + 0.5) / 16));
        EXPECT_NEAR(a[i].h_target.x, m.x, 1e-12) << "slot " << i;
        EXPECT_NEAR(a[i].h_target.y, m.y, 1e-12) << "slot " << i;
    }
}

// Roughness textures (issue 11): the target is the unit-roughness slope stretched by the alpha
// where the vertex lies. Anisotropic stretching is sample_m itself (stretch invariance), the
// inverse recovers the slope, and a vertex moved to a cell of other roughness gets that cell's
// target from the same draw.
TEST(HalfVectors, UnitSlopeStretchesWithTheRoughnessWhereTheVertexLies) {
    using MD = MicrofacetDistribution;
    const Sphere sphere(Vec3(0, 0, 0), 1.0);
    for (MD::Type type : {MD::Type::Beckmann, MD::Type::GGX}) {
        const RoughDielectricBSDF aniso(MD(type, 0.3, 0.08), Spectrum::constant(1.5), Spectrum::constant(1.0));
        ManifoldVertex v = with_bsdf(vertex_on(sphere, Vec3(0.3, 0.2, 1), 1.5), aniso);
        CountingSampler sampler;
        HalfVectorDraws draws(sampler);
        for (int i = 0; i < 8; ++i) {
            const Vec2 h = target_half_vector(v, i, draws);
            const Vec3 m = MD(type, 0.3, 0.08).sample_m(Vec2((i + 0.25) / 16, (i + 0.5) / 16));
            EXPECT_NEAR(h.x, m.x, 1e-12);
            EXPECT_NEAR(h.y, m.y, 1e-12);
            const Vec2 back = unit_slope_of(v, h);
            EXPECT_NEAR(back.x, v.unit_slope.x, 1e-9 * (1 + std::abs(back.x)));
            EXPECT_NEAR(back.y, v.unit_slope.y, 1e-9 * (1 + std::abs(back.y)));
        }
    }
    // A checkerboard of alpha 0.05 / 0.4 over the sphere's uv: the same unit slope gives targets
    // eight times apart in slope on the two cells.
    auto checks = std::make_shared<CheckerboardTexture>(ConstantTexture::make(0.05), ConstantTexture::make(0.4),
                                                        Transform::scale(Vec3(8, 8, 1)));
    const RoughDielectricBSDF textured(MicrofacetParam(MD(MD::Type::Beckmann, 0.1), checks, checks),
                                       Spectrum::constant(1.5), Spectrum::constant(1.0));
    const Vec2 slope(0.7, -0.3);
    double slopes[2] = {0, 0};
    int seen = 0;
    for (int k = 0; k < 64 && seen != 3; ++k) {
        const double phi = 2 * kPi * (k + 0.5) / 64;
        const ManifoldVertex w = with_bsdf(vertex_on(sphere, Vec3(std::cos(phi), std::sin(phi), 0.2), 1.5), textured);
        const Vec2 h = target_from_unit_slope(w, slope);
        const double cos_m = std::sqrt(1 - h.x * h.x - h.y * h.y);
        const bool first = checks->first_at(w.si.uv);
        slopes[first ? 0 : 1] = h.x / cos_m / slope.x;  // the stretch, i.e. alpha
        seen |= first ? 1 : 2;
    }
    ASSERT_EQ(seen, 3);
    EXPECT_NEAR(slopes[0], 0.05, 1e-12);
    EXPECT_NEAR(slopes[1], 0.4, 1e-12);
}
