#pragma once
// The white furnace shared by the furnace tests: a sphere of white diffuse inside a constant
// white environment. Every path carries the white illuminant exactly, so every pixel must be
// sRGB (1,1,1). Defines: integrator (nee), spectral_samples (4).
namespace snell::test {

inline const char* kFurnace = R"(<scene version="3.0.0">
  <default name="integrator" value="nee"/>
  <default name="spectral_samples" value="4"/>
  <integrator type="$integrator"><integer name="spectral_samples" value="$spectral_samples"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
  </sensor>
  <shape type="sphere"><float name="radius" value="1"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="1, 1, 1"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
</scene>)";

}  // namespace snell::test
