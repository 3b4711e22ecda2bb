#pragma once
// A textured plane seen head-on, for tests that check pixels against the texture where their
// rays hit: textures, normal and bump maps, cameras.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/vector.h"

namespace snell::test {

// The rectangle [-1, 1]^2 (uv = ((x + 1) / 2, (y + 1) / 2)) seen head-on by a 32 x 32 camera
// whose view spans [-0.8, 0.8]^2 of it, under a constant environment of radiance 1 (or
// `emitter`); `reflectance` is the diffuse BSDF's parameter element, or `bsdf` the whole BSDF.
// `sensor` replaces the camera's opening tag and placement (the film stays).
inline std::string plane_scene(const std::string& reflectance, const std::string& integrator = "path",
                               const std::string& bsdf = "", const std::string& emitter = "",
                               const std::string& sensor = "") {
    const double fov = 2 * std::atan(0.8 / 2.0) * 180 / M_PI;
    const std::string pinhole = R"(<sensor type="perspective"><float name="fov" value=")" + std::to_string(fov) +
                                R"("/>
    <transform name="to_world"><lookat origin="0, 0, 2" target="0, 0, 0" up="0, 1, 0"/></transform>)";
    return R"(<scene version="3.0.0">
  <integrator type=")" +
           integrator + R"("/>
  )" + (sensor.empty() ? pinhole : sensor) +
           R"(
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/>
      <rfilter type="box"/></film></sensor>
  )" + (emitter.empty() ? R"(<emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>)" : emitter) +
           R"(
  <shape type="rectangle">)" +
           (bsdf.empty() ? R"(<bsdf type="diffuse">)" + reflectance + "</bsdf>" : bsdf) + R"(</shape>
</scene>)";
}

/// A directional light of irradiance pi arriving from `towards_light` (unnormalised): a diffuse
/// albedo rho then shows rho cos.
inline std::string sun_from(double x, double z) {
    return R"(<emitter type="directional"><vector name="direction" x=")" + std::to_string(-x) + R"(" y="0" z=")" +
           std::to_string(-z) + R"("/><float name="irradiance" value="3.14159265358979"/></emitter>)";
}

/// Mean linear sRGB of the pixels whose whole footprint lies in the uv box [u0, u1] x [v0, v1].
inline Vec3 mean_over(const std::vector<float>& rgb, double u0, double u1, double v0, double v1) {
    Vec3 sum;
    int n = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            // Pixel x spans world [-0.8 + 0.05 x, -0.8 + 0.05 (x + 1)]; row 0 is the top (y = 0.8).
            const double wx0 = -0.8 + 0.05 * x, wy1 = 0.8 - 0.05 * y;
            const double pu0 = (wx0 + 1) / 2, pu1 = (wx0 + 0.05 + 1) / 2;
            const double pv1 = (wy1 + 1) / 2, pv0 = (wy1 - 0.05 + 1) / 2;
            if (pu0 < u0 || pu1 > u1 || pv0 < v0 || pv1 > v1) continue;
            const size_t i = (size_t(y) * 32 + x) * 3;
            sum += Vec3(rgb[i], rgb[i + 1], rgb[i + 2]);
            ++n;
        }
    EXPECT_GT(n, 0);
    return sum / double(std::max(n, 1));
}

// `rel` of the value, plus 0.005 for pure primaries: a smooth spectrum cannot reach exactly 0.
inline void expect_rgb(const Vec3& got, const Vec3& want, double rel, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], rel * want[c] + 5e-3) << what << " channel " << c;
}

}  // namespace snell::test
