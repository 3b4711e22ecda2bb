// Sensors in renders, against what the plane they look at must show: an orthographic camera
// sees the checkerboard cells at exactly their places; a thin lens focused on the plane sees
// what the pinhole sees, and focused elsewhere blurs each point over a disk of the predicted
// radius; bdpt refuses sensors it cannot connect light paths to.
#include <gtest/gtest.h>

#include <cmath>

#include "stat/render_stats.h"
#include "texture/plane_scene.h"
#include "unit/loader_errors.h"

using namespace snell;
using namespace snell::test;

namespace {

const char* kChecker = R"(<texture type="checkerboard" name="reflectance">
      <float name="color0" value="0.8"/><float name="color1" value="0.2"/></texture>)";

std::string thinlens(double aperture, double focus) {
    const double fov = 2 * std::atan(0.8 / 2.0) * 180 / M_PI;
    return R"(<sensor type="thinlens"><float name="fov" value=")" + std::to_string(fov) +
           R"("/><float name="aperture_radius" value=")" + std::to_string(aperture) +
           R"("/><float name="focus_distance" value=")" + std::to_string(focus) + R"("/>
    <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>)";
}

/// Fraction of a disk of radius r centred at signed distance x from a straight edge that lies
/// beyond the edge.
double beyond(double x, double r) {
    const double t = std::clamp(x / r, -1.0, 1.0);
    return (std::acos(t) - t * std::sqrt(1 - t * t)) / M_PI;
}

}  // namespace

TEST(Cameras, OrthographicSeesTheCellsWhereTheyAre) {
    // Mitsuba's window [-1, 1]^2 (square film) scaled by 0.8: the same [-0.8, 0.8]^2 of the plane.
    const std::string ortho = R"(<sensor type="orthographic">
    <transform name="to_world"><scale x="0.8" y="0.8"/><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>)";
    const auto rgb = render_rgb(load_xml(plane_scene(kChecker, "path", "", "", ortho)), 16, 1);
    // Every pixel lies inside one cell (pixel edges fall on the cell edges at x = 0, y = 0), so
    // none may show the other cell's value, and the cells' means are their values.
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool right = x >= 16, top = y < 16;
            const double want = right == top ? 0.8 : 0.2;  // u, v both high or both low: color0
            EXPECT_NEAR(rgb[(size_t(y) * 32 + x) * 3 + 1], want, 0.25) << x << "," << y;
        }
    expect_rgb(mean_over(rgb, 0.1, 0.5, 0.1, 0.5), Vec3(0.8, 0.8, 0.8), 0.02, "cell (0, 0)");
    expect_rgb(mean_over(rgb, 0.5, 0.9, 0.1, 0.5), Vec3(0.2, 0.2, 0.2), 0.02, "cell (1, 0)");
    expect_rgb(mean_over(rgb, 0.5, 0.9, 0.5, 0.9), Vec3(0.8, 0.8, 0.8), 0.02, "cell (1, 1)");
}

TEST(Cameras, ThinLensFocusedOnThePlaneMatchesThePinhole) {
    // `pt` on a diffuse plane under a constant environment: every sample is exactly the albedo
    // where the camera ray hits, so pixels differ only where they straddle a cell edge.
    const auto pin = render_rgb(load_xml(plane_scene(kChecker, "pt")), 64, 1);
    const auto lens = render_rgb(load_xml(plane_scene(kChecker, "pt", "", "", thinlens(0.3, 2.0))), 64, 1);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const size_t i = (size_t(y) * 32 + x) * 3 + 1;
            const bool edge = x == 15 || x == 16 || y == 15 || y == 16;
            EXPECT_NEAR(lens[i], pin[i], edge ? 0.2 : 1e-5) << x << "," << y;
        }
}

// Focused at 1 with the plane at 2, the rays of a pixel spread over a disk of radius
// aperture * (2 - 1) / 1 around the pinhole's point: next to the edge x = 0 the pixel's green is
// 0.2 + 0.6 (1 - beyond), averaged over the pixel's width (0.05 on the plane).
TEST(Cameras, ThinLensBlursOverThePredictedDisk) {
    const double r = 0.2;
    // `pt`: each sample is the albedo where its ray lands (see above); only the lens and pixel
    // positions are random: at 1024 spp the standard error is below 0.01.
    const auto rgb = render_rgb(load_xml(plane_scene(kChecker, "pt", "", "", thinlens(r, 1.0))), 1024, 1);
    // Row 4 (plane y = 0.575 .. 0.6, top half: cells color1 left of x = 0, color0 right).
    const int row = 4;
    for (int x = 10; x < 22; ++x) {
        double want = 0;
        const int n = 200;
        for (int k = 0; k < n; ++k) {
            const double px = -0.8 + 0.05 * (x + (k + 0.5) / n);  // plane x under the pixel
            want += 0.2 + 0.6 * (1 - beyond(px, r));              // share of the disk right of the edge
        }
        want /= n;  // (the other edge, y = 0, is 0.575 away: beyond every disk of this row)
        EXPECT_NEAR(rgb[(size_t(row) * 32 + x) * 3 + 1], want, 0.03) << "pixel " << x;
    }
}

TEST(Cameras, BdptRefusesSensorsWithoutAPinhole) {
    expect_load_error(plane_scene(kChecker, "bdpt", "", "", thinlens(0.1, 2.0)), ".", "test.xml:3: <sensor>",
                      "bdpt connects light paths to the camera and needs a perspective (pinhole) sensor");
    expect_load_error(
        plane_scene(kChecker, "path", "", "", R"(<sensor type="thinlens"><float name="focus_distance" value="1"/>)"),
        ".", "test.xml:3: <sensor>", "aperture_radius");
}
