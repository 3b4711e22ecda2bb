// Closed-form checks of Fresnel, microfacet identities, per-model flags/eta and the factory.
#include <gtest/gtest.h>

#include <memory>

#include "bsdf/conductor.h"
#include "bsdf/conductor_data.h"
#include "bsdf/conductor_table.h"
#include "bsdf/dielectric.h"
#include "bsdf/diffuse.h"
#include "bsdf/factory.h"
#include "bsdf/fresnel.h"
#include "bsdf/microfacet.h"
#include "bsdf/normalmap.h"
#include "bsdf/plastic.h"
#include "bsdf/principled.h"
#include "bsdf/principledthin.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/thindielectric.h"
#include "bsdf/twosided.h"
#include "core/frame.h"
#include "core/rng.h"
#include "stat/chi2.h"
#include "texture/constant.h"

using namespace snell;
using MD = MicrofacetDistribution;

namespace {

Vec3 dir(double theta_deg, double phi_deg = 17) {
    const double t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

/// Integral over the upper hemisphere of f(w) dw (dw = dz dphi), adaptive quadrature.
template <typename F>
double hemisphere_integral(const F& f) {
    auto inner = [&](double z) {
        const double s = safe_sqrt(1 - z * z);
        return snell::test::adaptive_simpson(
            [&](double phi) { return f(Vec3(s * std::cos(phi), s * std::sin(phi), z)); }, 0, 2 * kPi, 1e-10, 16);
    };
    return snell::test::adaptive_simpson(inner, 0, 1, 1e-9, 32);
}

TEST(Fresnel, NormalIncidenceClosedForm) {
    for (double eta : {1.2, 1.5, 2.4}) {
        const double R0 = sqr((eta - 1) / (eta + 1));
        EXPECT_NEAR(fresnel_dielectric(1.0, eta).R, R0, 1e-14);
        EXPECT_NEAR(fresnel_dielectric(-1.0, eta).R, R0, 1e-14);  // from inside: same
        EXPECT_NEAR(fresnel_conductor(1.0, eta, 0.0), R0, 1e-14);
        const double k = 3.1;
        EXPECT_NEAR(fresnel_conductor(1.0, eta, k), (sqr(eta - 1) + k * k) / (sqr(eta + 1) + k * k), 1e-14);
    }
    // Conductor with k = 0 equals the dielectric at all angles.
    for (double c : {0.1, 0.5, 0.9}) EXPECT_NEAR(fresnel_conductor(c, 1.5, 0), fresnel_dielectric(c, 1.5).R, 1e-12);
    EXPECT_NEAR(fresnel_dielectric(1e-9, 1.5).R, 1.0, 1e-6);  // grazing
    EXPECT_EQ(fresnel_dielectric(0.5, 1.0).R, 0.0);           // index matched
}

TEST(Fresnel, TotalInternalReflectionAndSnell) {
    const double eta = 1.5, cos_crit = std::sqrt(1 - 1 / (eta * eta));
    // Inside (cos < 0): beyond the critical angle everything reflects.
    EXPECT_EQ(fresnel_dielectric(-(cos_crit - 1e-6), eta).R, 1.0);
    EXPECT_LT(fresnel_dielectric(-(cos_crit + 1e-3), eta).R, 1.0);
    for (double th : {10.0, 35.0, 70.0}) {
        const Vec3 wo = dir(th);
        const DielectricFresnel f = fresnel_dielectric(wo.z, eta);
        EXPECT_LT(f.cos_t, 0);
        EXPECT_DOUBLE_EQ(f.eta_it, eta);
        const Vec3 wt = refract(wo, f.cos_t, f.eta_ti);
        EXPECT_NEAR(length(wt), 1.0, 1e-12);
        EXPECT_NEAR(std::sqrt(sin2_theta(wo)), eta * std::sqrt(sin2_theta(wt)), 1e-12);  // Snell
        // Through a tilted microfacet: Snell's law w.r.t. m.
        const Vec3 m = normalize(Vec3(0.2, -0.1, 1));
        const DielectricFresnel fm = fresnel_dielectric(dot(wo, m), eta);
        const Vec3 wm = refract(wo, m, fm.cos_t, fm.eta_ti);
        EXPECT_NEAR(length(wm), 1.0, 1e-12);
        EXPECT_NEAR(length(cross(wo, m)), eta * length(cross(wm, m)), 1e-12);
        // Reversibility: refracting back gives wo.
        const DielectricFresnel fb = fresnel_dielectric(dot(wm, m), eta);
        const Vec3 back = refract(wm, m, fb.cos_t, fb.eta_ti);
        EXPECT_NEAR(length(back - wo), 0.0, 1e-12);
    }
}

TEST(Fresnel, DiffuseReflectanceReciprocity) {
    // Hemispherical transmittances on the two sides relate by eta^2 (reciprocity):
    // 1 - Fdr(eta) = eta^2 (1 - Fdr(1 / eta)).
    for (double eta : {1.33, 1.5, 2.0}) {
        EXPECT_NEAR(1 - fresnel_diffuse_reflectance(eta), eta * eta * (1 - fresnel_diffuse_reflectance(1 / eta)), 1e-8);
    }
    EXPECT_NEAR(fresnel_diffuse_reflectance(1.0), 0.0, 1e-14);
    EXPECT_NEAR(fresnel_diffuse_reflectance(1.5), 0.0918, 2e-3);  // textbook value ~0.092
}

TEST(Conductors, NamedDataIsMeasured) {
    for (const char* n : {"Au", "Ag", "Cu", "Al", "a-C", "W", "Cr", "TiN", "Na_palik"})
        ASSERT_TRUE(named_conductor(n)) << n;
    EXPECT_FALSE(named_conductor("unobtainium"));
    // Every material of the generated table: ascending wavelengths from the near UV (a few end
    // early, AlSb at 590 nm: the last value holds beyond), non-negative eta and k, one value per
    // wavelength.
    EXPECT_GE(conductor_table().size(), 70u);
    for (const ConductorTableEntry& e : conductor_table()) {
        for (const auto* l : {&e.eta_lambda, &e.k_lambda}) {
            ASSERT_GE(l->size(), 2u) << e.name;
            EXPECT_LE(l->front(), 360.0) << e.name;
            EXPECT_GE(l->back(), 590.0) << e.name;
            for (size_t i = 1; i < l->size(); ++i) EXPECT_LT((*l)[i - 1], (*l)[i]) << e.name;
        }
        ASSERT_EQ(e.eta.size(), e.eta_lambda.size()) << e.name;
        ASSERT_EQ(e.k.size(), e.k_lambda.size()) << e.name;
        for (double v : e.eta) EXPECT_GE(v, 0) << e.name;  // AlAs has gaps written as 0
        for (double v : e.k) EXPECT_GE(v, 0) << e.name;
    }
    // Amorphous carbon (a-C) at 516.58 nm, as tabulated: eta 2.30.
    EXPECT_NEAR(named_conductor("a-C")->eta(516.583008), 2.30, 1e-9);
    auto au = *named_conductor("Au");
    // A tabulated point (Palik): Au at 619.92 nm has eta 0.194, k 3.06.
    EXPECT_NEAR(au.eta(619.920898), 0.194, 1e-9);
    EXPECT_NEAR(au.k(619.920898), 3.06, 1e-9);
    // Gold is yellow: reflects red much better than blue.
    auto R = [](const ConductorIOR& c, double l) { return fresnel_conductor(1.0, c.eta(l), c.k(l)); };
    EXPECT_GT(R(au, 650), R(au, 450) + 0.3);
    EXPECT_GT(R(*named_conductor("Ag"), 550), 0.9);
    EXPECT_GT(R(*named_conductor("Al"), 550), 0.85);
    auto cu = *named_conductor("Cu");
    EXPECT_GT(R(cu, 650), R(cu, 450) + 0.3);
    ConductorBSDF mirror(std::nullopt), gold(au);
    EXPECT_DOUBLE_EQ(mirror.reflectance(BSDFContext{SampledWavelengths::single(500)}, 0.3)[0], 1.0);
    EXPECT_NEAR(gold.reflectance(BSDFContext{SampledWavelengths::single(650)}, 1.0)[0], R(au, 650), 1e-14);
}

TEST(Microfacet, NormalisationAndSmithIdentity) {
    for (auto t : {MD::Type::Beckmann, MD::Type::GGX})
        for (auto [au, av] : {std::pair{0.1, 0.1}, std::pair{0.5, 0.5}, std::pair{0.15, 0.45}}) {
            const MD d(t, au, av);
            // Projected microfacet area equals the macro area: integral D cos = 1.
            EXPECT_NEAR(hemisphere_integral([&](const Vec3& m) { return d.D(m) * m.z; }), 1.0, 2e-4);
            // Smith: projected visible microfacet area equals the projected macro area,
            // integral G1(wo, m) max(0, wo.m) D(m) dm = cos(theta_o). Validates Lambda.
            for (double th : {0.0, 40.0, 75.0}) {
                const Vec3 wo = dir(th, 30);
                const double proj = hemisphere_integral(
                    [&](const Vec3& m) { return d.G1(wo, m) * std::max(0.0, dot(wo, m)) * d.D(m); });
                EXPECT_NEAR(proj, wo.z, 2e-4 * std::max(1.0, 1 / wo.z)) << int(t) << " " << au << " " << th;
            }
            EXPECT_EQ(d.D(Vec3(0, 0, -1)), 0.0);
            EXPECT_EQ(d.G1(dir(30), Vec3(0, 0, 1)), d.G1(dir(30), normalize(Vec3(0.1, 0, 1))));
            EXPECT_EQ(d.G1(dir(80, 0), normalize(Vec3(-5, 0, 1))), 0.0);  // back-facing
        }
    // Visible-normal density is normalised too (GGX exact; Beckmann falls back to global).
    const MD g(MD::Type::GGX, 0.3);
    EXPECT_TRUE(g.has_exact_visible());
    EXPECT_NEAR(hemisphere_integral([&](const Vec3& m) { return g.pdf_visible_m(dir(60), m); }), 1.0, 2e-4);
    EXPECT_DOUBLE_EQ(g.pdf_m(dir(20)), g.D(dir(20)) * dir(20).z);
}

TEST(Bsdfs, FlagsAndEta) {
    const auto one = Spectrum::constant(1.0);
    DiffuseBSDF diffuse(one);
    DielectricBSDF glass(Spectrum::from_ior_abbe(1.5, 40), Spectrum::constant(1.000277));
    ThinDielectricBSDF thin(Spectrum::constant(1.5), one);
    RoughDielectricBSDF rough(MD(MD::Type::GGX, 0.2), Spectrum::constant(1.33), one, one, one, Spectrum::constant(0.1));
    ConductorBSDF mirror(std::nullopt);
    RoughConductorBSDF rc(MD(MD::Type::Beckmann, 0.2), named_conductor("Cu"));
    PlasticBSDF plastic(one, one, 1.49, 1.0);
    TwoSidedBSDF two(std::make_shared<DiffuseBSDF>(one), std::make_shared<ConductorBSDF>(std::nullopt));

    EXPECT_EQ(diffuse.flags(), kReflection | kDiffuse);
    EXPECT_EQ(glass.flags(), kReflection | kTransmission | kSpecular);
    EXPECT_EQ(thin.flags(), kReflection | kTransmission | kSpecular);
    EXPECT_EQ(rough.flags(), kReflection | kTransmission | kGlossy);
    EXPECT_EQ(mirror.flags(), kReflection | kSpecular);
    EXPECT_EQ(rc.flags(), kReflection | kGlossy);
    EXPECT_EQ(plastic.flags(), kReflection | kSpecular | kDiffuse);
    EXPECT_EQ(two.flags(), kReflection | kDiffuse | kSpecular);
    EXPECT_TRUE(glass.has_delta() && glass.is_transmissive() && !glass.is_smooth_sampled());
    EXPECT_TRUE(plastic.has_delta() && plastic.is_smooth_sampled());

    // Dispersion: normal dispersion (Cauchy) with Abbe number 40.
    EXPECT_GT(glass.eta(400), glass.eta(700));
    EXPECT_NEAR(glass.eta(587.56), 1.5 / 1.000277, 1e-12);
    EXPECT_DOUBLE_EQ(rough.eta(500), 1.33);
    EXPECT_EQ(thin.eta(500), 1.0);
    EXPECT_EQ(rc.eta(500), 1.0);
    EXPECT_EQ(glass.interior_absorption(), nullptr);
    ASSERT_NE(rough.interior_absorption(), nullptr);
    EXPECT_DOUBLE_EQ(rough.interior_absorption()->eval(500), 0.1);
}

TEST(Bsdfs, SmoothDielectricSampling) {
    DielectricBSDF glass(Spectrum::constant(1.5), Spectrum::constant(1.0));
    BSDFContext ctx;
    const double R0 = 0.04;
    // uc below F reflects, above refracts.
    auto r = glass.sample(ctx, Vec3(0, 0, 1), 0.5 * R0, {0.5, 0.5});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->lobe, uint32_t(kReflection | kSpecular));
    EXPECT_NEAR(r->pdf, R0, 1e-12);
    EXPECT_EQ(r->wi, Vec3(0, 0, 1));
    auto t = glass.sample(ctx, Vec3(0, 0, 1), 0.5, {0.5, 0.5});
    ASSERT_TRUE(t);
    EXPECT_EQ(t->lobe, uint32_t(kTransmission | kSpecular));
    EXPECT_NEAR(t->wi.z, -1, 1e-15);
    EXPECT_NEAR(t->weight[0], 1 / 2.25, 1e-12);  // radiance compressed entering the glass
    EXPECT_DOUBLE_EQ(t->eta, 1.5);
    // Leaving the glass: radiance expands by eta^2; importance mode: no scaling.
    auto out = glass.sample(ctx, Vec3(0, 0, -1), 0.5, {0.5, 0.5});
    EXPECT_NEAR(out->weight[0], 2.25, 1e-12);
    EXPECT_NEAR(out->eta, 1 / 1.5, 1e-15);
    ctx.mode = TransportMode::Importance;
    EXPECT_NEAR(glass.sample(ctx, Vec3(0, 0, -1), 0.5, {0.5, 0.5})->weight[0], 1.0, 1e-15);
    // Total internal reflection from inside beyond 41.8 degrees: always reflects.
    auto tir = glass.sample(ctx, dir(180 - 50), 0.999, {0.5, 0.5});
    EXPECT_EQ(tir->lobe, uint32_t(kReflection | kSpecular));
    EXPECT_TRUE(glass.eval(ctx, dir(10), dir(170)).is_zero());
    EXPECT_EQ(glass.pdf(ctx, dir(10), reflect(dir(10))), 0.0);
}

// --- factory -------------------------------------------------------------------------------

Props make(const std::string& type) { return Props("bsdf", type, SourceLoc{"test.xml", 3}); }
const SourceLoc kLoc{"test.xml", 4};

TEST(BsdfFactory, BuildsEveryTypeWithMitsubaParameters) {
    {
        Props p = make("roughdielectric");
        p.set("distribution", std::string("ggx"), kLoc);
        p.set("alpha", 0.3, kLoc);
        p.set("int_ior", std::string("water"), kLoc);
        p.set("abbe", 55.0, kLoc);
        p.set("sigma_a", 0.5, kLoc);
        auto b = create_bsdf(p);
        auto* rd = dynamic_cast<RoughDielectricBSDF*>(b.get());
        ASSERT_NE(rd, nullptr);
        EXPECT_NEAR(rd->eta(587.56), 1.333 / 1.00028, 1e-9);
        EXPECT_GT(rd->eta(400), rd->eta(700));
        EXPECT_EQ(rd->distribution().type(), MD::Type::GGX);
        ASSERT_NE(rd->interior_absorption(), nullptr);
    }
    {
        Props p = make("roughconductor");
        p.set("alpha_u", 0.1, kLoc);
        p.set("alpha_v", 0.3, kLoc);
        p.set("material", std::string("Au"), kLoc);
        const auto bsdf = create_bsdf(p);  // alive while rc is used
        auto* rc = dynamic_cast<RoughConductorBSDF*>(bsdf.get());
        ASSERT_NE(rc, nullptr);
        EXPECT_DOUBLE_EQ(rc->distribution().alpha_v(), 0.3);
    }
    for (const char* t : {"diffuse", "dielectric", "thindielectric", "conductor", "plastic"}) {
        EXPECT_NE(create_bsdf(make(t)), nullptr) << t;
    }
    {
        Props p = make("twosided");
        p.add_child("", std::make_shared<DiffuseBSDF>(Spectrum::constant(0.5)), kLoc);
        EXPECT_NE(dynamic_cast<TwoSidedBSDF*>(create_bsdf(p).get()), nullptr);
    }
}

// pbrt-v4's "effectively smooth" rule: below alpha 1e-3 (both directions) a rough dielectric or
// conductor is built as the smooth one, so `-D alpha=0` makes a scene's glass smooth (a delta
// lobe that MNEE treats as specular); at 1e-3 it stays rough.
TEST(BsdfFactory, EffectivelySmoothRoughnessBuildsTheSmoothModel) {
    const auto build = [](const char* type, double alpha) {
        Props p = make(type);
        p.set("alpha", alpha, kLoc);
        return create_bsdf(p);
    };
    auto smooth = build("roughdielectric", 0.0);
    ASSERT_NE(dynamic_cast<DielectricBSDF*>(smooth.get()), nullptr);
    EXPECT_TRUE(smooth->has_delta());
    EXPECT_FALSE(smooth->has_microfacet());
    EXPECT_NE(dynamic_cast<DielectricBSDF*>(build("roughdielectric", 0.0009).get()), nullptr);
    EXPECT_NE(dynamic_cast<RoughDielectricBSDF*>(build("roughdielectric", 0.001).get()), nullptr);
    EXPECT_NE(dynamic_cast<ConductorBSDF*>(build("roughconductor", 0.0).get()), nullptr);
    EXPECT_NE(dynamic_cast<RoughConductorBSDF*>(build("roughconductor", 0.01).get()), nullptr);
}

TEST(BsdfFactory, RejectsBadInput) {
    auto throws = [](Props p) { EXPECT_THROW(create_bsdf(p), SceneError) << p.type(); };
    throws(make("velvet"));
    {
        Props p = make("roughconductor");
        p.set("alpha", -0.1, kLoc);
        throws(p);
    }
    {
        Props p = make("roughdielectric");
        p.set("distribution", std::string("phong"), kLoc);
        throws(p);
    }
    {
        Props p = make("diffuse");
        p.set("reflectanse", 0.5, kLoc);  // typo: unused parameter
        throws(p);
    }
    {
        Props p = make("conductor");
        p.set("material", std::string("Xx"), kLoc);
        throws(p);
    }
    {
        Props p = make("dielectric");
        p.set("int_ior", std::string("unobtainium"), kLoc);
        throws(p);
    }
    {
        Props p = make("twosided");
        p.add_child("", std::make_shared<DielectricBSDF>(Spectrum::constant(1.5), Spectrum::constant(1.0)), kLoc);
        throws(p);  // transmissive BSDFs cannot be two-sided
    }
    {
        Props p = make("principled");
        p.set("eta", 1.4, kLoc);
        p.set("specular", 0.5, kLoc);
        throws(p);  // one or the other, as in Mitsuba
    }
    {
        Props p = make("principled");
        p.set("roughness", 1.5, kLoc);
        throws(p);  // principled parameters lie in [0, 1]
    }
    {
        Props p = make("principled");
        p.set("spec_trans", 0.5, kLoc);
        p.set("base_color", RGB(0.8, 0.3, 0.2), kLoc);
        p.set("clearcoat", 0.3, kLoc);
        EXPECT_TRUE(create_bsdf(p)->is_transmissive());
        EXPECT_NEAR(PrincipledBSDF::eta_from_specular(0.5), 1.5, 1e-12);
    }
}

}  // namespace

// Two corners of the principled BSDF in closed form. With spec_trans = 1, metallic = 0 and a white
// base it is the rough dielectric (GGX, alpha = roughness^2) in value and density, from both
// sides; with metallic = 1 it is a GGX reflector with Schlick's Fresnel of F0 = base colour.
TEST(Principled, CornersInClosedForm) {
    using MD = MicrofacetDistribution;
    PrincipledBSDF::Params glass;
    glass.base_color = ConstantTexture::make(1.0);
    glass.roughness = 0.5;
    glass.spec_trans = 1.0;
    glass.spec_trans_on = true;
    glass.eta = 1.5;
    const PrincipledBSDF p(glass);
    const RoughDielectricBSDF rd(MD(MD::Type::GGX, 0.25), Spectrum::constant(1.5), Spectrum::constant(1.0));
    BSDFContext ctx;
    PCG32 rng(7, 3);
    auto random_dir = [&] {
        const double z = 2 * rng.next_double() - 1, phi = 2 * kPi * rng.next_double();
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return Vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    int compared = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 wo = random_dir(), wi = random_dir();
        const double a = p.eval(ctx, wo, wi)[0], b = rd.eval(ctx, wo, wi)[0];
        EXPECT_NEAR(a, b, 1e-9 * (1 + b)) << k;
        EXPECT_NEAR(p.pdf(ctx, wo, wi), rd.pdf(ctx, wo, wi), 1e-9 * (1 + rd.pdf(ctx, wo, wi))) << k;
        compared += b > 0;
    }
    EXPECT_GT(compared, 500);

    PrincipledBSDF::Params metal;
    metal.base_color = ConstantTexture::make(0.7);
    metal.roughness = 0.4;
    metal.metallic = 1.0;
    const PrincipledBSDF m(metal);
    const MD ggx(MD::Type::GGX, 0.16);
    for (int k = 0; k < 200; ++k) {
        Vec3 wo = random_dir(), wi = random_dir();
        wo.z = std::abs(wo.z);
        wi.z = std::abs(wi.z);
        const Vec3 h = normalize(wo + wi);
        const double F = 0.7 + 0.3 * std::pow(1 - dot(wo, h), 5);
        const double want = F * ggx.D(h) * ggx.G(wo, wi, h) / (4 * wo.z * wi.z);
        EXPECT_NEAR(m.eval(ctx, wo, wi)[0], want, 1e-9 * (1 + want)) << k;
    }
}

// Mitsuba 3's flip_invalid_normals: a viewer behind the perturbed normal (a normal map tilted
// 60 degrees towards +x, seen from -x at 70 degrees) would see black; the flip mirrors the normal
// about the surface's, so the value equals that of the mirrored map, unflipped. Without the flip
// it is 0. The shadowing term is Estevez et al.'s closed form, and 1 for the unperturbed normal.
TEST(NormalMap, FlipInvalidNormalsAndShadowing) {
    auto normal_tex = [](const Vec3& n) {
        const RGB c(0.5 * (n.x + 1), 0.5 * (n.y + 1), 0.5 * (n.z + 1));
        return ConstantTexture::make(Spectrum::from_rgb_unbounded(c), c.luminance(), c);
    };
    const double t = kPi / 3;
    const Vec3 n(std::sin(t), 0, std::cos(t)), mirrored(-std::sin(t), 0, std::cos(t));
    auto diffuse = std::make_shared<DiffuseBSDF>(Spectrum::constant(0.5));
    SurfaceInteraction si;
    si.n = si.ng = Vec3(0, 0, 1);
    BSDFContext ctx;
    ctx = ctx.at(si);
    const Vec3 wo = Vec3(-std::sin(70 * kPi / 180), 0, std::cos(70 * kPi / 180));
    const Vec3 wi = normalize(Vec3(-0.3, 0.1, 0.95));
    const NormalMapBSDF flipped(normal_tex(n), diffuse, {true, false});
    const NormalMapBSDF unflipped(normal_tex(n), diffuse, {false, false});
    const NormalMapBSDF mirror(normal_tex(mirrored), diffuse, {false, false});
    EXPECT_EQ(unflipped.eval(ctx, wo, wi)[0], 0.0);
    EXPECT_GT(flipped.eval(ctx, wo, wi)[0], 0.0);
    EXPECT_NEAR(flipped.eval(ctx, wo, wi)[0], mirror.eval(ctx, wo, wi)[0], 1e-6);
    EXPECT_NEAR(flipped.pdf(ctx, wo, wi), mirror.pdf(ctx, wo, wi), 1e-6);
    // A viewer in front of the normal sees no flip.
    const Vec3 front = normalize(Vec3(0.5, 0, 1));
    EXPECT_NEAR(flipped.eval(ctx, front, wi)[0], unflipped.eval(ctx, front, wi)[0], 1e-12);
    // Shadowing: G = 2 / (1 + sqrt(1 + a^2 tan^2 theta_i)), a^2 = min(tan^2 theta_n / 8, 1).
    const NormalMapBSDF shadowed(normal_tex(n), diffuse, {false, true});
    const double a2 = std::min(std::tan(t) * std::tan(t) / 8, 1.0), tan2 = (1 - wi.z * wi.z) / (wi.z * wi.z);
    const double G = 2 / (1 + std::sqrt(1 + a2 * tan2));
    EXPECT_NEAR(shadowed.eval(ctx, front, wi)[0], G * unflipped.eval(ctx, front, wi)[0], 1e-6);
    EXPECT_NEAR(shadowed.shadowing(Vec3(0, 0, 1), wi), 1.0, 0.0);
}

// The thin sheet is reciprocal in every lobe, reflection and transmission (its specular
// transmission uses the half vector of one direction and the other carried through the sheet,
// which is the same pair either way round up to a point reflection that GGX does not see), and
// looks the same from both sides.
TEST(PrincipledThin, ReciprocalAndTwoSided) {
    PrincipledThinBSDF::Params q;
    const RGB rgb(0.8, 0.4, 0.2);
    q.base_color = ConstantTexture::make(Spectrum::from_rgb_reflectance(rgb), rgb.luminance(), rgb);
    q.roughness = 0.35;
    q.anisotropic = 0.5;
    q.anisotropic_on = true;
    q.spec_trans = 0.6;
    q.spec_trans_on = true;
    q.diff_trans = 0.7;
    q.diff_trans_on = true;
    q.spec_tint = 0.4;
    q.sheen = 0.5;
    q.flatness = 0.3;
    const PrincipledThinBSDF p(q);
    BSDFContext ctx;
    ctx.wl = SampledWavelengths::sample_visible(Vec2(0.7, 0.2));
    PCG32 rng(6, 3);
    int transmitted = 0;
    for (int k = 0; k < 500; ++k) {
        const double z1 = 2 * rng.next_double() - 1, z2 = 2 * rng.next_double() - 1;
        const double p1 = 2 * kPi * rng.next_double(), p2 = 2 * kPi * rng.next_double();
        const Vec3 a(std::sqrt(1 - z1 * z1) * std::cos(p1), std::sqrt(1 - z1 * z1) * std::sin(p1), z1);
        const Vec3 b(std::sqrt(1 - z2 * z2) * std::cos(p2), std::sqrt(1 - z2 * z2) * std::sin(p2), z2);
        const SampledSpectrum ab = p.eval(ctx, a, b), ba = p.eval(ctx, b, a), flipped = p.eval(ctx, -a, -b);
        transmitted += a.z * b.z < 0 && ab[0] > 0;
        for (int i = 0; i < kSpectrumSamples; ++i) {
            EXPECT_NEAR(ab[i], ba[i], 1e-9 * (1 + ab[i])) << k;
            EXPECT_NEAR(ab[i], flipped[i], 1e-9 * (1 + ab[i])) << k;
        }
    }
    EXPECT_GT(transmitted, 100);
}

// Every reflection lobe of the principled BSDF is reciprocal (the Fresnel terms read the half
// angle, the diffuse and sheen terms are symmetric in the two directions), and a white metal
// reflects at most all the light (estimated albedo by cosine-weighted quadrature).
TEST(Principled, ReflectionIsReciprocalAndWhiteMetalConservesEnergy) {
    PrincipledBSDF::Params q;
    const RGB rgb(0.8, 0.4, 0.2);
    q.base_color = ConstantTexture::make(Spectrum::from_rgb_reflectance(rgb), rgb.luminance(), rgb);
    q.roughness = 0.35;
    q.metallic = 0.3;
    q.spec_tint = 0.5;
    q.sheen = 0.6;
    q.sheen_tint = 0.4;
    q.clearcoat = 0.8;
    q.clearcoat_on = true;
    q.flatness = 0.3;
    const PrincipledBSDF p(q);
    BSDFContext ctx;
    ctx.wl = SampledWavelengths::sample_visible(Vec2(0.3, 0.6));
    PCG32 rng(5, 9);
    for (int k = 0; k < 500; ++k) {
        const double z1 = rng.next_double(), z2 = rng.next_double();
        const double p1 = 2 * kPi * rng.next_double(), p2 = 2 * kPi * rng.next_double();
        const Vec3 a(std::sqrt(1 - z1 * z1) * std::cos(p1), std::sqrt(1 - z1 * z1) * std::sin(p1), z1);
        const Vec3 b(std::sqrt(1 - z2 * z2) * std::cos(p2), std::sqrt(1 - z2 * z2) * std::sin(p2), z2);
        const SampledSpectrum ab = p.eval(ctx, a, b), ba = p.eval(ctx, b, a);
        for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_NEAR(ab[i], ba[i], 1e-9 * (1 + ab[i])) << k;
    }
    PrincipledBSDF::Params w;
    w.base_color = ConstantTexture::make(1.0);
    w.roughness = 0.3;
    w.metallic = 1.0;
    const PrincipledBSDF white(w);
    for (double theta : {0.2, 0.8, 1.3}) {
        const Vec3 wo(std::sin(theta), 0, std::cos(theta));
        double albedo = 0;
        const int n = 200000;
        for (int k = 0; k < n; ++k) {
            const auto s = white.sample(ctx, wo, rng.next_double(), Vec2(rng.next_double(), rng.next_double()));
            if (s) albedo += s->weight[0];
        }
        albedo /= n;
        EXPECT_LE(albedo, 1.0 + 0.01) << theta;
        EXPECT_GT(albedo, 0.8) << theta;  // only shadowing is lost at this roughness
    }
}
