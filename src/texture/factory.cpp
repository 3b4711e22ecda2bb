#include "texture/factory.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "io/texture_image.h"
#include "io/volume_grid.h"
#include "texture/bitmap.h"
#include "texture/checkerboard.h"
#include "texture/constant.h"
#include "texture/gridvolume.h"
#include "texture/mesh_attribute.h"

namespace snell {

namespace {

TextureRef make_bitmap(const Props& p) {
    std::filesystem::path file = p.get_string("filename");
    const std::string base = p.get_string("__base_dir", "");
    if (file.is_relative() && !base.empty()) file = std::filesystem::path(base) / file;
    const std::string filter = p.get_string("filter_type", "bilinear");
    BitmapTexture::Filter f;
    if (filter == "bilinear")
        f = BitmapTexture::Filter::Bilinear;
    else if (filter == "nearest")
        f = BitmapTexture::Filter::Nearest;
    else
        p.raise_param("filter_type", "unknown filter_type '" + filter +
                                         "' (expected bilinear or nearest; snell does not MIP-map, see "
                                         "docs/scene-format.md)");
    const std::string wrap = p.get_string("wrap_mode", "repeat");
    BitmapTexture::Wrap w;
    if (wrap == "repeat")
        w = BitmapTexture::Wrap::Repeat;
    else if (wrap == "mirror")
        w = BitmapTexture::Wrap::Mirror;
    else if (wrap == "clamp")
        w = BitmapTexture::Wrap::Clamp;
    else
        p.raise_param("wrap_mode", "unknown wrap_mode '" + wrap + "' (expected repeat, mirror or clamp)");
    const bool raw = p.get_bool("raw", false);
    // Mitsuba's storage precision (auto, variant, fp16): snell keeps texels in float.
    if (p.has("format")) {
        const std::string f = p.get_string("format");
        if (f != "auto" && f != "variant" && f != "fp16")
            p.raise_param("format", "unknown format '" + f + "' (expected auto, variant or fp16)");
    }
    const Transform to_uv = p.get_transform("to_uv");
    TextureImage img;
    try {
        img = read_texture_image(file.string());
    } catch (const std::exception& e) {
        p.raise_param("filename", e.what());
    }
    for (float v : img.texels)
        if (!std::isfinite(v)) p.raise_param("filename", "image '" + file.string() + "' holds NaN or infinite values");
    return std::make_shared<BitmapTexture>(std::move(img), f, w, raw, to_uv);
}

TextureRef make_checkerboard(const Props& p) {
    // Mitsuba's defaults: color0 0.4, color1 0.2.
    auto c0 = get_texture(p, "color0", SpectrumUse::Reflectance, Spectrum::constant(0.4));
    auto c1 = get_texture(p, "color1", SpectrumUse::Reflectance, Spectrum::constant(0.2));
    return std::make_shared<CheckerboardTexture>(c0, c1, p.get_transform("to_uv"));
}

/// Mitsuba's `rawconstant`: a value taken as it is (no spectral upsampling), e.g. the flat normal
/// (0.5, 0.5, 1) of a normal map.
TextureRef make_rawconstant(const Props& p) {
    RGB v(1.0);
    if (p.has("value")) {
        try {
            v = p.get_rgb("value", v);
        } catch (const SceneError&) {  // Mitsuba's test scenes write it as a <vector>
            const Vec3 q = p.get_vec3("value");
            v = RGB(q.x, q.y, q.z);
        }
    }
    return ConstantTexture::make(Spectrum::from_rgb_unbounded(v), v.luminance(), v);
}

/// Mitsuba's `mesh_attribute`: `name` ("vertex_..." or "face_..."), `scale` (1).
TextureRef make_mesh_attribute(const Props& p) {
    const std::string name = p.get_string("name");
    if (name.rfind("vertex_", 0) != 0 && name.rfind("face_", 0) != 0)
        p.raise_param("name", "a mesh attribute's name starts with 'vertex_' or 'face_' (got '" + name + "')");
    const double scale = p.get_float("scale", 1.0);
    if (!std::isfinite(scale) || scale < 0) p.raise_param("scale", "scale must be finite and non-negative");
    return std::make_shared<MeshAttributeTexture>(name, scale);
}

/// Mitsuba's `gridvolume` (a <volume> inside a `volume` texture): filename, filter_type
/// (trilinear, nearest), wrap_mode (clamp, repeat, mirror), raw, to_world, use_grid_bbox.
TextureRef make_gridvolume(const Props& p) {
    std::filesystem::path file = p.get_string("filename");
    const std::string base = p.get_string("__base_dir", "");
    if (file.is_relative() && !base.empty()) file = std::filesystem::path(base) / file;
    const std::string filter = p.get_string("filter_type", "trilinear");
    if (filter != "trilinear" && filter != "nearest")
        p.raise_param("filter_type", "unknown filter_type '" + filter + "' (expected trilinear or nearest)");
    const std::string wrap = p.get_string("wrap_mode", "clamp");
    WrapMode w = WrapMode::Clamp;
    if (wrap == "repeat")
        w = WrapMode::Repeat;
    else if (wrap == "mirror")
        w = WrapMode::Mirror;
    else if (wrap != "clamp")
        p.raise_param("wrap_mode", "unknown wrap_mode '" + wrap + "' (expected clamp, repeat or mirror)");
    const bool raw = p.get_bool("raw", false);
    Transform to_world = p.get_transform("to_world");
    p.mark_used("max_value");  // a majorant for media, meaningless for a texture
    p.mark_used("accel");      // Mitsuba's GPU texture setting
    VolumeGrid grid;
    try {
        grid = read_volume_grid(file.string());
    } catch (const std::exception& e) {
        p.raise_param("filename", e.what());
    }
    if (p.get_bool("use_grid_bbox", false)) {
        // The file's box instead of the unit cube.
        const auto& b = grid.bbox;
        to_world = to_world * Transform::translate(Vec3(b[0], b[1], b[2])) *
                   Transform::scale(Vec3(b[3] - b[0], b[4] - b[1], b[5] - b[2]));
    }
    if (!(std::abs(to_world.det3()) > 0)) p.raise_param("to_world", "to_world must be invertible");
    return std::make_shared<GridVolumeTexture>(std::move(grid), to_world, filter == "nearest", w, raw);
}

/// Mitsuba's `volume` texture: its nested <volume> (gridvolume, constvolume) looked up at the
/// surface point, or a constant `volume` value.
TextureRef make_volume_texture(const Props& p) {
    if (auto v = p.named_child<const Texture>("volume")) return v;
    if (p.has("volume")) return get_texture(p, "volume", SpectrumUse::Reflectance, Spectrum::constant(1.0));
    p.raise("a volume texture needs a nested <volume type=\"gridvolume\"> (or a constant 'volume')");
}

}  // namespace

TextureRef create_texture(const Props& p) {
    TextureRef t;
    if (p.type() == "bitmap")
        t = make_bitmap(p);
    else if (p.type() == "checkerboard")
        t = make_checkerboard(p);
    else if (p.type() == "rawconstant")
        t = make_rawconstant(p);
    else if (p.type() == "mesh_attribute")
        t = make_mesh_attribute(p);
    else if (p.type() == "volume")
        t = make_volume_texture(p);
    else if (p.type() == "gridvolume")
        t = make_gridvolume(p);
    else if (p.type() == "constvolume")
        t = get_texture(p, "value", SpectrumUse::Reflectance, Spectrum::constant(1.0));
    else
        p.raise("unknown " + p.tag() + " type '" + p.type() +
                "' (known: bitmap, checkerboard, rawconstant, mesh_attribute, volume; volumes: gridvolume, "
                "constvolume)");
    p.check_unused();
    return t;
}

TextureRef get_texture(const Props& p, const std::string& name, SpectrumUse use, const Spectrum& def) {
    if (auto t = p.named_child<const Texture>(name)) return t;
    if (!p.has(name)) return ConstantTexture::make(def, spectrum_to_xyz(def).y);
    const bool rgb = p.is_rgb(name);
    const Spectrum s = p.get_spectrum(name, use);
    const double y = spectrum_to_xyz(s).y;
    return ConstantTexture::make(s, y, rgb ? p.get_rgb(name, RGB(y)) : RGB(y));
}

TextureRef get_float_texture(const Props& p, const std::string& name, double def, double lo, double hi) {
    TextureRef child = p.named_child<const Texture>(name);
    TextureRef t = child ? child : ConstantTexture::make(p.get_float(name, def));
    if (!(t->min_value() >= lo && t->max_value() <= hi)) {
        auto num = [](double v) {
            std::ostringstream os;
            os << v;
            return os.str();
        };
        const std::string what =
            "'" + name + "' must lie in [" + num(lo) + ", " + num(hi) + "]" +
            (child ? " everywhere (the texture reaches " + num(t->min_value()) + " .. " + num(t->max_value()) + ")"
                   : "");
        if (child) throw SceneError(p.child_loc(name), p.tag(), what);
        p.raise_param(name, what);
    }
    return t;
}

}  // namespace snell
