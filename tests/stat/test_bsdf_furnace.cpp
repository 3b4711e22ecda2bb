// White-furnace (energy conservation) and reciprocity tests of the BSDFs. Every threshold is
// either exact (lossless smooth models with unit weights) or a multiple of the Monte Carlo
// standard error estimated in the test.
#include <gtest/gtest.h>

#include <memory>

#include "bsdf/blend.h"
#include "bsdf/conductor.h"
#include "bsdf/conductor_data.h"
#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/fresnel.h"
#include "bsdf/microfacet.h"
#include "bsdf/null_bsdf.h"
#include "bsdf/plastic.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/roughplastic.h"
#include "bsdf/thindielectric.h"
#include "bsdf/twosided.h"
#include "core/rng.h"
#include "core/warp.h"

using namespace snell;

namespace {

using MD = MicrofacetDistribution;

Vec3 dir(double theta_deg, double phi_deg = 17) {
    const double t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct Estimate {
    double mean = 0, sigma = 0;  ///< mean and its standard error
};

Estimate finish(double sum, double sum2, size_t n) {
    const double mean = sum / n;
    const double var = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(var / (n - 1))};
}

/// Directional albedo by importance sampling: E[weight] (deltas included).
Estimate albedo_sampled(const BSDF& b, const BSDFContext& ctx, const Vec3& wo, size_t n, uint64_t seed) {
    PCG32 rng(seed, 1);
    double s = 0, s2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double uc = rng.next_double();
        const Vec2 u(rng.next_double(), rng.next_double());
        const auto r = b.sample(ctx, wo, uc, u);
        const double w = r ? r->weight[0] : 0.0;
        s += w;
        s2 += w * w;
    }
    return finish(s, s2, n);
}

/// Directional albedo of the non-delta part from eval() alone, by uniform sphere sampling:
/// an estimator independent of sample()/pdf().
Estimate albedo_uniform(const BSDF& b, const BSDFContext& ctx, const Vec3& wo, size_t n, uint64_t seed) {
    PCG32 rng(seed, 2);
    double s = 0, s2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const Vec3 wi = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
        const double v = b.eval(ctx, wo, wi)[0] * std::abs(wi.z) / warp::square_to_uniform_sphere_pdf();
        s += v;
        s2 += v * v;
    }
    return finish(s, s2, n);
}

BSDFContext importance_ctx() {
    BSDFContext ctx;
    ctx.wl = SampledWavelengths::single(550);
    ctx.mode = TransportMode::Importance;  // no 1/eta^2 radiance compression
    return ctx;
}

TEST(BsdfFurnace, WhiteDiffuseAndTwoSidedAreExactlyOne) {
    auto d = std::make_shared<DiffuseBSDF>(Spectrum::constant(1.0));
    TwoSidedBSDF two(d);
    const BSDFContext ctx;
    for (double th : {0.0, 45.0, 85.0}) {
        EXPECT_NEAR(albedo_sampled(*d, ctx, dir(th), 10000, 1).mean, 1.0, 1e-12);
        EXPECT_NEAR(albedo_sampled(two, ctx, dir(180 - th), 10000, 2).mean, 1.0, 1e-12);
        const Estimate u = albedo_uniform(*d, ctx, dir(th), 200000, 3);
        EXPECT_NEAR(u.mean, 1.0, 4 * u.sigma);
    }
    // Below the surface a one-sided diffuse BSDF reflects nothing.
    EXPECT_EQ(albedo_sampled(*d, ctx, dir(120), 1000, 4).mean, 0.0);
}

TEST(BsdfFurnace, SmoothDielectricIsLossless) {
    DielectricBSDF glass(Spectrum::constant(1.5), Spectrum::constant(1.0));
    ThinDielectricBSDF thin(Spectrum::constant(1.5), Spectrum::constant(1.0));
    ConductorBSDF mirror(std::nullopt);
    const BSDFContext imp = importance_ctx();
    for (double th : {0.0, 30.0, 60.0, 89.0, 120.0, 150.0, 179.0}) {
        // Every weight is exactly 1 in Importance mode (lobe chosen with probability F).
        EXPECT_NEAR(albedo_sampled(glass, imp, dir(th), 20000, 5).mean, 1.0, 1e-12) << th;
        EXPECT_NEAR(albedo_sampled(thin, imp, dir(th), 20000, 6).mean, 1.0, 1e-12) << th;
        if (th < 90) {
            EXPECT_NEAR(albedo_sampled(mirror, imp, dir(th), 100, 7).mean, 1.0, 1e-12);
        }
        // Radiance mode: transmitted radiance is scaled by 1/eta_it^2.
        BSDFContext rad;
        rad.wl = SampledWavelengths::single(550);
        const DielectricFresnel f = fresnel_dielectric(dir(th).z, 1.5);
        const Estimate e = albedo_sampled(glass, rad, dir(th), 200000, 8);
        const double expect = f.R + (1 - f.R) * sqr(f.eta_ti);
        EXPECT_NEAR(e.mean, expect, 4 * e.sigma + 1e-12) << th;
    }
}

TEST(BsdfFurnace, WhitePlasticConservesEnergyExactly) {
    // With a white base and no specular tint, the coating model is exactly energy
    // conserving: F + (1 - F) (1 - Fdr_ext) / (eta^2 (1 - Fdr_int)) = 1.
    PlasticBSDF p(Spectrum::constant(1.0), Spectrum::constant(1.0), 1.49, 1.0);
    const BSDFContext ctx;
    for (double th : {10.0, 50.0, 80.0}) {
        const Estimate e = albedo_sampled(p, ctx, dir(th), 200000, 9);
        EXPECT_NEAR(e.mean, 1.0, 4 * e.sigma) << th;
        EXPECT_GT(e.sigma, 0);
    }
    // A grey plastic reflects less than a white one.
    PlasticBSDF grey(Spectrum::constant(0.5), Spectrum::constant(1.0), 1.49, 1.0, true);
    const Estimate g = albedo_sampled(grey, ctx, dir(30), 100000, 10);
    EXPECT_LT(g.mean + 4 * g.sigma, 1.0);
}

// roughplastic: with a white base and no tint, it loses only what the single-scattering coating
// loses (Smith shadowing of its reflection, and of its transmission on the way in and out) and
// never gains energy; the albedo from eval() by uniform sampling equals the sampled one, and a
// grey base reflects less.
TEST(BsdfFurnace, WhiteRoughPlasticLosesOnlyShadowedEnergy) {
    const BSDFContext ctx;
    uint64_t seed = 300;
    for (auto t : {MD::Type::Beckmann, MD::Type::GGX})
        for (double a : {0.05, 0.3})
            for (double th : {10.0, 50.0, 80.0}) {
                RoughPlasticBSDF p(MD(t, a), Spectrum::constant(1.0), Spectrum::constant(1.0), 1.49, 1.0);
                const Estimate e = albedo_sampled(p, ctx, dir(th), 100000, ++seed);
                EXPECT_LE(e.mean, 1 + 3 * e.sigma) << "a=" << a << " th=" << th;
                EXPECT_GE(e.mean, 1 - 1.3 * a - 0.05) << "a=" << a << " th=" << th;
                if (a >= 0.3) {
                    const Estimate u = albedo_uniform(p, ctx, dir(th), 400000, ++seed);
                    EXPECT_NEAR(u.mean, e.mean, 4 * std::hypot(u.sigma, e.sigma)) << "a=" << a << " th=" << th;
                }
            }
    RoughPlasticBSDF grey(MD(MD::Type::GGX, 0.2), Spectrum::constant(0.5), Spectrum::constant(1.0), 1.49, 1.0, true);
    const Estimate g = albedo_sampled(grey, ctx, dir(30), 100000, 399);
    EXPECT_LT(g.mean + 4 * g.sigma, 0.8);
}

// The coating's tabulated transmittance is the transmission lobe's albedo, estimated here
// independently by sampling roughdielectric (energy, so importance transport: no 1/eta^2).
// Taking 1 - (specular albedo) instead made roughplastic 4-16 % brighter than Mitsuba 3's
// references at alpha 0.4-1 (docs/scene-format.md); this test fails on that mutation for a >= 0.3.
TEST(BsdfFurnace, RoughPlasticTransmittanceIsTheTransmissionLobesAlbedo) {
    BSDFContext ctx;
    ctx.mode = TransportMode::Importance;
    uint64_t seed = 500;
    for (double a : {0.05, 0.3, 1.0})
        for (double th : {0.0, 45.0, 75.0}) {
            const RoughPlasticBSDF p(MD(MD::Type::GGX, a), Spectrum::constant(1.0), Spectrum::constant(1.0), 1.5, 1.0);
            const RoughDielectricBSDF d(MD(MD::Type::GGX, a), Spectrum::constant(1.5), Spectrum::constant(1.0));
            PCG32 rng(++seed, 3);
            double s = 0, s2 = 0;
            const size_t n = 200000;
            for (size_t i = 0; i < n; ++i) {
                const auto r = d.sample(ctx, dir(th), rng.next_double(), {rng.next_double(), rng.next_double()});
                const double w = r && r->wi.z < 0 ? r->weight[0] : 0.0;
                s += w;
                s2 += w * w;
            }
            const Estimate T = finish(s, s2, n);
            EXPECT_NEAR(p.external_transmittance(std::cos(th * kPi / 180)), T.mean, 4 * T.sigma + 2e-3)
                << "alpha " << a << " theta " << th;
        }
}

// Its internal diffuse reflectance is Mitsuba 3's: twice the plain mean of R(mu) mu over 64
// uniformly spaced mu (endpoints weighted fully), with R the reflection lobe's albedo from inside,
// estimated here by sampling roughdielectric from below. The trapezoid rule (snell's earlier
// choice) is 1.5 % higher and fails: it rendered Mitsuba's roughplastic scenes 2-5 % too bright.
TEST(BsdfFurnace, RoughPlasticInternalReflectanceIsMitsubas) {
    BSDFContext ctx;
    ctx.mode = TransportMode::Importance;
    const double a = 0.05, eta = 1.49;
    const RoughPlasticBSDF p(MD(MD::Type::Beckmann, a), Spectrum::constant(0.5), Spectrum::constant(1.0), eta, 1.0);
    const RoughDielectricBSDF d(MD(MD::Type::Beckmann, a), Spectrum::constant(eta), Spectrum::constant(1.0));
    PCG32 rng(77, 5);
    const int points = 64;
    const size_t n = 20000;
    double mean = 0, var = 0;
    for (int i = 0; i < points; ++i) {
        const double mu = std::max(1e-6, double(i) / (points - 1));
        const Vec3 wo(std::sqrt(1 - mu * mu), 0, -mu);  // from inside
        double s = 0, s2 = 0;
        for (size_t k = 0; k < n; ++k) {
            const auto r = d.sample(ctx, wo, rng.next_double(), {rng.next_double(), rng.next_double()});
            const double w = r && r->wi.z < 0 ? r->weight[0] : 0.0;
            s += w;
            s2 += w * w;
        }
        const Estimate R = finish(s, s2, n);
        mean += 2 * R.mean * mu / points;
        var += sqr(2 * R.sigma * mu / points);
    }
    EXPECT_NEAR(p.internal_reflectance(), mean, 4 * std::sqrt(var) + 1e-3) << "sigma " << std::sqrt(var);
}

// null passes everything; a mask of a white diffuse BSDF reflects its opacity and passes the
// rest; a blend of two white BSDFs is white.
TEST(BsdfFurnace, NullMaskAndBlendConserveEnergy) {
    const BSDFContext ctx;
    auto white = std::make_shared<DiffuseBSDF>(Spectrum::constant(1.0));
    const NullBSDF null;
    EXPECT_NEAR(albedo_sampled(null, ctx, dir(30), 1000, 1).mean, 1.0, 1e-12);
    const BlendBSDF mask(0.3, std::make_shared<NullBSDF>(), white);
    const Estimate m = albedo_sampled(mask, ctx, dir(40), 100000, 2);
    EXPECT_NEAR(m.mean, 1.0, 4 * m.sigma + 1e-9);
    const BlendBSDF grey_mask(0.3, std::make_shared<NullBSDF>(),
                              std::make_shared<DiffuseBSDF>(Spectrum::constant(0.5)));
    const Estimate g = albedo_sampled(grey_mask, ctx, dir(40), 100000, 3);
    EXPECT_NEAR(g.mean, 0.7 + 0.3 * 0.5, 4 * g.sigma);
    const BlendBSDF blend(0.6, white,
                          std::make_shared<PlasticBSDF>(Spectrum::constant(1.0), Spectrum::constant(1.0), 1.49, 1.0));
    const Estimate b = albedo_sampled(blend, ctx, dir(60), 100000, 4);
    EXPECT_NEAR(b.mean, 1.0, 4 * b.sigma);
}

struct RoughCase {
    MD::Type type;
    double alpha;
    double theta;
};

TEST(BsdfFurnace, RoughModelsLoseOnlyShadowedEnergy) {
    // Single-scattering microfacet models lose the energy of inter-reflections between
    // microfacets; the loss grows with roughness (Heitz et al. 2016 measure up to ~20% for
    // alpha = 0.5 at moderate angles and far less for alpha <= 0.2). The lower bounds below
    // allow twice that. The upper bound is energy conservation, with 3 standard errors.
    const BSDFContext imp = importance_ctx();
    const size_t n = 100000;
    uint64_t seed = 100;
    for (auto t : {MD::Type::Beckmann, MD::Type::GGX})
        for (double a : {0.05, 0.2, 0.5})
            for (double th : {20.0, 60.0, 150.0}) {
                const MD distr(t, a);
                const double lower = 1 - 0.8 * a;
                RoughDielectricBSDF rd(distr, Spectrum::constant(1.5), Spectrum::constant(1.0));
                const Estimate e = albedo_sampled(rd, imp, dir(th), n, ++seed);
                EXPECT_LE(e.mean, 1 + 3 * e.sigma) << "roughdielectric a=" << a << " th=" << th;
                EXPECT_GE(e.mean, lower) << "roughdielectric a=" << a << " th=" << th;
                if (th < 90) {
                    RoughConductorBSDF rc(distr, std::nullopt);
                    const Estimate c = albedo_sampled(rc, imp, dir(th), n, ++seed);
                    EXPECT_LE(c.mean, 1 + 3 * c.sigma) << "roughconductor a=" << a << " th=" << th;
                    EXPECT_GE(c.mean, lower) << "roughconductor a=" << a << " th=" << th;
                }
                // The same albedo from eval() alone (independent of the sampler), where the
                // lobe is wide enough for uniform sampling to have a usable variance.
                if (a >= 0.2) {
                    const Estimate u = albedo_uniform(rd, imp, dir(th), 400000, ++seed);
                    EXPECT_NEAR(u.mean, e.mean, 4 * std::hypot(u.sigma, e.sigma))
                        << "roughdielectric sampled vs uniform a=" << a << " th=" << th;
                }
            }
}

TEST(BsdfReciprocity, ReflectionIsSymmetric) {
    auto au = named_conductor("Au");
    std::vector<std::pair<std::string, std::shared_ptr<BSDF>>> bsdfs = {
        {"diffuse", std::make_shared<DiffuseBSDF>(Spectrum::constant(0.8))},
        {"roughconductor", std::make_shared<RoughConductorBSDF>(MD(MD::Type::GGX, 0.1, 0.4), au)},
        {"roughconductor_beckmann", std::make_shared<RoughConductorBSDF>(MD(MD::Type::Beckmann, 0.3), au)},
        {"plastic", std::make_shared<PlasticBSDF>(Spectrum::constant(0.6), Spectrum::constant(1.0), 1.5, 1.0)},
        {"roughplastic", std::make_shared<RoughPlasticBSDF>(MD(MD::Type::GGX, 0.3), Spectrum::constant(0.6),
                                                            Spectrum::constant(1.0), 1.5, 1.0)},
        {"roughdielectric", std::make_shared<RoughDielectricBSDF>(MD(MD::Type::GGX, 0.3), Spectrum::constant(1.5),
                                                                  Spectrum::constant(1.0))},
        {"twosided", std::make_shared<TwoSidedBSDF>(
                         std::make_shared<PlasticBSDF>(Spectrum::constant(0.6), Spectrum::constant(1.0), 1.5, 1.0))},
    };
    PCG32 rng(11, 3);
    BSDFContext ctx;
    for (auto& [name, b] : bsdfs)
        for (int i = 0; i < 2000; ++i) {
            Vec3 wo = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
            Vec3 wi = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
            if (wo.z * wi.z < 0) wi.z = -wi.z;  // reflection pairs, both sides
            const double a = b->eval(ctx, wo, wi)[0], c = b->eval(ctx, wi, wo)[0];
            ASSERT_NEAR(a, c, 1e-10 * std::max(a, c)) << name;
        }
}

TEST(BsdfReciprocity, TransmissionObeysGeneralisedReciprocity) {
    // Radiance-mode BTDF: f(wi, wo) = eta_it^2 f(wo, wi) with eta_it = n(wi side) / n(wo side);
    // and the Importance-mode BSDF is the adjoint: f_imp(wo, wi) = f_rad(wi, wo).
    for (auto t : {MD::Type::Beckmann, MD::Type::GGX}) {
        RoughDielectricBSDF b(MD(t, 0.4), Spectrum::from_ior_abbe(1.5, 40), Spectrum::constant(1.0));
        PCG32 rng(12, 4);
        BSDFContext rad, imp;
        rad.wl = imp.wl = SampledWavelengths::single(480);
        imp.mode = TransportMode::Importance;
        const double eta = b.eta(480);
        int nonzero = 0;
        for (int i = 0; i < 2000; ++i) {
            const Vec3 wo = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
            Vec3 wi = warp::square_to_uniform_sphere({rng.next_double(), rng.next_double()});
            if (wo.z * wi.z > 0) wi.z = -wi.z;
            const double eta_it = wo.z > 0 ? eta : 1 / eta;
            const double f = b.eval(rad, wo, wi)[0], g = b.eval(rad, wi, wo)[0];
            ASSERT_NEAR(g, sqr(eta_it) * f, 1e-10 * std::max(g, 1e-300));
            ASSERT_NEAR(b.eval(imp, wo, wi)[0], g, 1e-10 * std::max(g, 1e-300));
            nonzero += f > 0;
        }
        EXPECT_GT(nonzero, 200);  // the test saw actual transmission (about 20% of pairs)
    }
}

}  // namespace
