// Chi-square tests of every non-delta BSDF lobe (and of the microfacet samplers themselves):
// the directions produced by sample() must follow pdf(), and each sample's weight and pdf
// must equal eval |cos| / pdf and pdf() at the sampled direction.
#include <gtest/gtest.h>

#include <memory>
#include <tuple>

#include "bsdf/blend.h"
#include "bsdf/bumpmap.h"
#include "bsdf/conductor_data.h"
#include "bsdf/diffuse.h"
#include "bsdf/microfacet.h"
#include "bsdf/normalmap.h"
#include "bsdf/null_bsdf.h"
#include "bsdf/plastic.h"
#include "bsdf/principled.h"
#include "bsdf/principledthin.h"
#include "bsdf/roughconductor.h"
#include "bsdf/roughdielectric.h"
#include "bsdf/roughplastic.h"
#include "bsdf/twosided.h"
#include "stat/chi2.h"
#include "texture/bitmap.h"
#include "texture/constant.h"

using namespace snell;
using snell::test::Chi2Options;
using snell::test::Chi2Result;

namespace {

using MD = MicrofacetDistribution;

Vec3 dir(double theta_deg, double phi_deg = 17) {
    const double t = theta_deg * kPi / 180, p = phi_deg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

struct Case {
    std::string name;
    std::shared_ptr<const BSDF> bsdf;  // null for the microfacet-only cases
    Vec3 wo;
    std::shared_ptr<const MD> distr;  // microfacet cases
    bool visible = false;             // microfacet case: visible-normal sampler
    TransportMode mode = TransportMode::Radiance;
    std::shared_ptr<const SurfaceInteraction> si;  // the surface point textured BSDFs read
};

// Readable parameter names in gtest output.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

Case bsdf_case(std::string name, std::shared_ptr<const BSDF> bsdf, Vec3 wo) {
    return {std::move(name), std::move(bsdf), wo, nullptr, false, TransportMode::Radiance, nullptr};
}

std::shared_ptr<const BSDF> rough_dielectric(MD::Type t, double au, double av, bool vis = true) {
    return std::make_shared<RoughDielectricBSDF>(MD(t, au, av, vis), Spectrum::constant(1.5), Spectrum::constant(1.0));
}

std::vector<Case> make_cases() {
    std::vector<Case> c;
    const auto B = MD::Type::Beckmann, G = MD::Type::GGX;
    c.push_back(bsdf_case("diffuse", std::make_shared<DiffuseBSDF>(Spectrum::constant(0.7)), dir(30)));
    // Rough dielectric: both distributions, alphas 0.05..0.5, outside and inside (wo below;
    // beyond 41.8 deg inside a smooth interface would reflect totally).
    for (auto t : {B, G})
        for (double a : {0.05, 0.2, 0.5})
            for (double th : {10.0, 70.0, 150.0, 125.0}) {
                const std::string n = std::string(t == B ? "beckmann" : "ggx") + "_a" + std::to_string(int(a * 100)) +
                                      "_th" + std::to_string(int(th));
                c.push_back(bsdf_case("roughdielectric_" + n, rough_dielectric(t, a, a), dir(th)));
            }
    c.push_back(bsdf_case("roughdielectric_ggx_aniso", rough_dielectric(G, 0.1, 0.4), dir(50, 60)));
    c.push_back(bsdf_case("roughdielectric_ggx_global", rough_dielectric(G, 0.3, 0.3, false), dir(40)));
    c.push_back(bsdf_case("roughdielectric_beckmann_aniso_below", rough_dielectric(B, 0.4, 0.15), dir(140, 30)));
    {
        Case imp = bsdf_case("roughdielectric_importance", rough_dielectric(G, 0.3, 0.3), dir(135));
        imp.mode = TransportMode::Importance;
        c.push_back(imp);
    }
    auto au = named_conductor("Au");
    c.push_back(bsdf_case("roughconductor_beckmann_au", std::make_shared<RoughConductorBSDF>(MD(B, 0.2), au), dir(20)));
    c.push_back(bsdf_case("roughconductor_ggx_a05", std::make_shared<RoughConductorBSDF>(MD(G, 0.05), au), dir(60)));
    c.push_back(bsdf_case("roughconductor_ggx_aniso",
                          std::make_shared<RoughConductorBSDF>(MD(G, 0.1, 0.4), std::nullopt), dir(70, 100)));
    c.push_back(bsdf_case("roughconductor_beckmann_global",
                          std::make_shared<RoughConductorBSDF>(MD(B, 0.5, 0.5, false), au), dir(45)));
    auto plastic = std::make_shared<PlasticBSDF>(Spectrum::constant(0.6), Spectrum::constant(1.0), 1.49, 1.0);
    c.push_back(bsdf_case("plastic_30", plastic, dir(30)));
    c.push_back(bsdf_case("plastic_80", plastic, dir(80)));
    c.push_back(bsdf_case(
        "plastic_nonlinear",
        std::make_shared<PlasticBSDF>(Spectrum::constant(0.9), Spectrum::constant(0.5), 1.6, 1.0, true), dir(50)));
    for (auto [t, a, th] : {std::tuple{B, 0.1, 30.0}, std::tuple{G, 0.3, 70.0}, std::tuple{G, 0.05, 10.0}})
        c.push_back(bsdf_case(
            "roughplastic_" + std::string(t == B ? "beckmann" : "ggx") + "_" + std::to_string(int(a * 100)) + "_th" +
                std::to_string(int(th)),
            std::make_shared<RoughPlasticBSDF>(MD(t, a), Spectrum::constant(0.6), Spectrum::constant(1.0), 1.49, 1.0),
            dir(th)));
    c.push_back(bsdf_case("roughplastic_nonlinear",
                          std::make_shared<RoughPlasticBSDF>(MD(G, 0.2), Spectrum::constant(0.9),
                                                             Spectrum::constant(0.5), 1.6, 1.0, true),
                          dir(50)));
    auto diffuse = std::make_shared<DiffuseBSDF>(Spectrum::constant(0.5));
    c.push_back(bsdf_case(
        "blendbsdf_diffuse_roughconductor",
        std::make_shared<BlendBSDF>(0.3, diffuse, std::make_shared<RoughConductorBSDF>(MD(G, 0.1), au)), dir(40)));
    c.push_back(
        bsdf_case("mask_diffuse", std::make_shared<BlendBSDF>(0.4, std::make_shared<NullBSDF>(), diffuse), dir(25)));
    c.push_back(bsdf_case("twosided_diffuse_below", std::make_shared<TwoSidedBSDF>(diffuse), dir(120)));
    // Mitsuba's principled BSDF: its default, every lobe at once (anisotropic), transmission
    // from both sides, the fake subsurface.
    {
        const RGB rgb(0.8, 0.4, 0.2);
        const auto base = ConstantTexture::make(Spectrum::from_rgb_reflectance(rgb), rgb.luminance(), rgb);
        auto principled = [&](auto tweak) {
            PrincipledBSDF::Params q;
            q.base_color = base;
            tweak(q);
            return std::make_shared<PrincipledBSDF>(q);
        };
        c.push_back(bsdf_case("principled_default", principled([](auto&) {}), dir(30)));
        c.push_back(bsdf_case("principled_all_lobes", principled([](auto& q) {
                                  q.roughness = 0.3;
                                  q.metallic = 0.4;
                                  q.anisotropic = 0.6;
                                  q.anisotropic_on = true;
                                  q.spec_tint = 0.5;
                                  q.sheen = 0.5;
                                  q.sheen_tint = 0.3;
                                  q.clearcoat = 0.7;
                                  q.clearcoat_gloss = 0.4;
                                  q.clearcoat_on = true;
                                  q.spec_trans = 0.3;
                                  q.spec_trans_on = true;
                              }),
                              dir(60)));
        c.push_back(bsdf_case("principled_clearcoat", principled([](auto& q) {
                                  q.clearcoat = 1.0;
                                  q.clearcoat_gloss = 0.4;
                                  q.clearcoat_on = true;
                              }),
                              dir(60)));
        c.push_back(bsdf_case("principled_anisotropic", principled([](auto& q) {
                                  q.roughness = 0.3;
                                  q.anisotropic = 0.6;
                                  q.anisotropic_on = true;
                              }),
                              dir(60)));
        auto glassy = [](auto& q) {
            q.roughness = 0.5;
            q.spec_trans = 0.8;
            q.spec_trans_on = true;
        };
        c.push_back(bsdf_case("principled_transmission_front", principled(glassy), dir(40)));
        c.push_back(bsdf_case("principled_transmission_back", principled(glassy), dir(130)));
        c.push_back(bsdf_case("principled_flatness", principled([](auto& q) {
                                  q.roughness = 0.8;
                                  q.flatness = 0.6;
                              }),
                              dir(70)));
        // The thin sheet: all its lobes (specular reflection and unbent transmission, diffuse
        // reflection and transmission, sheen), from the front and from the back.
        auto thin = [&](auto tweak) {
            PrincipledThinBSDF::Params q;
            q.base_color = base;
            tweak(q);
            return std::make_shared<PrincipledThinBSDF>(q);
        };
        c.push_back(bsdf_case("principledthin_default", thin([](auto&) {}), dir(35)));
        auto sheet = [](auto& q) {
            q.roughness = 0.4;
            q.spec_trans = 0.5;
            q.spec_trans_on = true;
            q.diff_trans = 0.8;
            q.diff_trans_on = true;
            q.sheen = 0.4;
            q.spec_tint = 0.3;
            q.eta = 1.4;
        };
        c.push_back(bsdf_case("principledthin_all_lobes_front", thin(sheet), dir(50)));
        c.push_back(bsdf_case("principledthin_all_lobes_back", thin(sheet), dir(125)));
        c.push_back(bsdf_case("principledthin_anisotropic", thin([](auto& q) {
                                  q.roughness = 0.3;
                                  q.anisotropic = 0.7;
                                  q.anisotropic_on = true;
                                  q.spec_trans = 0.9;
                                  q.spec_trans_on = true;
                              }),
                              dir(65)));
    }
    // Perturbed shading frames at a point of a plane (dp/du = 2 x, dp/dv = 2 y): a normal map
    // tilted by 35 degrees, and a bump map whose height rises along u and v. Grazing directions
    // come from the side each normal leans to (the bumps lean towards -u): from the other side
    // they lie below the perturbed surface, where both BSDFs are zero.
    auto point = std::make_shared<SurfaceInteraction>();
    point->n = point->ng = Vec3(0, 0, 1);
    point->dpdu = Vec3(2, 0, 0);
    point->dpdv = Vec3(0, 2, 0);
    point->uv = Vec2(0.4, 0.45);
    point->shading = Frame::from_normal_tangent(point->n, point->dpdu);
    const Vec3 tilted(std::sin(0.61), 0.1, std::cos(0.61));
    auto normals = ConstantTexture::make(Spectrum::constant(0.5), 0.5,
                                         RGB(0.5 * (tilted.x + 1), 0.5 * (tilted.y + 1), 0.5 * (tilted.z + 1)));
    TextureImage heights;
    heights.width = heights.height = 2;
    heights.channels = 1;
    heights.texels = {0.0f, 0.3f, 0.2f, 0.6f};
    auto bumps = std::make_shared<BitmapTexture>(heights, BitmapTexture::Filter::Bilinear, BitmapTexture::Wrap::Repeat,
                                                 true, Transform());
    for (auto [name, nested] :
         {std::pair{"diffuse", std::shared_ptr<const BSDF>(diffuse)},
          std::pair{"roughconductor",
                    std::shared_ptr<const BSDF>(std::make_shared<RoughConductorBSDF>(MD(G, 0.2), au))}}) {
        for (double theta : {20.0, 70.0}) {
            Case nm = bsdf_case(std::string("normalmap_") + name + "_" + std::to_string(int(theta)),
                                std::make_shared<NormalMapBSDF>(normals, nested), dir(theta, theta > 45 ? 20 : 200));
            nm.si = point;
            c.push_back(nm);
            Case bm = bsdf_case(std::string("bumpmap_") + name + "_" + std::to_string(int(theta)),
                                std::make_shared<BumpMapBSDF>(bumps, 1.5, nested), dir(theta, 200));
            bm.si = point;
            c.push_back(bm);
        }
    }
    c.push_back(bsdf_case("twosided_two_below",
                          std::make_shared<TwoSidedBSDF>(diffuse, std::make_shared<RoughConductorBSDF>(MD(G, 0.3), au)),
                          dir(130)));
    // The microfacet samplers on their own (global D cos sampling is what MNEE uses).
    for (auto t : {B, G})
        for (auto [au_, av_] : {std::pair{0.1, 0.1}, std::pair{0.5, 0.5}, std::pair{0.1, 0.4}}) {
            const std::string n = std::string(t == B ? "beckmann" : "ggx") + "_" + std::to_string(int(au_ * 100)) +
                                  "_" + std::to_string(int(av_ * 100));
            auto d = std::make_shared<const MD>(t, au_, av_);
            c.push_back({"microfacet_global_" + n, nullptr, dir(0), d, false, TransportMode::Radiance, nullptr});
            c.push_back({"microfacet_visible_" + n, nullptr, dir(65, 40), d, true, TransportMode::Radiance, nullptr});
        }
    return c;
}

const std::vector<Case>& cases() {
    static const std::vector<Case> c = make_cases();
    return c;
}

class BsdfChi2 : public ::testing::TestWithParam<Case> {};

TEST_P(BsdfChi2, SamplesFollowPdf) {
    const Case& c = GetParam();
    Chi2Options opt;
    opt.theta_res = 12;
    opt.phi_res = 24;
    opt.samples = 1000000;
    opt.test_count = int(cases().size());
    opt.seed = std::hash<std::string>{}(c.name);
    Chi2Result r;
    size_t weight_bad = 0, pdf_bad = 0, checked = 0;
    std::string first_bad;
    if (c.bsdf) {
        BSDFContext ctx;
        ctx.wl = SampledWavelengths::sample_visible(Vec2(0.3, 0.6));  // four distinct wavelengths
        ctx.mode = c.mode;
        if (c.si) ctx = ctx.at(*c.si);
        const BSDF& b = *c.bsdf;
        r = snell::test::chi2_sphere_test(
            [&](PCG32& rng) -> std::optional<Vec3> {
                const double uc = rng.next_double();
                const Vec2 u(rng.next_double(), rng.next_double());
                auto s = b.sample(ctx, c.wo, uc, u);
                if (!s || s->is_delta()) return std::nullopt;
                // Consistency of the sample record with eval()/pdf().
                const double p = b.pdf(ctx, c.wo, s->wi);
                const SampledSpectrum f = b.eval(ctx, c.wo, s->wi) * (std::abs(s->wi.z) / p);
                ++checked;
                if (!(std::abs(s->pdf - p) <= 1e-9 * p)) {
                    if (!pdf_bad++) first_bad = "pdf " + std::to_string(s->pdf) + " vs " + std::to_string(p);
                }
                // Every wavelength's weight is its f |cos| over the hero's pdf; a hero-only
                // sample (dispersive refraction) carries the hero's and zeros.
                for (int i = 0; i < kSpectrumSamples; ++i) {
                    const double w = s->hero_only && i > 0 ? 0.0 : f[i];
                    if (!(std::abs(s->weight[i] - w) <= 1e-9 * w + 1e-14)) {
                        if (!weight_bad++)
                            first_bad += " weight[" + std::to_string(i) + "] " + std::to_string(s->weight[i]) + " vs " +
                                         std::to_string(w);
                    }
                }
                return s->wi;
            },
            [&](const Vec3& wi) { return b.pdf(ctx, c.wo, wi); }, opt);
    } else {
        const MD& d = *c.distr;
        r = snell::test::chi2_sphere_test(
            [&](PCG32& rng) -> std::optional<Vec3> {
                const Vec2 u(rng.next_double(), rng.next_double());
                return c.visible ? d.sample_visible_m(c.wo, u) : d.sample_m(u);
            },
            [&](const Vec3& m) { return c.visible ? d.pdf_visible_m(c.wo, m) : d.pdf_m(m); }, opt);
        EXPECT_NEAR(r.pdf_integral, 1.0, 1e-4);  // these samplers never fail
    }
    EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
    EXPECT_LE(r.pdf_integral, 1.0 + 1e-4) << c.name;
    EXPECT_GT(r.valid_samples, opt.samples / 10) << c.name;
    EXPECT_EQ(pdf_bad, 0u) << c.name << " (" << checked << " checked) " << first_bad;
    EXPECT_EQ(weight_bad, 0u) << c.name << " (" << checked << " checked) " << first_bad;
}

INSTANTIATE_TEST_SUITE_P(All, BsdfChi2, ::testing::ValuesIn(cases()), [](const auto& info) { return info.param.name; });

}  // namespace
