// Emitters that read textures (a textured area light, a spot light's projected texture, the
// projector) and textures read from meshes (mesh_attribute): renders against closed-form values,
// agreement of the techniques that reach a textured light at different points, and the loader's
// handling of Mitsuba's file layout (<path> through the main scene's folder, capitalised types).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/spectrum.h"
#include "light/spot.h"
#include "plane_scene.h"
#include "stat/render_stats.h"
#include "texture/checkerboard.h"
#include "texture/constant.h"
#include "texture_files.h"
#include "unit/loader_errors.h"

using namespace snell;
using namespace snell::test;

namespace {

const char* kCheckerRadiance = R"(<texture type="checkerboard" name="radiance">
      <rgb name="color0" value="0.8, 0.2, 0.1"/><rgb name="color1" value="0.3, 0.3, 0.3"/></texture>)";

// The plane of plane_scene() as a light: black, emitting `radiance` (a texture element) towards
// the camera, with nothing else in the scene.
std::string emitting_plane(const std::string& integrator) {
    std::string xml = plane_scene(R"(<rgb name="reflectance" value="0"/>)", integrator, "", " ");
    const std::string shape_end = "</shape>";
    xml.insert(xml.rfind(shape_end), std::string(R"(<emitter type="area">)") + kCheckerRadiance + "</emitter>");
    return xml;
}

/// The colour a texture of colour `rgb` emits (Mitsuba 3 gives a texture in an emitter its own
/// reflectance-like spectrum, not a D65-based one as for an <rgb>): that spectrum's linear sRGB.
Vec3 emission_rgb(const RGB& rgb) { return xyz_to_linear_srgb(spectrum_to_xyz(Spectrum::from_rgb_reflectance(rgb))); }

}  // namespace

// Seen directly, a textured area light shows its texture's spectrum where each camera ray meets
// it, with every integrator (bdpt through its s = 0 strategy, the others through the emitter hit).
TEST(EmitterTextures, TexturedAreaLightShowsItsTexture) {
    for (const char* integ : {"path", "pt", "direct", "bdpt", "mnee"}) {
        SCOPED_TRACE(integ);
        const auto rgb = render_rgb(load_xml(emitting_plane(integ)), 4, 1);
        const Vec3 c0 = emission_rgb(RGB(0.8, 0.2, 0.1)), c1 = emission_rgb(RGB(0.3, 0.3, 0.3));
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.1, 0.5), c0, 0.03, "cell (0, 0)");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.5, 0.9), c0, 0.03, "cell (1, 1)");
        expect_rgb(mean_over(rgb, 0.5, 0.9, 0.1, 0.5), c1, 0.03, "cell (1, 0)");
        expect_rgb(mean_over(rgb, 0.1, 0.5, 0.5, 0.9), c1, 0.03, "cell (0, 1)");
    }
}

// Lit by a textured light, a floor receives the same light whether it is found by emitter
// sampling (which reads the texture at the sampled point's uv) or by BSDF sampling (at the hit's
// uv): `path` (both, MIS) and `pt` (BSDF sampling only) agree per quadrant. Reading the texture
// anywhere else for light samples (uv left at 0: all color0) fails this. The light has a null
// BSDF, so that the camera sees the floor through it.
TEST(EmitterTextures, TexturedAreaLightLightsTheSameWhicheverTechniqueFindsIt) {
    const std::string light = std::string(R"(<shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="180"/><translate z="0.6"/></transform>
        <bsdf type="null"/><emitter type="area">)") +
                              kCheckerRadiance + R"(</emitter></shape>)";  // the camera sees through it
    auto scene = [&](const std::string& integ) {
        return plane_scene(R"(<rgb name="reflectance" value="0.7"/>)", integ, "", light,
                           R"(<sensor type="orthographic"><transform name="to_world"><scale x="0.8" y="0.8"/>
                <lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>)");
    };
    const auto direct = render_rgb(load_xml(scene("path")), 64, 2);
    const auto pt = render_rgb(load_xml(scene("pt")), 256, 3);
    for (auto [u0, v0] : {std::pair{0.1, 0.1}, std::pair{0.5, 0.1}, std::pair{0.1, 0.5}, std::pair{0.5, 0.5}}) {
        const Vec3 a = mean_over(direct, u0, u0 + 0.4, v0, v0 + 0.4), b = mean_over(pt, u0, u0 + 0.4, v0, v0 + 0.4);
        EXPECT_GT(b[0], 0.1);  // lit
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 0.04 * b[c] + 2e-3) << "quadrant " << u0 << ", " << v0;
    }
}

// A projector at distance z in front of a plane lights it with the irradiance pi scale E / z^2
// (Mitsuba 3's normalisation, its references follow it) wherever the image reaches, uniformly:
// the 1 / cos^3 of its intensity cancels the plane's cos / d^2. A diffuse albedo rho then shows
// rho scale E / z^2 inside the image's footprint, |x|, |y| < z tan(fov / 2), and nothing outside.
TEST(EmitterTextures, ProjectorLightsAPlaneUniformlyInsideItsImage) {
    const std::string projector = R"(<emitter type="projector"><float name="fov" value="40"/>
        <float name="scale" value="2"/><rgb name="irradiance" value="1"/>
        <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform></emitter>)";
    const double expected = 0.5 * 2 * 1 / 4.0, edge = 2 * std::tan(20 * M_PI / 180);  // 0.25, 0.728
    for (const char* integ : {"direct", "path", "bdpt", "mnee"}) {
        SCOPED_TRACE(integ);
        const auto rgb =
            render_rgb(load_xml(plane_scene(R"(<rgb name="reflectance" value="0.5"/>)", integ, "", projector)), 4, 4);
        const double in = (1 - edge) / 2 + 0.02;  // uv of the footprint's edge, plus a margin
        expect_rgb(mean_over(rgb, in, 1 - in, in, 1 - in), Vec3(expected), 0.02, "inside");
        expect_rgb(mean_over(rgb, 0.87, 0.91, 0.09, 0.91), Vec3(0.0), 0.0, "outside, right");
        expect_rgb(mean_over(rgb, 0.09, 0.91, 0.09, 0.13), Vec3(0.0), 0.0, "outside, bottom");
    }
}

// A textured projector placed where the camera is projects its image unmirrored into the camera's
// view: texel (u, v) = (0, 0) at the top left (v = 0 is the image's first row), as a camera's
// raster has it. The checkerboard's color0 cells land top left and bottom right.
TEST(EmitterTextures, ProjectedImageIsNotMirrored) {
    const std::string projector = R"(<emitter type="projector"><float name="fov" value="45"/>
        <texture type="checkerboard" name="irradiance"><rgb name="color0" value="0.8, 0.2, 0.1"/>
        <rgb name="color1" value="0.1, 0.2, 0.8"/></texture>
        <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform></emitter>)";
    const auto rgb =
        render_rgb(load_xml(plane_scene(R"(<rgb name="reflectance" value="1"/>)", "direct", "", projector)), 4, 5);
    // Irradiance pi E / 4 on the plane: radiance E / 4 for a white plane.
    const Vec3 c0 = emission_rgb(RGB(0.8, 0.2, 0.1)) / 4, c1 = emission_rgb(RGB(0.1, 0.2, 0.8)) / 4;
    expect_rgb(mean_over(rgb, 0.25, 0.45, 0.55, 0.75), c0, 0.04, "top left");
    expect_rgb(mean_over(rgb, 0.55, 0.75, 0.25, 0.45), c0, 0.04, "bottom right");
    expect_rgb(mean_over(rgb, 0.55, 0.75, 0.55, 0.75), c1, 0.04, "top right");
}

// A spot light's texture spans the cutoff cone's tangent plane: uv = 1/2 + (x, y) / (2 z
// tan(cutoff)) in the light's frame, as Mitsuba 3 maps it; it multiplies the intensity.
TEST(EmitterTextures, SpotTextureFollowsTheBeam) {
    auto c0 = ConstantTexture::make(Spectrum::constant(0.8), 0.8);
    auto c1 = ConstantTexture::make(Spectrum::constant(0.2), 0.2);
    auto checker = std::make_shared<CheckerboardTexture>(c0, c1, Transform());
    const SpotLight spot(Spectrum::constant(3.0), Transform(), 30, 30, checker);
    const SampledWavelengths wl = SampledWavelengths::single(550);
    const double t = 0.4 * std::tan(30 * M_PI / 180);  // inside the cone, off axis in x and y
    EXPECT_NEAR(spot.emitted(Vec3(), Vec3(), Vec2(), normalize(Vec3(t, t, 1)), wl)[0], 3 * 0.8, 1e-12);
    EXPECT_NEAR(spot.emitted(Vec3(), Vec3(), Vec2(), normalize(Vec3(-t, -t, 1)), wl)[0], 3 * 0.8, 1e-12);
    EXPECT_NEAR(spot.emitted(Vec3(), Vec3(), Vec2(), normalize(Vec3(t, -t, 1)), wl)[0], 3 * 0.2, 1e-12);
    EXPECT_NEAR(spot.emitted(Vec3(), Vec3(), Vec2(), normalize(Vec3(-t, t, 1)), wl)[0], 3 * 0.2, 1e-12);
    // The same through sample_li from a point on the beam (intensity / distance^2).
    const auto ls = spot.sample_li({Vec3(-t, t, 1) * 2, Vec3()}, Vec2(), wl);
    ASSERT_TRUE(ls);
    EXPECT_NEAR(ls->Le[0], 3 * 0.2 / length_squared(Vec3(-t, t, 1) * 2), 1e-12);
    // Power for light selection: the texture's mean times the untextured spot's.
    const SpotLight plain(Spectrum::constant(3.0), Transform(), 30, 30);
    EXPECT_NEAR(spot.power(), 0.5 * plain.power(), 1e-12);
}

// mesh_attribute on a PLY square: a per-face weight shows per triangle, an 8-bit vertex colour
// (scaled to [0, 1]) interpolates across it; a missing attribute is a load error naming both the
// texture and the shape, and a name without its vertex_/face_ prefix is refused.
TEST(EmitterTextures, MeshAttributesFromPly) {
    const std::filesystem::path ply = texture_dir() / "square_attrs.ply";
    {
        std::ofstream f(ply);
        f << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
             "property uchar red\nproperty uchar green\nproperty uchar blue\n"
             "element face 2\nproperty list uchar int vertex_indices\nproperty float weight_0\nend_header\n"
             "-1 -1 0 204 102 51\n1 -1 0 51 102 204\n1 1 0 51 102 204\n-1 1 0 204 102 51\n"
             "3 0 1 2 0.25\n3 0 2 3 0.75\n";
    }
    auto scene = [&](const std::string& name) {
        std::string xml = plane_scene("",
                                      "path", R"(<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">
            <string name="name" value=")" + name + R"("/></texture></bsdf>)");
        const std::string rect = R"(<shape type="rectangle">)";
        xml.replace(xml.find(rect), rect.size(),
                    R"(<shape type="ply"><string name="filename" value=")" + ply.string() + R"("/>)");
        return xml;
    };
    // Triangle (0, 1, 2) is below the diagonal y = x, (0, 2, 3) above it.
    const auto w = render_rgb(load_xml(scene("face_weight")), 4, 6);
    expect_rgb(mean_over(w, 0.6, 0.9, 0.1, 0.3), Vec3(0.25), 0.02, "lower triangle");
    expect_rgb(mean_over(w, 0.1, 0.3, 0.6, 0.9), Vec3(0.75), 0.02, "upper triangle");
    const auto c = render_rgb(load_xml(scene("vertex_color")), 32, 7);  // spectral noise: more samples
    const Vec3 left(0.8, 0.4, 0.2), right(0.2, 0.4, 0.8);
    // The two pixel columns at u in [0.1, 0.15] hold on average the blend at u = 0.125.
    expect_rgb(mean_over(c, 0.095, 0.155, 0.2, 0.8), left * 0.875 + right * 0.125, 0.03, "left strip");
    expect_rgb(mean_over(c, 0.845, 0.905, 0.2, 0.8), left * 0.125 + right * 0.875, 0.03, "right strip");
    const std::string err = load_error(scene("vertex_weight"), texture_dir().string());
    EXPECT_NE(err.find("mesh attribute 'vertex_weight' is not on the <shape>"), std::string::npos) << err;
    EXPECT_NE(err.find("it has vertex_color, face_weight"), std::string::npos) << err;
    EXPECT_NE(load_error(scene("color"), texture_dir().string()).find("starts with 'vertex_' or 'face_'"),
              std::string::npos);
}

// Mitsuba's file layout: an included file's <path> is resolved relative to that file, else
// through the earlier <path> folders and the main scene's folder (Mitsuba's documentation scenes
// include "include/x.xml", which names "../../common" relative to the main file). A type written
// with capitals ("Rectangle") is read in lower case with a notice; hdrfilm's file_format is
// accepted.
TEST(EmitterTextures, MitsubaFileLayout) {
    namespace fs = std::filesystem;
    const fs::path root = texture_dir() / "layout";
    fs::create_directories(root / "scenes" / "include");
    fs::create_directories(root / "common");
    std::ofstream(root / "scenes" / "include" / "inc.xml")
        << R"(<scene version="3.0.0"><path value="../common"/></scene>)";
    const std::string xml = R"(<scene version="3.0.0"><include filename="include/inc.xml"/>
        <sensor type="perspective"><float name="fov" value="30"/>
        <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/>
        <string name="file_format" value="openexr"/></film></sensor>
        <shape type="Rectangle"/></scene>)";
    // "../common" does not exist next to include/inc.xml (that would be scenes/common); relative
    // to the main scene's folder, scenes/, it is root/common.
    const LoadedScene ls = load_scene_string(xml, "main.xml", (root / "scenes").string());
    bool noted = false;
    for (const auto& n : ls.notices)
        noted = noted || n.find("type=\"Rectangle\"> read as 'rectangle'") != std::string::npos;
    EXPECT_TRUE(noted);
    expect_load_error(R"(<scene version="3.0.0"><path value="nowhere"/></scene>)", root.string(), "test.xml:1: <path>",
                      "no such folder 'nowhere'");
}

// A `volume` texture reads its grid at the surface point in world space: a 2 x 1 x 1 grid placed
// over the plane shows its two voxels on the two halves (nearest), and their blend along x
// (trilinear, clamped beyond the outer voxel centres). A missing or damaged .vol file, and a
// volume texture without its grid, are errors naming the element.
TEST(EmitterTextures, VolumeTextureFromAGrid) {
    const std::filesystem::path vol = texture_dir() / "two.vol";
    {
        std::ofstream f(vol, std::ios::binary);
        const char magic[4] = {'V', 'O', 'L', 3};
        const int32_t head[5] = {1, 2, 1, 1, 1};
        const float bbox[6] = {0, 0, 0, 1, 1, 1}, data[2] = {0.2f, 0.8f};
        f.write(magic, 4);
        f.write(reinterpret_cast<const char*>(head), sizeof(head));
        f.write(reinterpret_cast<const char*>(bbox), sizeof(bbox));
        f.write(reinterpret_cast<const char*>(data), sizeof(data));
    }
    auto scene = [&](const std::string& filter, const std::string& file) {
        return plane_scene(R"(<texture type="volume" name="reflectance"><volume type="gridvolume" name="volume">
            <string name="filename" value=")" +
                           file + R"("/><string name="filter_type" value=")" + filter +
                           R"("/><transform name="to_world"><translate value="-0.5, -0.5, -0.5"/>
            <scale value="2"/></transform></volume></texture>)");
    };
    const auto n = render_rgb(load_xml(scene("nearest", vol.string())), 4, 8);
    expect_rgb(mean_over(n, 0.1, 0.45, 0.1, 0.9), Vec3(0.2), 0.02, "left voxel");
    expect_rgb(mean_over(n, 0.55, 0.9, 0.1, 0.9), Vec3(0.8), 0.02, "right voxel");
    const auto t = render_rgb(load_xml(scene("trilinear", vol.string())), 4, 9);
    // Voxel centres at x = -0.5 and 0.5 (u = 0.25, 0.75): a linear blend between, clamped outside.
    expect_rgb(mean_over(t, 0.1, 0.2, 0.1, 0.9), Vec3(0.2), 0.02, "clamped left");
    expect_rgb(mean_over(t, 0.45, 0.55, 0.1, 0.9), Vec3(0.5), 0.02, "middle");
    std::ofstream(texture_dir() / "bad.vol") << "VOX";
    for (const std::string& bad : {(texture_dir() / "bad.vol").string(), (texture_dir() / "none.vol").string()}) {
        const std::string err = load_error(scene("nearest", bad), texture_dir().string());
        EXPECT_NE(err.find("<volume>"), std::string::npos) << err;
        EXPECT_NE(err.find(bad), std::string::npos) << err;
    }
    EXPECT_NE(load_error(plane_scene(R"(<texture type="volume" name="reflectance"/>)"), texture_dir().string())
                  .find("needs a nested <volume"),
              std::string::npos);
}

// Bad input to the new plugins names file:line, the element and what is wrong.
TEST(EmitterTextures, BadInputNamesTheElement) {
    const std::string dir = texture_dir().string();
    auto scene = [](const std::string& body) {
        return std::string(R"(<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="30"/></sensor>
)") + body + "\n</scene>";
    };
    expect_load_error(scene(R"(<emitter type="projector"><float name="fov" value="190"/></emitter>)"), dir,
                      "test.xml:2: <emitter>", "fov must lie in (0, 180)");
    expect_load_error(scene(R"(<emitter type="projector"><float name="scale" value="-1"/></emitter>)"), dir,
                      "test.xml:2: <emitter>", "scale must be finite and non-negative");
    expect_load_error(scene(R"(<emitter type="spot"><rgb name="texture" value="0.5"/></emitter>)"), dir,
                      "test.xml:2: <emitter>", "must be a <texture>");
    expect_load_error(
        scene(
            R"(<shape type="sphere"><bsdf type="principledthin"><float name="diff_trans" value="2.5"/></bsdf></shape>)"),
        dir, "test.xml:2: <bsdf>", "'diff_trans' must lie in [0, 2]");
    expect_load_error(scene(R"(<shape type="sphere"><bsdf type="principledthin"><float name="spec_trans" value="0.5"/>
        <float name="specular_transmittance_sampling_rate" value="-1"/></bsdf></shape>)"),
                      dir, "test.xml:3: <bsdf>", "must be >= 0");
}
