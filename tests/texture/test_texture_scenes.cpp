// Textures in scenes: the loader (nested, referenced and Mitsuba 2's <spectrum type=...> forms,
// and bad input), and renders checked against values known in closed form. A one-sided diffuse
// plane under a constant environment of radiance 1 reflects exactly its albedo, so every pixel
// shows the texture's colour where its ray hits; every integrator must agree on that.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bsdf/bsdf.h"
#include "core/stats.h"
#include "plane_scene.h"
#include "stat/render_stats.h"
#include "texture/bitmap.h"
#include "texture_files.h"
#include "unit/loader_errors.h"

using namespace snell;
using namespace snell::test;

namespace {

const char* kChecker = R"(<texture type="checkerboard" name="reflectance">
      <rgb name="color0" value="0.8, 0.2, 0.1"/><rgb name="color1" value="0.3, 0.3, 0.3"/></texture>)";

}  // namespace

// Every integrator reads the checkerboard where its paths hit: cell colours within 3 %, and no
// BSDF is ever evaluated without its surface point.
TEST(TextureScenes, CheckerboardPlaneEveryIntegrator) {
    for (const char* integ : {"path", "pt", "direct", "bdpt", "mnee"}) {
        SCOPED_TRACE(integ);
        reset_stats();
        const auto rgb = render_rgb(load_xml(plane_scene(kChecker, integ)), 16, 3);
        EXPECT_EQ(stat_totals().get("bsdf.lookups_without_point"), 0u);
        const Vec3 c0(0.8, 0.2, 0.1), c1(0.3, 0.3, 0.3);
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.1, 0.5), c0, 0.03, "cell (0, 0)");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.5, 0.9), c0, 0.03, "cell (1, 1)");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.1, 0.5), c1, 0.03, "cell (1, 0)");
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.5, 0.9), c1, 0.03, "cell (0, 1)");
    }
}

// A 2 x 2 sRGB PNG read nearest: each quadrant of the plane shows its texel, decoded, with the
// image's first row at v = 0 (Mitsuba 3), and the same through a referenced top-level texture
// and Mitsuba 2's <spectrum type="bitmap"> spelling.
TEST(TextureScenes, BitmapPlaneShowsItsTexels) {
    const std::vector<uint8_t> px = {255, 0, 0,   0,   255, 0,  // top row: red, green
                                     0,   0, 255, 128, 128, 128};
    write_texture("quad.png", 2, 2, 3, px);
    const std::string dir = texture_dir().string();
    const std::string nested =
        R"(<texture type="bitmap" name="reflectance"><string name="filename" value="quad.png"/>
           <string name="filter_type" value="nearest"/></texture>)";
    const std::string spectrum_form =
        R"(<spectrum type="bitmap" name="reflectance"><string name="filename" value="quad.png"/>
           <string name="filter_type" value="nearest"/></spectrum>)";
    const double grey = srgb_to_linear(128.0 / 255);
    for (const std::string& form : {nested, spectrum_form}) {
        const auto ls = load_scene_string(plane_scene(form), "t.xml", dir);
        const auto rgb = render_rgb(ls, 16, 1);
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.1, 0.5), Vec3(1, 0, 0), 0.03, "v < 1/2, u < 1/2: red");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.1, 0.5), Vec3(0, 1, 0), 0.03, "green");
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.5, 0.9), Vec3(0, 0, 1), 0.03, "blue");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.5, 0.9), Vec3(grey, grey, grey), 0.03, "grey");
    }
}

TEST(TextureScenes, TopLevelTextureByReference) {
    const std::string xml = R"(<scene version="3.0.0">
  <texture type="checkerboard" id="checks"><float name="color0" value="0.9"/><float name="color1" value="0.1"/></texture>
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <shape type="sphere"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf></shape>
  <shape type="sphere"><transform name="to_world"><translate x="3"/></transform>
    <bsdf type="roughconductor"><ref name="alpha" id="checks"/></bsdf></shape>
  <shape type="sphere"><transform name="to_world"><translate x="6"/></transform>
    <bsdf type="principled"><ref name="base_color" id="checks"/><ref name="roughness" id="checks"/>
      <float name="spec_trans" value="0.5"/><float name="clearcoat" value="0.2"/></bsdf></shape>
</scene>)";
    EXPECT_EQ(load_error(xml, "."), "");
}

TEST(TextureScenes, BadInputNamesFileLineAndElement) {
    const std::string dir = texture_dir().string();
    auto scene_with = [](const std::string& bsdf) {
        return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"sphere\">\n" + bsdf +
               "\n</shape>\n</scene>";
    };
    expect_load_error(scene_with(R"(<bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="missing.png"/></texture></bsdf>)"),
                      dir, "test.xml:5: <texture>", "missing.png");
    expect_load_error(scene_with(R"(<bsdf type="diffuse"><texture type="wood" name="reflectance"/></bsdf>)"), dir,
                      "test.xml:4: <texture>",
                      "unknown texture type 'wood' (known: bitmap, checkerboard, rawconstant, mesh_attribute");
    write_texture("quad.png", 2, 2, 3, std::vector<uint8_t>(12, 7));
    expect_load_error(scene_with(R"(<bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="quad.png"/><string name="filter_type" value="ewa"/></texture></bsdf>)"),
                      dir, "test.xml:5: <texture>", "unknown filter_type 'ewa'");
    expect_load_error(scene_with(R"(<bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="quad.png"/><string name="wrap_mode" value="zigzag"/></texture></bsdf>)"),
                      dir, "test.xml:5: <texture>", "unknown wrap_mode 'zigzag'");
    // Mitsuba's roughplastic takes a constant alpha only.
    expect_load_error(scene_with(R"(<bsdf type="roughplastic"><texture type="checkerboard" name="alpha"/></bsdf>)"),
                      dir, "test.xml:4: <bsdf>", "nested object 'alpha'");
    // A blend weight must stay in [0, 1] everywhere.
    expect_load_error(scene_with(R"(<bsdf type="blendbsdf"><texture type="checkerboard" name="weight">
        <float name="color0" value="2"/></texture><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>)"),
                      dir, "test.xml:4: <bsdf>", "'weight' must lie in [0, 1] everywhere");
    // A texture where only objects of other kinds may be nested.
    expect_load_error(
        R"(<scene version="3.0.0"><sensor type="perspective"><texture type="checkerboard"/></sensor></scene>)", dir,
        "test.xml:1: <texture>", "cannot be nested inside <sensor>");
}

// A normal-mapped plane under a directional light of irradiance pi from l = (-1, 0, 1) / sqrt 2:
// a diffuse BSDF of albedo 0.5 in the perturbed frame shows 0.5 cos(l, n') (Mitsuba's and
// pbrt's convention: the cosine is the perturbed normal's), times Mitsuba 3's shadowing term
// G = 2 / (1 + sqrt(1 + a^2 tan^2 theta_l)), a^2 = tan^2 theta_n' / 8, unless
// use_shadowing_function is false. The map is a checkerboard of two normals, n' tilted 30 degrees
// towards -x (cos = cos 15 deg) and the surface's own (cos 45 deg, G = 1).
TEST(TextureScenes, NormalMappedPlaneIrradiance) {
    const double s30 = std::sin(M_PI / 6), c30 = std::cos(M_PI / 6);
    char colour[96];
    std::snprintf(colour, sizeof colour, "%.9f, 0.5, %.9f", 0.5 * (1 - s30), 0.5 * (1 + c30));
    for (bool shadowing : {true, false}) {
        SCOPED_TRACE(shadowing);
        const std::string bsdf_open =
            std::string(R"(<bsdf type="normalmap"><boolean name="use_shadowing_function" value=")") +
            (shadowing ? "true" : "false") + R"("/>
      <texture type="checkerboard" name="normalmap"><rgb name="color0" value=")" +
            colour + R"("/><rgb name="color1" value="0.5, 0.5, 1"/></texture>
      <bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></bsdf>)";
        const std::string xml = plane_scene("", "direct", bsdf_open, sun_from(-1, 1));
        const auto rgb = render_rgb(load_xml(xml), 4, 2);
        const double a2 = std::tan(M_PI / 6) * std::tan(M_PI / 6) / 8, tan2_l = 1.0;
        const double G = shadowing ? 2 / (1 + std::sqrt(1 + a2 * tan2_l)) : 1.0;
        const double tilted = 0.5 * std::cos(M_PI / 12) * G, flat = 0.5 * std::cos(M_PI / 4);
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.1, 0.5), Vec3(tilted, tilted, tilted), 0.005, "tilted cell (0, 0)");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.1, 0.5), Vec3(flat, flat, flat), 0.005, "flat cell (1, 0)");
    }
}

// A bump map whose height is u (a 2 x 1 linear EXR, values 0 and 1, read bilinearly with clamp):
// between the texel centres (u in [1/4, 3/4]) dh/du = 2, so with scale s the perturbed tangent is
// dp/du + n 2 s = (2, 0, 2 s) and n' = (-s, 0, 1) / sqrt(1 + s^2); outside, the height is flat.
// s = tan 30 deg tilts n' by 30 degrees towards -x: under the light from (1, 0, 1) / sqrt 2 the
// middle shows 0.5 cos 75 deg times the shadowing term (as for the normal map) and the flat edges
// 0.5 cos 45 deg.
TEST(TextureScenes, BumpMappedPlaneIrradiance) {
    write_texture("ramp.exr", 2, 1, 1, std::vector<float>{0.0f, 1.0f});
    const std::string dir = texture_dir().string();
    char bsdf[512];
    std::snprintf(bsdf, sizeof bsdf, R"(<bsdf type="bumpmap"><float name="scale" value="%.12f"/>
      <texture type="bitmap" name="height"><string name="filename" value="ramp.exr"/>
        <string name="wrap_mode" value="clamp"/></texture>
      <bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></bsdf>)",
                  std::tan(M_PI / 6));
    const std::string xml = plane_scene("", "direct", bsdf, sun_from(1, 1));
    const auto rgb = render_rgb(load_scene_string(xml, "t.xml", dir), 4, 2);
    const double a2 = std::tan(M_PI / 6) * std::tan(M_PI / 6) / 8;
    const double middle = 0.5 * std::cos(5 * M_PI / 12) * 2 / (1 + std::sqrt(1 + a2)), edge = 0.5 * std::cos(M_PI / 4);
    expect_rgb(mean_over(rgb, 0.3, 0.7, 0.1, 0.9), Vec3(middle, middle, middle), 0.01, "sloped middle");
    expect_rgb(mean_over(rgb, 0.1, 0.2, 0.1, 0.9), Vec3(edge, edge, edge), 0.01, "flat edge");
}

// A plane seen along its normal (orthographic) under a constant environment of radiance 1 shows
// its BSDF's directional albedo at normal incidence, which a quadrature of eval() alone computes,
// independently of the BSDF's sampling and of the integrator: for principled (its base colour a
// checkerboard of two greys, both cells checked), roughplastic, blendbsdf, roughconductor, and
// principledthin with its transmission lobes (the environment behind the plane shows through:
// the quadrature covers the sphere).
TEST(TextureScenes, PlanesShowTheirAlbedo) {
    const std::string ortho = R"(<sensor type="orthographic">
    <transform name="to_world"><scale x="0.8" y="0.8"/><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>)";
    const std::string principled = R"(<float name="roughness" value="0.4"/><float name="metallic" value="0.2"/>
      <float name="sheen" value="0.5"/><float name="clearcoat" value="0.5"/><float name="spec_tint" value="0.3"/>)";
    struct Case {
        std::string name, bsdf;  // the plane's BSDF; `$c` is the grey of the checked cell
        bool checker;
        bool transmits = false;  // the environment behind the plane shows through: integrate over the sphere
    };
    const std::vector<Case> cases = {
        {"principled", R"(<bsdf type="principled"><float name="base_color" value="$c"/>)" + principled + "</bsdf>",
         true},
        {"roughplastic", R"(<bsdf type="roughplastic"><float name="diffuse_reflectance" value="$c"/>
           <float name="alpha" value="0.3"/></bsdf>)",
         false},
        {"blendbsdf", R"(<bsdf type="blendbsdf"><float name="weight" value="0.35"/>
           <bsdf type="diffuse"><float name="reflectance" value="$c"/></bsdf>
           <bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></bsdf>)",
         false},
        {"roughconductor", R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/>
           <float name="alpha" value="0.25"/><float name="specular_reflectance" value="$c"/></bsdf>)",
         false},
        {"principledthin", R"(<bsdf type="principledthin"><float name="base_color" value="$c"/>
           <float name="roughness" value="0.4"/><float name="spec_trans" value="0.4"/>
           <float name="diff_trans" value="0.6"/><float name="sheen" value="0.3"/><float name="eta" value="1.4"/></bsdf>)",
         false, true},
    };
    auto with_grey = [](std::string xml, double grey) {
        xml.replace(xml.find("$c"), 2, std::to_string(grey));
        return xml;
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        std::string shown = with_grey(c.bsdf, 0.8);
        if (c.checker) {
            const std::string tex = R"(<texture type="checkerboard" name="base_color">
      <float name="color0" value="0.8"/><float name="color1" value="0.3"/></texture>)";
            shown = R"(<bsdf type="principled">)" + tex + principled + "</bsdf>";
        }
        const auto rgb = render_rgb(load_xml(plane_scene("", "path", shown, "", ortho)), 64, 4);
        for (double grey : c.checker ? std::vector<double>{0.8, 0.3} : std::vector<double>{0.8}) {
            const auto one = load_xml(plane_scene("", "path", with_grey(c.bsdf, grey), "", ortho));
            const BSDF& b = *one.scene->shapes()[0]->bsdf();
            // 2 pi int f(z, wi(theta)) cos sin dtheta: isotropic, so f depends on theta alone.
            const int n = 20000;
            Vec3 albedo;
            BSDFContext ctx;
            ctx.wl = SampledWavelengths::single(550);
            const double range = c.transmits ? M_PI : M_PI / 2;
            for (int k = 0; k < n; ++k) {
                const double th = (k + 0.5) / n * range;
                albedo += Vec3(1, 1, 1) * (b.eval(ctx, Vec3(0, 0, 1), Vec3(std::sin(th), 0, std::cos(th)))[0] *
                                           std::abs(std::cos(th)) * std::sin(th));
            }
            albedo = albedo * (2 * M_PI * range / n);
            const Vec3 got = grey == 0.8 ? mean_over(rgb, 0.1, 0.5, 0.1, 0.5) : mean_over(rgb, 0.5, 0.9, 0.1, 0.5);
            expect_rgb(got, albedo, 0.02, c.name + " albedo " + std::to_string(grey));
        }
    }
}
