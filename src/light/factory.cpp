// Emitter factory: reads every parameter of the Mitsuba 3 emitters snell supports and reports
// anything it did not understand with its file:line (Props::check_unused).
#include "light/factory.h"

#include <filesystem>
#include <stdexcept>

#include "camera/field_of_view.h"
#include "io/image.h"
#include "light/area.h"
#include "light/constant.h"
#include "light/directional.h"
#include "light/envmap.h"
#include "light/point.h"
#include "light/projector.h"
#include "light/spot.h"

namespace snell {

namespace {

// Mitsuba's default emission: the white illuminant at unit strength.
Spectrum default_white() { return Spectrum::from_rgb_illuminant(RGB(1.0)); }

Spectrum emission(const Props& props, const char* name) {
    return props.get_spectrum(name, SpectrumUse::Illuminant, default_white());
}

// Mitsuba accepts either an explicit position/direction or a to_world transform, not both.
void exclusive(const Props& props, const char* a, const char* b) {
    if (props.has(a) && props.has(b))
        props.raise_param(a, std::string("give either '") + a + "' or '" + b + "', not both");
}

std::shared_ptr<Light> make_point(const Props& props) {
    exclusive(props, "position", "to_world");
    const Spectrum intensity = emission(props, "intensity");
    Vec3 pos;
    if (props.has("position"))
        pos = props.get_vec3("position");
    else
        pos = props.get_transform("to_world").point(Vec3(0, 0, 0));
    return std::make_shared<PointLight>(intensity, pos);
}

std::shared_ptr<Light> make_spot(const Props& props) {
    const Spectrum intensity = emission(props, "intensity");
    const Transform to_world = props.get_transform("to_world");
    const double cutoff = props.get_float("cutoff_angle", 20.0);
    const double beam = props.get_float("beam_width", cutoff * 0.75);
    if (!(cutoff > 0 && cutoff <= 180)) props.raise_param("cutoff_angle", "cutoff_angle must lie in (0, 180] degrees");
    if (!(beam >= 0 && beam <= cutoff))
        props.raise_param("beam_width", "beam_width must lie in [0, cutoff_angle] degrees");
    // Mitsuba 3: the projected texture multiplies the intensity; it must vary over the image.
    TextureRef texture = props.named_child<const Texture>("texture");
    if (!texture && props.has("texture"))
        props.raise_param("texture", "a spot light's 'texture' must be a <texture> (a colour belongs in 'intensity')");
    return std::make_shared<SpotLight>(intensity, to_world, cutoff, beam, std::move(texture));
}

std::shared_ptr<Light> make_projector(const Props& props) {
    TextureRef texture = props.named_child<const Texture>("irradiance");
    const Spectrum irradiance = texture ? default_white() : emission(props, "irradiance");
    const double scale = props.get_float("scale", 1.0);
    if (!std::isfinite(scale) || scale < 0) props.raise_param("scale", "scale must be finite and non-negative");
    const auto [w, h] = texture ? texture->resolution() : std::pair<int, int>(1, 1);
    const Vec2 tan_half = fov_tangents(read_field_of_view(props), double(w) / double(h));
    return std::make_shared<ProjectorLight>(irradiance, std::move(texture), scale, props.get_transform("to_world"),
                                            tan_half);
}

std::shared_ptr<Light> make_directional(const Props& props) {
    exclusive(props, "direction", "to_world");
    const Spectrum irradiance = emission(props, "irradiance");
    Vec3 dir;
    if (props.has("direction"))
        dir = props.get_vec3("direction");
    else
        dir = props.get_transform("to_world").vector(Vec3(0, 0, 1));
    if (!(length(dir) > 0) || !is_finite(dir)) props.raise_param("direction", "direction must be a non-zero vector");
    return std::make_shared<DirectionalLight>(irradiance, dir);
}

std::shared_ptr<Light> make_envmap(const Props& props) {
    std::filesystem::path file = props.get_string("filename");
    const std::string base = props.get_string("__base_dir", "");
    if (file.is_relative() && !base.empty()) file = std::filesystem::path(base) / file;
    const double scale = props.get_float("scale", 1.0);
    const Transform to_world = props.get_transform("to_world");
    if (!std::isfinite(scale) || scale < 0) props.raise_param("scale", "scale must be finite and non-negative");
    Image img;
    try {
        img = read_image(file.string());
    } catch (const std::exception& e) {
        props.raise_param("filename", e.what());
    }
    try {
        return std::make_shared<EnvironmentMap>(std::move(img), scale, to_world);
    } catch (const std::invalid_argument& e) {
        props.raise_param("filename", file.string() + ": " + e.what());
    }
}

}  // namespace

std::shared_ptr<Light> create_light(const Props& props) {
    const std::string& t = props.type();
    std::shared_ptr<Light> light;
    if (t == "point")
        light = make_point(props);
    else if (t == "spot")
        light = make_spot(props);
    else if (t == "projector")
        light = make_projector(props);
    else if (t == "directional")
        light = make_directional(props);
    else if (t == "constant")
        light = std::make_shared<ConstantLight>(emission(props, "radiance"));
    else if (t == "envmap")
        light = make_envmap(props);
    else if (t == "area")
        props.raise("an area emitter must be nested inside a shape");
    else
        props.raise("unknown emitter type '" + t +
                    "' (known: point, spot, projector, directional, constant, envmap, area)");
    props.check_unused();
    light->set_id(props.id());
    return light;
}

std::shared_ptr<Light> create_area_light(const Props& props, const std::shared_ptr<Shape>& shape) {
    if (props.type() != "area")
        props.raise("only emitters of type 'area' can be nested in a shape, got '" + props.type() + "'");
    if (!shape) props.raise("area emitter without a shape");
    // A textured radiance reads the shape's uv (Mitsuba 3 gives it no D65 white point).
    TextureRef texture = props.named_child<const Texture>("radiance");
    auto light = texture ? std::make_shared<AreaLight>(std::move(texture), shape)
                         : std::make_shared<AreaLight>(emission(props, "radiance"), shape);
    props.check_unused();
    light->set_id(props.id());
    shape->set_emitter(light.get());
    return light;
}

}  // namespace snell
