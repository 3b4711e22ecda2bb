#pragma once
// The MNEE agreement scenes' droplet: a sphere (radius 0.8, centre 0.35 above the plane) sunk
// into a diffuse plane under a large rectangular light, on a 24 x 18 film, so that BSDF sampling
// reaches the light through the sphere often enough for `nee` to converge. The defines
// `integrator` (nee), `radiance` (3), `alpha` and `biased` are left to the caller's load.
#include <string>

namespace snell::test {

inline const char* kDropletScene = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <default name="radiance" value="3"/>
  <default name="alpha" value="0.0"/>
  <default name="biased" value="false"/>
  <integrator type="$integrator"><integer name="max_depth" value="8"/>$extra</integrator>
  <sensor type="perspective">
    <float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 3.2, 3.2" target="0, 0.2, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="18"/></film>
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.7, 0.7"/></bsdf>
  </shape>
  <shape type="sphere">
    <point name="center" x="0" y="0.35" z="0"/><float name="radius" value="0.8"/>
    $droplet_bsdf
  </shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="$light_size"/><rotate x="1" angle="90"/><translate x="-0.8" y="3" z="-0.5"/></transform>
    <emitter type="area"><rgb name="radiance" value="$radiance"/></emitter>
  </shape>
</scene>)";

/// The droplet with the sphere's BSDF, the integrator's extra parameters and the light's scale.
inline std::string droplet_scene(const std::string& droplet_bsdf, const std::string& extra,
                                 const std::string& light_size = "1.5") {
    std::string s = kDropletScene;
    s.replace(s.find("$droplet_bsdf"), 13, droplet_bsdf);
    s.replace(s.find("$extra"), 6, extra);
    s.replace(s.find("$light_size"), 11, light_size);
    return s;
}

}  // namespace snell::test
