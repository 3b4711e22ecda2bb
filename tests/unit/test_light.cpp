// Unit tests of the emitters: sampling/pdf consistency, falloff profiles, the envmap mapping
// convention, the RGB upsampling lattice and the factory's parameter handling.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/props.h"
#include "core/rng.h"
#include "io/image.h"
#include "light/area.h"
#include "light/constant.h"
#include "light/directional.h"
#include "light/envmap.h"
#include "light/factory.h"
#include "light/point.h"
#include "light/rgb_illuminant_table.h"
#include "light/spot.h"
#include "unit/test_light_disk.h"

using namespace snell;

namespace {

const SourceLoc kLoc{"test.xml", 7};

Props make_props(const std::string& type) { return Props("emitter", type, kLoc); }

Vec2 next2(PCG32& rng) {
    const double a = rng.next_double();
    return {a, rng.next_double()};
}

double rel_diff(double a, double b) { return std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

// A small non-trivial HDR map: smooth gradient, a hot texel and a black band.
Image test_image(int W, int H) {
    Image img;
    img.width = W;
    img.height = H;
    img.rgb.assign(size_t(3) * W * H, 0.f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            img.at(x, y, 0) = float(0.2 + 0.1 * x);
            img.at(x, y, 1) = float(0.5 + 0.05 * y);
            img.at(x, y, 2) = float(0.3 + 0.02 * x * y);
            if (y == H - 2) img.at(x, y, 0) = img.at(x, y, 1) = img.at(x, y, 2) = 0.f;
        }
    img.at(3, 2, 0) = 40.f;
    img.at(3, 2, 1) = 30.f;
    return img;
}

}  // namespace

// --- area --------------------------------------------------------------------------------------

TEST(AreaLight, SamplePdfMatchesPdfLiAndAreaDensity) {
    auto disk = std::make_shared<test::TestDisk>(Vec3(0, 0, 2), Vec3(0.2, 0.1, -1), 0.7);
    const Spectrum L = Spectrum::from_rgb_illuminant(RGB(3, 2, 1));
    AreaLight light(L, disk);
    const LightSampleContext ref{Vec3(0.3, -0.2, 0), Vec3(0, 0, 1)};
    PCG32 rng(1, 2);
    int n_ok = 0;
    for (int i = 0; i < 1000; ++i) {
        const double lambda = 400 + 300 * rng.next_double();
        auto ls = light.sample_li(ref, next2(rng), SampledWavelengths::single(lambda));
        ASSERT_TRUE(ls);
        ++n_ok;
        EXPECT_NEAR(length(ls->wi), 1.0, 1e-12);
        EXPECT_NEAR(length(ls->p - ref.p), ls->dist, 1e-12);
        EXPECT_LT(rel_diff(ls->pdf, light.pdf_li(ref, ls->p, ls->n, ls->wi)), 1e-12);
        // Area density of the disk's uniform sampling is 1 / area.
        EXPECT_LT(rel_diff(ls->pdf_area, 1.0 / disk->area()), 1e-10);
        EXPECT_DOUBLE_EQ(ls->Le[0], L.eval(lambda));
        EXPECT_FALSE(ls->delta);
    }
    EXPECT_EQ(n_ok, 1000);
}

TEST(AreaLight, OneSidedEmission) {
    auto disk = std::make_shared<test::TestDisk>(Vec3(0, 0, 0), Vec3(0, 0, 1), 1.0);
    AreaLight light(Spectrum::constant(2.0), disk);
    EXPECT_EQ(
        light.le(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(), normalize(Vec3(0.3, 0, 1)), SampledWavelengths::single(550))[0],
        2.0);
    EXPECT_EQ(
        light.le(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec2(), normalize(Vec3(0.3, 0, -1)), SampledWavelengths::single(550))[0],
        0.0);
    // A reference point behind the disk sees no emission: nothing to sample.
    PCG32 rng(3, 4);
    for (int i = 0; i < 100; ++i)
        EXPECT_FALSE(light.sample_li({Vec3(0, 0, -1), Vec3()}, next2(rng), SampledWavelengths::single(550)));
    // ...while one in front always gets a sample.
    for (int i = 0; i < 100; ++i)
        EXPECT_TRUE(light.sample_li({Vec3(0, 0, 1), Vec3()}, next2(rng), SampledWavelengths::single(550)));
}

TEST(AreaLight, PowerAndFactoryRegistration) {
    auto disk = std::make_shared<test::TestDisk>(Vec3(0, 0, 0), Vec3(0, 0, 1), 0.5);
    Props p = make_props("area");
    p.set("radiance", RGB(4, 4, 4), kLoc);
    auto light = create_area_light(p, disk);
    ASSERT_TRUE(light);
    EXPECT_EQ(disk->emitter(), light.get());
    EXPECT_EQ(light->shape(), disk.get());
    EXPECT_EQ(light->kind(), LightKind::Area);
    const double expected = Spectrum::from_rgb_illuminant(RGB(4)).average() * disk->area() * kPi;
    EXPECT_GT(light->power(), 0);
    EXPECT_NEAR(light->power(), expected, 1e-12 * expected);
}

// --- point / spot / directional ----------------------------------------------------------------

TEST(PointLight, InverseSquareAndDelta) {
    PointLight light(Spectrum::constant(8.0), Vec3(1, 2, 3));
    auto ls = light.sample_li({Vec3(1, 2, 1), Vec3()}, Vec2(0.3, 0.9), SampledWavelengths::single(500));
    ASSERT_TRUE(ls);
    EXPECT_TRUE(ls->delta);
    EXPECT_EQ(ls->pdf, 1.0);
    EXPECT_NEAR(ls->dist, 2.0, 1e-15);
    EXPECT_NEAR(ls->Le[0], 8.0 / 4.0, 1e-15);
    EXPECT_NEAR(ls->wi.z, 1.0, 1e-15);
    EXPECT_EQ(light.pdf_li({}, Vec3(), Vec3(), Vec3(0, 0, 1)), 0.0);
    EXPECT_NEAR(light.power(), 4 * kPi * 8.0, 1e-12);
    EXPECT_TRUE(light.is_delta());
}

TEST(PointLight, FactoryPositionOrToWorld) {
    Props a = make_props("point");
    a.set("position", Vec3(0, 5, 0), kLoc);
    a.set("intensity", 3.0, kLoc);
    auto la = create_light(a);
    EXPECT_EQ(static_cast<PointLight&>(*la).position(), Vec3(0, 5, 0));

    Props b = make_props("point");
    b.set("to_world", Transform::translate(Vec3(1, 2, 3)), kLoc);
    auto lb = create_light(b);
    EXPECT_EQ(static_cast<PointLight&>(*lb).position(), Vec3(1, 2, 3));

    Props c = make_props("point");
    c.set("to_world", Transform::translate(Vec3(1, 2, 3)), kLoc);
    c.set("position", Vec3(0, 5, 0), kLoc);
    EXPECT_THROW(create_light(c), SceneError);
}

TEST(SpotLight, MitsubaLinearFalloff) {
    // Shines along world -y (to_world rotates local +z onto -y).
    const Transform to_world = Transform::translate(Vec3(0, 4, 0)) * Transform::rotate(Vec3(1, 0, 0), 90);
    ASSERT_NEAR(to_world.vector(Vec3(0, 0, 1)).y, -1.0, 1e-12);
    const double cutoff = 30, beam = 20;
    SpotLight light(Spectrum::constant(10.0), to_world, cutoff, beam);
    auto dir_at = [](double deg) {
        const double t = deg * kPi / 180;
        return Vec3(std::sin(t), -std::cos(t), 0);
    };
    EXPECT_DOUBLE_EQ(light.falloff(dir_at(0)), 1.0);
    EXPECT_DOUBLE_EQ(light.falloff(dir_at(19.9)), 1.0);
    EXPECT_NEAR(light.falloff(dir_at(25)), 0.5, 1e-9);  // half-way through the ramp
    EXPECT_NEAR(light.falloff(dir_at(29)), 0.1, 1e-9);
    EXPECT_EQ(light.falloff(dir_at(30.01)), 0.0);
    EXPECT_EQ(light.falloff(dir_at(120)), 0.0);

    // sample_li: Le = I * falloff / d^2 towards a point 25 degrees off axis at distance 2.
    const Vec3 ref = Vec3(0, 4, 0) + dir_at(25) * 2.0;
    auto ls = light.sample_li({ref, Vec3()}, Vec2(), SampledWavelengths::single(600));
    ASSERT_TRUE(ls);
    EXPECT_NEAR(ls->Le[0], 10.0 * 0.5 / 4.0, 1e-8);
    EXPECT_TRUE(ls->delta);
    // Outside the cone: the light point is still returned (MNEE needs it) but carries no light.
    const auto outside =
        light.sample_li({Vec3(0, 4, 0) + dir_at(40) * 2.0, Vec3()}, Vec2(), SampledWavelengths::single(600));
    ASSERT_TRUE(outside);
    EXPECT_EQ(outside->Le[0], 0.0);

    // power: I times the solid-angle integral of the profile (midpoint rule in theta).
    double integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n * kPi;
        integral += light.falloff(dir_at(t * 180 / kPi)) * std::sin(t) * (kPi / n) * 2 * kPi;
    }
    EXPECT_NEAR(light.power(), 10.0 * integral, 1e-6 * light.power());
}

TEST(SpotLight, FactoryDefaultsAndValidation) {
    Props a = make_props("spot");
    a.set("cutoff_angle", 40.0, kLoc);
    auto l = create_light(a);
    auto& s = static_cast<SpotLight&>(*l);
    // Default beam_width = 3/4 cutoff = 30 degrees; the light points along +z.
    const double t = 35 * kPi / 180;
    EXPECT_NEAR(s.falloff(Vec3(std::sin(t), 0, std::cos(t))), 0.5, 1e-9);

    Props b = make_props("spot");
    b.set("cutoff_angle", 10.0, kLoc);
    b.set("beam_width", 15.0, kLoc);
    EXPECT_THROW(create_light(b), SceneError);

    Props c = make_props("spot");
    c.set("cuttoff_angle", 10.0, kLoc);  // misspelt: must be reported
    EXPECT_THROW(create_light(c), SceneError);
}

TEST(DirectionalLight, DeltaDirectionAndFarPoint) {
    Props p = make_props("directional");
    p.set("direction", Vec3(0, -2, 0), kLoc);
    p.set("irradiance", 5.0, kLoc);
    auto light = create_light(p);
    Bounds3 b;
    b.expand(Vec3(-1, -1, -1));
    b.expand(Vec3(1, 1, 1));
    light->preprocess(b);
    auto ls = light->sample_li({Vec3(0.5, 0, 0), Vec3()}, Vec2(0.1, 0.2), SampledWavelengths::single(550));
    ASSERT_TRUE(ls);
    EXPECT_EQ(ls->wi, Vec3(0, 1, 0));
    // A <float> irradiance is grey: 5 times the renderer's white illuminant.
    const Spectrum white5 = Spectrum::from_rgb_illuminant(RGB(5.0));
    EXPECT_NEAR(ls->Le[0], white5.eval(550), 1e-12);
    EXPECT_TRUE(ls->delta);
    EXPECT_EQ(ls->dist, kInfinity);
    EXPECT_GT(ls->p.y, std::sqrt(3.0));  // outside the scene's bounding sphere
    EXPECT_NEAR(light->power(), white5.average() * kPi * 3.0, 1e-9);
    EXPECT_TRUE(light->is_infinite());

    Props q = make_props("directional");
    q.set("to_world", Transform::rotate(Vec3(1, 0, 0), 90), kLoc);  // local +z -> world -y
    auto l2 = create_light(q);
    EXPECT_NEAR(static_cast<DirectionalLight&>(*l2).direction().y, -1.0, 1e-12);
}

// --- constant ----------------------------------------------------------------------------------

TEST(ConstantLight, UniformSphere) {
    Props p = make_props("constant");
    p.set("radiance", RGB(0.5, 0.7, 0.9), kLoc);
    auto light = create_light(p);
    const Spectrum L = Spectrum::from_rgb_illuminant(RGB(0.5, 0.7, 0.9));
    PCG32 rng(5, 6);
    const LightSampleContext ref{Vec3(0.1, 0.2, 0.3), Vec3()};
    for (int i = 0; i < 200; ++i) {
        auto ls = light->sample_li(ref, next2(rng), SampledWavelengths::single(470));
        ASSERT_TRUE(ls);
        EXPECT_DOUBLE_EQ(ls->pdf, 1 / (4 * kPi));
        EXPECT_DOUBLE_EQ(ls->pdf, light->pdf_li(ref, ls->p, ls->n, ls->wi));
        EXPECT_DOUBLE_EQ(ls->Le[0], L.eval(470));
        EXPECT_DOUBLE_EQ(light->le_escaped(ls->wi, SampledWavelengths::single(470))[0], L.eval(470));
        EXPECT_EQ(ls->dist, kInfinity);
        EXPECT_NEAR(length(ls->wi), 1.0, 1e-12);
    }
    EXPECT_GT(light->power(), 0);
    EXPECT_TRUE(std::isfinite(light->power()));
}

TEST(Factory, UnknownTypeAndNestedAreaAreErrors) {
    EXPECT_THROW(create_light(make_props("laser")), SceneError);
    EXPECT_THROW(create_light(make_props("area")), SceneError);
    auto disk = std::make_shared<test::TestDisk>(Vec3(), Vec3(0, 0, 1), 1);
    EXPECT_THROW(create_area_light(make_props("point"), disk), SceneError);
    Props p = make_props("area");
    p.set("radiance", 1.0, kLoc);
    p.set("intensity", 1.0, kLoc);  // not an area parameter
    EXPECT_THROW(create_area_light(p, disk), SceneError);
    try {
        create_light(make_props("laser"));
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("test.xml:7"), std::string::npos) << e.what();
    }
}

// --- envmap ------------------------------------------------------------------------------------

TEST(EnvironmentMap, MitsubaLatLongConvention) {
    // +y is up (v = 0), -z is u = 0, +x is u = 1/4, +z is u = 1/2, -x is u = 3/4.
    auto uv = [](const Vec3& d) { return EnvironmentMap::direction_to_uv(d); };
    EXPECT_NEAR(uv(Vec3(0, 1, 0)).y, 0.0, 1e-12);
    EXPECT_NEAR(uv(Vec3(0, -1, 0)).y, 1.0, 1e-12);
    EXPECT_NEAR(uv(Vec3(0, 0, -1)).x, 0.0, 1e-12);
    EXPECT_NEAR(uv(Vec3(1, 0, 0)).x, 0.25, 1e-12);
    EXPECT_NEAR(uv(Vec3(0, 0, 1)).x, 0.5, 1e-12);
    EXPECT_NEAR(uv(Vec3(-1, 0, 0)).x, 0.75, 1e-12);
    EXPECT_NEAR(uv(Vec3(1, 0, 0)).y, 0.5, 1e-12);
    PCG32 rng(7, 8);
    for (int i = 0; i < 100; ++i) {
        const Vec2 a = next2(rng);
        const Vec2 b = uv(EnvironmentMap::uv_to_direction(a));
        EXPECT_NEAR(a.x, b.x, 1e-9);
        EXPECT_NEAR(a.y, b.y, 1e-9);
    }
}

TEST(EnvironmentMap, TexelCentresAndBilinearLookup) {
    const int W = 8, H = 5;
    Image img = test_image(W, H);
    EnvironmentMap env(img, 2.0, Transform());
    // Column i is centred at u = (i + 1/2) / W, row j at v = j / (H - 1).
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const RGB c = env.lookup_rgb(Vec2((i + 0.5) / W, double(j) / (H - 1)));
            EXPECT_NEAR(c.r, img.at(i, j, 0), 1e-6);
            EXPECT_NEAR(c.g, img.at(i, j, 1), 1e-6);
            EXPECT_NEAR(c.b, img.at(i, j, 2), 1e-6);
        }
    // Periodic in u: u = 0 is half-way between the last and the first column.
    const RGB c = env.lookup_rgb(Vec2(0.0, 0.0));
    EXPECT_NEAR(c.r, 0.5 * (img.at(W - 1, 0, 0) + img.at(0, 0, 0)), 1e-6);
    // The hot texel (3, 2) seen along its own direction, with scale 2.
    const Vec3 d = EnvironmentMap::uv_to_direction(Vec2(3.5 / W, 2.0 / (H - 1)));
    const double expect = 2.0 * RGBIlluminantTable::get().eval(RGB(40, 30, img.at(3, 2, 2)), 600);
    EXPECT_NEAR(env.le_escaped(d, SampledWavelengths::single(600))[0], expect, 1e-9 * expect);
}

TEST(EnvironmentMap, SamplePdfMatchesPdfLi) {
    EnvironmentMap env(test_image(16, 9), 1.5, Transform::rotate(Vec3(1, 1, 0), 35));
    const LightSampleContext ref{Vec3(0.2, 0.3, -0.1), Vec3()};
    PCG32 rng(9, 10);
    int n_ok = 0;
    for (int i = 0; i < 5000; ++i) {
        const double lambda = 380 + 440 * rng.next_double();
        auto ls = env.sample_li(ref, next2(rng), SampledWavelengths::single(lambda));
        if (!ls) continue;
        ++n_ok;
        EXPECT_LT(rel_diff(ls->pdf, env.pdf_li(ref, ls->p, ls->n, ls->wi)), 1e-6);
        EXPECT_LT(rel_diff(ls->Le[0], env.le_escaped(ls->wi, SampledWavelengths::single(lambda))[0]), 1e-6);
        EXPECT_NEAR(length(ls->wi), 1.0, 1e-12);
        EXPECT_EQ(ls->dist, kInfinity);
    }
    // Only the black band (one row of 9) and poles can be empty.
    EXPECT_GT(n_ok, 4000);
}

TEST(EnvironmentMap, PdfIntegratesToOneOverTheSphere) {
    EnvironmentMap env(test_image(16, 9), 1.0, Transform::rotate(Vec3(0, 0, 1), 20));
    // Midpoint rule in (theta, phi) with d(omega) = sin(theta) d(theta) d(phi). The grid is
    // not aligned with the bins, so this checks the 1 / (2 pi^2 sin theta) Jacobian and the
    // rotation, not a tautology; the error is the bin-edge discretisation, O(1/n).
    const int nt = 1000, np = 2000;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) / nt * kPi;
        for (int j = 0; j < np; ++j) {
            const double ph = (j + 0.5) / np * 2 * kPi;
            const Vec3 w(std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t));
            sum += env.pdf_li({}, Vec3(), Vec3(), w) * std::sin(t);
        }
    }
    sum *= (kPi / nt) * (2 * kPi / np);
    EXPECT_NEAR(sum, 1.0, 5e-3);
}

TEST(EnvironmentMap, ConstantExrBehavesLikeConstant) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snell_test_light";
    std::filesystem::create_directories(dir);
    const std::string file = (dir / "const.exr").string();
    Image img;
    img.width = 32;
    img.height = 16;
    img.rgb.assign(size_t(3) * 32 * 16, 0.75f);  // exact in half precision
    write_exr(file, img);

    Props p = make_props("envmap");
    p.set("filename", file, kLoc);
    p.set("scale", 2.0, kLoc);
    auto env = create_light(p);
    ConstantLight ref_light(Spectrum::from_rgb_illuminant(RGB(1.5)));
    PCG32 rng(11, 12);
    for (int i = 0; i < 200; ++i) {
        const Vec3 d = warp::square_to_uniform_sphere(next2(rng));
        const double lambda = 360 + 470 * rng.next_double();
        const SampledWavelengths wl = SampledWavelengths::single(lambda);
        const double a = env->le_escaped(d, wl)[0], b = ref_light.le_escaped(d, wl)[0];
        EXPECT_NEAR(a, b, 1e-12 * b);
    }
    EXPECT_NEAR(env->power(), ref_light.power(), 1e-3 * ref_light.power());
    std::filesystem::remove_all(dir);
}

TEST(EnvironmentMap, FactoryErrors) {
    Props p = make_props("envmap");
    p.set("filename", std::string("/nonexistent/sky.exr"), kLoc);
    EXPECT_THROW(create_light(p), SceneError);
    Props q = make_props("envmap");
    EXPECT_THROW(create_light(q), SceneError);  // filename is required
}

// --- RGB upsampling lattice ------------------------------------------------------------------

TEST(RGBIlluminantTable, ReproducesColourAndWhite) {
    const RGBIlluminantTable& t = RGBIlluminantTable::get();
    const Spectrum white = Spectrum::from_rgb_illuminant(RGB(1.0));
    for (double l = 360; l <= 830; l += 7.3) EXPECT_NEAR(t.eval(RGB(2.5), l), 2.5 * white.eval(l), 1e-12);
    EXPECT_EQ(t.eval(RGB(0.0), 500), 0.0);
    EXPECT_EQ(t.eval(RGB(-1, -2, -3), 500), 0.0);

    auto to_rgb = [&](const RGB& c) {
        Vec3 xyz;
        for (int i = 0; i <= 470; ++i) {
            const double l = 360 + i, w = (i == 0 || i == 470) ? 0.5 : 1.0;
            xyz += cie_xyz(l) * (t.eval(c, l) * w);
        }
        return xyz_to_linear_srgb(xyz / cie_y_integral());
    };
    // The fitted spectra themselves reproduce their RGB to about this accuracy.
    const RGB cols[] = {RGB(0.2, 0.5, 0.9), RGB(3, 1, 0.5), RGB(0.8, 0.8, 0.1), RGB(0.33, 0.9, 0.61)};
    for (const RGB& c : cols) {
        const Vec3 ref = to_rgb(c);
        const Vec3 fit = xyz_to_linear_srgb(spectrum_to_xyz(Spectrum::from_rgb_illuminant(c)));
        const double tol = 0.01 * c.max();
        EXPECT_NEAR(ref.x, c.r, tol);
        EXPECT_NEAR(ref.y, c.g, tol);
        EXPECT_NEAR(ref.z, c.b, tol);
        EXPECT_NEAR(fit.x, c.r, tol);
    }
    // Continuity across the boundary between faces (r max vs g max).
    for (double l = 400; l < 800; l += 50)
        EXPECT_NEAR(t.eval(RGB(1.0, 1.0 - 1e-9, 0.3), l), t.eval(RGB(1.0 - 1e-9, 1.0, 0.3), l), 1e-6);
}
