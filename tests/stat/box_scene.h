#pragma once
// The Cornell-box-like scene shared by the integrator agreement tests (path/nee, bdpt,
// pssmlt): a large area light, diffuse walls, a rough conductor sphere and a rough glass
// sphere, so that every BSDF family lies on some path and every estimator converges.
// Defaults that tests override with -D: integrator, radiance (the light's), light_scale (the
// light's size; shrinking it at constant radiance dims it), res (film width and height).

namespace snell::test {

inline const char* kCornellBox = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <default name="radiance" value="6"/>
  <default name="light_scale" value="0.5"/>
  <default name="res" value="32"/>
  <integrator type="$integrator"><integer name="max_depth" value="6"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0, 1, 3.4" target="0, 1, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film>
  </sensor>
  <bsdf type="diffuse" id="white"><rgb name="reflectance" value="0.7, 0.7, 0.7"/></bsdf>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><translate z="-1"/><translate y="1"/></transform><ref id="white"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="90"/><translate x="-1" y="1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.1, 0.1"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><rotate y="1" angle="-90"/><translate x="1" y="1"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.6, 0.1"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform><ref id="white"/></shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="$light_scale"/><rotate x="1" angle="90"/><translate y="1.99"/></transform>
    <emitter type="area"><rgb name="radiance" value="$radiance"/></emitter>
  </shape>
  <shape type="sphere"><point name="center" x="-0.45" y="0.35" z="-0.2"/><float name="radius" value="0.35"/>
    <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="0.45" y="0.35" z="0.2"/><float name="radius" value="0.35"/>
    <bsdf type="roughdielectric"><float name="alpha" value="0.3"/><float name="int_ior" value="1.5"/></bsdf></shape>
</scene>)";

}  // namespace snell::test
