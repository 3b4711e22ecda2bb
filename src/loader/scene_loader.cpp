// Stage 2 of scene loading: instantiate the parsed XML (loader/xml_scene.h) through the plugin
// factories. Every Props is checked for unused entries after its factory ran, so a parameter no
// plugin understood is always an error with its file:line. The syntax is in docs/scene-format.md.
#include "loader/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "bsdf/factory.h"
#include "camera/factory.h"
#include "camera/field_of_view.h"
#include "camera/orthographic.h"
#include "camera/thinlens.h"
#include "geometry/instance.h"
#include "integrators/integrator.h"
#include "light/factory.h"
#include "loader/mitsuba_integrators.h"
#include "loader/shape_factory.h"
#include "loader/unsupported.h"
#include "loader/xml_scene.h"
#include "texture/factory.h"
#include "texture/mesh_attribute.h"

namespace snell {

namespace {

namespace fs = std::filesystem;

/// Runs a factory; non-scene exceptions (bad data deep in a plugin) get the element's location.
template <typename F>
auto located(const XmlObject& o, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const SceneError&) {
        throw;
    } catch (const std::exception& e) {
        throw SceneError(o.loc, o.tag, e.what());
    }
}

/// The largest sample count a scene may ask for (the samplers index samples in 32 bits).
constexpr int64_t kMaxSampleCount = int64_t(1) << 30;

class Instantiator {
public:
    explicit Instantiator(LoadedScene& out) : m_out(out) {}

    void run(const XmlObject& root) {
        note_type_case(root);
        auto scene = std::make_unique<Scene>();
        const XmlObject* sensor = nullptr;
        const XmlObject* integrator = nullptr;
        for (const auto& c : root.children) {
            const XmlObject& o = *c.obj;
            if (o.tag == "sensor") {
                if (sensor)
                    throw SceneError(o.loc, o.tag, "more than one <sensor> (first at " + sensor->loc.str() + ")");
                sensor = &o;
            } else if (o.tag == "integrator") {
                if (integrator)
                    throw SceneError(o.loc, o.tag,
                                     "more than one <integrator> (first at " + integrator->loc.str() + ")");
                integrator = &o;
            } else if (o.tag == "bsdf") {
                bsdf(o);  // instantiated even if unused, so its errors are reported
            } else if (o.tag == "texture") {
                texture(o);  // likewise
            } else if (o.tag == "shape") {
                add_shape(o, *scene);
            } else if (o.tag == "film" || o.tag == "sampler" || o.tag == "rfilter") {
                // A declaration (Mitsuba 3): instantiated where a <ref> uses it.
                if (!o.referenced)
                    throw SceneError(
                        o.loc, o.tag,
                        "a top-level <" + o.tag + "> is used only through <ref id=\"...\"/> " + "inside a <sensor>" +
                            (o.tag == "rfilter" ? "'s <film>" : "") +
                            (o.id.empty() ? ", and this one has no id" : ", and none names '" + o.id + "'"));
            } else if (o.tag == "emitter") {
                if (o.type == "area" && o.referenced) continue;  // declared here, used by a <shape>'s <ref>
                if (o.type == "area")
                    throw SceneError(o.loc, o.tag, "an area emitter must be nested inside the <shape> that emits");
                Props p = emitter_props(o);
                auto light = located(o, [&] { return create_light(p); });
                p.check_unused();
                scene->add_light(light);
            }
        }
        if (!sensor) throw SceneError(root.loc, "scene", "the scene has no <sensor type=\"perspective\">");
        scene->set_camera(camera(*sensor));
        if (integrator) {
            Props p = integrator_props(*integrator, &m_out.notices);
            // Mitsuba's render-loop settings, common to its sampling integrators: the time
            // budget, and the samples per pass (snell renders tiles progressively anyway).
            if (p.has("timeout")) m_out.time_limit = std::max(0.0, p.get_float("timeout"));
            p.mark_used("samples_per_pass");
            auto integ = located(*integrator, [&] { return create_integrator(p); });
            p.check_unused();
            if (integ->needs_pinhole_camera() && !scene->camera()->pinhole())
                throw SceneError(sensor->loc, "sensor",
                                 "<sensor type=\"" + sensor->type + "\">: " + integ->name() +
                                     " connects light paths to the camera and needs a perspective (pinhole) sensor; "
                                     "render this one with path, pt, nee, mnee, direct, pssmlt or erpt");
            m_out.integrator = integ;
        } else {  // Mitsuba's default integrator
            Props p("integrator", "path", root.loc);
            m_out.integrator = create_integrator(p);
        }
        located(root, [&] {
            try {
                scene->build();
            } catch (const InstanceRangeError& e) {
                const XmlObject& inst = *m_instances.at(e.index);
                throw SceneError(inst.loc, inst.tag, e.what());
            }
        });
        m_out.scene = std::move(scene);
    }

private:
    LoadedScene& m_out;
    std::set<const XmlObject*> m_case_checked;  // note_type_case visits each element once
    std::map<const XmlObject*, std::vector<const XmlObject*>> m_mesh_attr_below;  // mesh_attribute_textures()
    std::map<const XmlObject*, std::shared_ptr<BSDF>> m_bsdfs;  // one instance per element (refs share)
    std::map<const XmlObject*, TextureRef> m_textures;
    std::map<const XmlObject*, std::shared_ptr<ShapeGroup>> m_groups;
    std::vector<const XmlObject*> m_instances;  // in the order the scene holds them

    // The SMS code's caustic flags on shapes and emitters: accepted, one notice per scene.
    void sms_flags(const Props& p) {
        if (!consume_sms_flags(p) || m_sms_notice) return;
        m_sms_notice = true;
        m_out.notices.push_back(p.loc().str() +
                                ": the SMS code's caustic_* flags are ignored: snell's mnee treats every refractive "
                                "shape as a caster and every other surface as a receiver");
    }
    bool m_sms_notice = false;

    static Props props(const XmlObject& o) { return object_props(o); }

    /// A notice for every type written with capitals ("Rectangle"), which is read in lower case.
    void note_type_case(const XmlObject& o) {
        if (!m_case_checked.insert(&o).second) return;  // referenced objects: once
        if (o.type != o.type_as_written)
            m_out.notices.push_back(o.loc.str() + ": <" + o.tag + " type=\"" + o.type_as_written + "\"> read as '" +
                                    o.type + "' (Mitsuba's plugin names are lower case)");
        for (const auto& c : o.children)
            if (c.obj) note_type_case(*c.obj);
    }

    /// An emitter's parameters with its nested or referenced textures.
    Props emitter_props(const XmlObject& o) {
        Props p = props(o);
        if (o.param("filename")) p.set("__base_dir", o.base_dir, o.loc);  // envmap image
        for (const auto& c : o.children) p.add_child(c.name, std::const_pointer_cast<Texture>(texture(*c.obj)), c.loc);
        sms_flags(p);
        return p;
    }

    std::shared_ptr<BSDF> bsdf(const XmlObject& o) {
        if (auto it = m_bsdfs.find(&o); it != m_bsdfs.end()) return it->second;
        Props p = props(o);
        if (o.param("filename")) p.set("__base_dir", o.base_dir, o.loc);  // the SMS code's normalmap image
        for (const auto& c : o.children)                                  // twosided's nested bsdf, textured parameters
            if (c.obj->tag == "texture")
                p.add_child(c.name, std::const_pointer_cast<Texture>(texture(*c.obj)), c.loc);
            else
                p.add_child(c.name, bsdf(*c.obj), c.loc);
        auto b = located(o, [&] { return create_bsdf(p); });
        p.check_unused();
        b->set_id(o.id);
        m_bsdfs[&o] = b;
        return b;
    }

    TextureRef texture(const XmlObject& o) {
        if (auto it = m_textures.find(&o); it != m_textures.end()) return it->second;
        Props p = props(o);
        if (o.param("filename")) p.set("__base_dir", o.base_dir, o.loc);  // the image
        for (const auto& c : o.children)
            p.add_child(c.name, std::const_pointer_cast<Texture>(texture(*c.obj)), c.loc);  // checkerboard colours
        auto t = located(o, [&] { return create_texture(p); });
        std::const_pointer_cast<Texture>(t)->set_id(o.id);
        m_textures[&o] = t;
        return t;
    }

    void add_shape(const XmlObject& o, Scene& scene) {
        if (o.type == "shapegroup") {
            group(o);  // a declaration, placed by instances; built now so that its errors are reported
            return;
        }
        if (o.type == "instance") {
            Props p = props(o);
            const XmlObject* g = nullptr;
            for (const auto& c : o.children) {
                if (c.obj->tag != "shape" || c.obj->type != "shapegroup" || g)
                    throw SceneError(c.loc, c.obj->tag, "an instance takes exactly one <ref> to a shapegroup");
                g = c.obj.get();
            }
            if (!g) p.raise("an instance needs a <ref id=\"...\"/> to a shapegroup");
            const Transform to_world = p.get_transform("to_world");
            p.check_unused();
            if (!(std::abs(to_world.det3()) > 0)) p.raise_param("to_world", "to_world must be invertible");
            scene.add_instance(std::make_shared<Instance>(group(*g), to_world));
            m_instances.push_back(&o);
            return;
        }
        const XmlObject* emitter = nullptr;
        auto shape = make_shape(o, &emitter);
        if (emitter) {
            Props ep = emitter_props(*emitter);
            auto light = located(*emitter, [&] { return create_area_light(ep, shape); });
            ep.check_unused();
            scene.add_light(light);
        }
        scene.add_shape(shape);
    }

    /// A shape with its BSDF; its nested area emitter, if any, in *emitter.
    std::shared_ptr<Shape> make_shape(const XmlObject& o, const XmlObject** emitter) {
        Props p = props(o);
        // Mesh file names are relative to the file the shape was written in.
        if (o.param("filename")) p.set("__base_dir", o.base_dir, o.loc);
        for (const auto& c : o.children) {
            if (c.obj->tag == "bsdf") {
                p.add_child(c.name, bsdf(*c.obj), c.loc);
            } else if (c.obj->tag == "shape") {
                throw SceneError(c.loc, "shape",
                                 "only a <shape type=\"shapegroup\"> contains shapes (and only an instance "
                                 "refers to one)");
            } else {  // emitter (the parser allows nothing else here)
                if (*emitter)
                    throw SceneError(c.obj->loc, "emitter",
                                     "a shape has at most one emitter (first at " + (*emitter)->loc.str() + ")");
                if (c.obj->type != "area")
                    throw SceneError(
                        c.obj->loc, "emitter",
                        "only type=\"area\" emitters can be nested in a <shape>, not '" + c.obj->type + "'");
                *emitter = c.obj.get();
            }
        }
        sms_flags(p);
        auto shape = located(o, [&] { return create_shape(p); });
        p.check_unused();
        shape->set_id(o.id);
        for (const auto& c : o.children)
            if (c.obj->tag == "bsdf") check_mesh_attributes(*c.obj, o, *shape);
        return shape;
    }

    /// Every `mesh_attribute` texture under the BSDF `o` must name an attribute the shape has
    /// (Mitsuba finds out while rendering; the loader says so with both places).
    void check_mesh_attributes(const XmlObject& o, const XmlObject& shape_xml, const Shape& shape) {
        for (const XmlObject* tex_xml : mesh_attribute_textures(o)) {
            const auto* t = dynamic_cast<const MeshAttributeTexture*>(texture(*tex_xml).get());
            if (!t) continue;
            const std::vector<std::string> names = shape.attribute_names();
            if (std::find(names.begin(), names.end(), t->attribute_name()) != names.end()) continue;
            std::string have;
            for (const auto& n : names) have += (have.empty() ? "" : ", ") + n;
            throw SceneError(tex_xml->loc, "texture",
                             "mesh attribute '" + t->attribute_name() + "' is not on the <shape> at " +
                                 shape_xml.loc.str() + " (it has " + (have.empty() ? "none" : have) + ")");
        }
    }

    /// The `mesh_attribute` textures below `o`, once per element: a <ref> can name one BSDF twice
    /// per level, and walking such a tree without memory costs 2^depth (issue 12).
    const std::vector<const XmlObject*>& mesh_attribute_textures(const XmlObject& o) {
        if (auto it = m_mesh_attr_below.find(&o); it != m_mesh_attr_below.end()) return it->second;
        std::vector<const XmlObject*> found;
        for (const auto& c : o.children) {
            if (!c.obj) continue;
            if (c.obj->tag == "texture" && c.obj->type == "mesh_attribute") found.push_back(c.obj.get());
            for (const XmlObject* t : mesh_attribute_textures(*c.obj))
                if (std::find(found.begin(), found.end(), t) == found.end()) found.push_back(t);
        }
        return m_mesh_attr_below[&o] = std::move(found);
    }

    /// A shapegroup's shapes, built once however many instances place it.
    std::shared_ptr<ShapeGroup> group(const XmlObject& o) {
        if (auto it = m_groups.find(&o); it != m_groups.end()) return it->second;
        Props p = props(o);
        std::vector<std::shared_ptr<Shape>> shapes;
        for (const auto& c : o.children) {
            if (c.obj->tag != "shape")
                throw SceneError(c.loc, c.obj->tag, "a shapegroup contains only shapes (with their BSDFs)");
            if (c.obj->type == "shapegroup" || c.obj->type == "instance")
                throw SceneError(c.loc, "shape", "shapegroups and instances do not nest");
            const XmlObject* emitter = nullptr;
            shapes.push_back(make_shape(*c.obj, &emitter));
            if (emitter)
                throw SceneError(emitter->loc, "emitter",
                                 "a shape in a shapegroup cannot emit (as in Mitsuba): instance the geometry, and "
                                 "give the emitting shape its own <shape>");
        }
        p.check_unused();
        if (shapes.empty()) p.raise("an empty shapegroup");
        auto g = std::make_shared<ShapeGroup>(std::move(shapes));
        m_groups[&o] = g;
        return g;
    }

    std::shared_ptr<Camera> camera(const XmlObject& o) {
        Props p = props(o);
        static const std::set<std::string> types = {"perspective", "thinlens", "orthographic"};
        if (!types.count(o.type))
            p.raise("unknown sensor type '" + o.type + "' (supported: perspective, thinlens, orthographic)");
        const double near_clip = p.get_float("near_clip", 1e-2), far_clip = p.get_float("far_clip", 1e4);
        if (!(near_clip > 0 && far_clip > near_clip && std::isfinite(far_clip)))
            p.raise_param("near_clip", "need 0 < near_clip < far_clip");
        const Transform to_world = p.get_transform("to_world");
        // A projective camera's frame must be rigid, as Mitsuba 3 requires (Transform::has_scale,
        // same 1e-3 tolerance): its clip planes, importance and lens are in world units, so a
        // scale would silently change the picture (bdpt's light paths clipped at the wrong depth).
        if (o.type != "orthographic") {
            const auto& m = to_world.matrix();
            for (int i = 0; i < 3; ++i)
                for (int j = i; j < 3; ++j) {
                    const double g = m[0][i] * m[0][j] + m[1][i] * m[1][j] + m[2][i] * m[2][j];
                    if (!(std::abs(g - (i == j ? 1.0 : 0.0)) <= 1e-3))
                        p.raise_param("to_world", "a " + o.type +
                                                      " sensor's to_world must not scale or shear (Mitsuba 3 "
                                                      "refuses it too); scale the scene instead");
                }
        }
        double fov = 0, aperture = 0, focus = 0;
        std::string axis;
        if (o.type != "orthographic") {
            const FieldOfView f = read_field_of_view(p);
            fov = f.fov_deg;
            axis = f.axis;
        }
        if (o.type == "thinlens") {
            // Mitsuba's thinlens takes both, without defaults.
            aperture = p.get_float("aperture_radius");
            focus = p.get_float("focus_distance");
            if (!(aperture > 0) || !std::isfinite(aperture))
                p.raise_param("aperture_radius", "aperture_radius must be > 0 (a pinhole is type=\"perspective\")");
            if (!(focus > 0) || !std::isfinite(focus)) p.raise_param("focus_distance", "focus_distance must be > 0");
        } else if (o.type == "perspective") {
            // Mitsuba's exporters write focus_distance on every perspective sensor; a pinhole keeps
            // everything in focus, so the value is checked and has no effect.
            if (p.has("focus_distance") && !(p.get_float("focus_distance") > 0))
                p.raise_param("focus_distance", "focus_distance must be > 0");
        }

        FilmSpec film;
        film.filter = default_filter();  // a sensor without <film> gets Mitsuba's default hdrfilm
        const XmlObject *film_obj = nullptr, *sampler_obj = nullptr;
        for (const auto& c : o.children) {
            const XmlObject*& slot = c.obj->tag == "film" ? film_obj : sampler_obj;
            if (slot) throw SceneError(c.obj->loc, c.obj->tag, "more than one <" + c.obj->tag + "> in the sensor");
            slot = c.obj.get();
        }
        if (film_obj) film = read_film(*film_obj);
        if (sampler_obj) read_sampler(*sampler_obj);
        p.check_unused();
        m_out.film = film;
        return located(o, [&]() -> std::shared_ptr<Camera> {
            if (o.type == "orthographic")
                return std::make_shared<OrthographicCamera>(to_world, film, near_clip, far_clip);
            if (o.type == "thinlens")
                return std::make_shared<ThinLensCamera>(to_world, fov, axis, film, aperture, focus, near_clip,
                                                        far_clip);
            return std::make_shared<PerspectiveCamera>(to_world, fov, axis, film, near_clip, far_clip);
        });
    }

    static FilmSpec read_film(const XmlObject& o) {
        Props p = props(o);
        if (o.type != "hdrfilm") p.raise("unknown film type '" + o.type + "' (supported: hdrfilm)");
        FilmSpec f;
        // Read as 64-bit and range-checked before any narrowing (issue 12: 4294967312 became 16).
        constexpr int64_t kMaxSide = int64_t(1) << 16;
        const int64_t width = p.get_int("width", 768), height = p.get_int("height", 576);
        for (auto [name, v] : {std::pair{"width", width}, std::pair{"height", height}})
            if (v <= 0 || v > kMaxSide)
                p.raise_param(name,
                              std::string("film ") + name + " must lie in [1, 65536] (got " + std::to_string(v) + ")");
        f.width = int(width);
        f.height = int(height);
        // 64-bit sums: offset + size cannot overflow (issue 12: crop_offset_x=2147483647 did).
        const int64_t cx = p.get_int("crop_offset_x", 0), cy = p.get_int("crop_offset_y", 0);
        const int64_t cw = p.get_int("crop_width", width - cx), ch = p.get_int("crop_height", height - cy);
        if (cx < 0 || cy < 0 || cw <= 0 || ch <= 0 || cx > width || cy > height || cw > width || ch > height ||
            cx + cw > width || cy + ch > height)
            p.raise("crop window (offset " + std::to_string(cx) + "," + std::to_string(cy) + ", size " +
                    std::to_string(cw) + "x" + std::to_string(ch) + ") does not fit the " + std::to_string(f.width) +
                    "x" + std::to_string(f.height) + " film");
        if (cx != 0 || cy != 0 || cw != f.width || ch != f.height) {
            f.crop_x = int(cx);
            f.crop_y = int(cy);
            f.crop_w = int(cw);
            f.crop_h = int(ch);
        }
        // Accepted for compatibility with Mitsuba files; the output format is chosen by the app.
        static const std::set<std::string> pixel_formats = {"rgb", "rgba", "luminance", "luminance_alpha",
                                                            "xyz", "xyza"};
        static const std::set<std::string> component_formats = {"float16", "float32", "uint32"};
        if (!pixel_formats.count(p.get_string("pixel_format", "rgb")))
            p.raise_param("pixel_format", "unknown pixel_format (rgb, rgba, luminance, luminance_alpha, xyz, xyza)");
        if (!component_formats.count(p.get_string("component_format", "float16")))
            p.raise_param("component_format", "unknown component_format (float16, float32, uint32)");
        p.mark_used("banner");  // Mitsuba 0.6's; Mitsuba 3 accepts and ignores it too
        static const std::set<std::string> file_formats = {"openexr", "exr", "rgbe", "hdr", "pfm"};
        if (!file_formats.count(p.get_string("file_format", "openexr")))
            p.raise_param("file_format", "unknown file_format (openexr, rgbe, pfm)");
        f.filter = default_filter();
        for (const auto& c : o.children) f.filter = read_rfilter(*c.obj);
        if (o.children.size() > 1)
            throw SceneError(o.children[1].loc, "rfilter", "more than one <rfilter> in the film");
        p.check_unused();
        return f;
    }

    /// Mitsuba 3's reconstruction filter when the film names none: gaussian, stddev 0.5.
    static std::shared_ptr<const Filter> default_filter() { return std::make_shared<GaussianFilter>(0.5); }

    static std::shared_ptr<const Filter> read_rfilter(const XmlObject& o) {
        Props p = props(o);
        auto filter = create_filter(p);
        p.check_unused();
        return filter;
    }

    void read_sampler(const XmlObject& o) {
        Props p = props(o);
        const auto& types = sampler_types();
        if (std::find(types.begin(), types.end(), o.type) == types.end()) {
            std::string supported;
            for (const auto& t : types) supported += (supported.empty() ? "" : ", ") + t;
            p.raise("unknown sampler type '" + o.type + "' (supported: " + supported + ")");
        }
        SamplerSpec spec;
        spec.type = o.type;
        if (o.type == "stratified" || o.type == "multijitter" || o.type == "orthogonal")
            spec.jitter = p.get_bool("jitter", true);
        if (o.type == "orthogonal" && p.get_int("strength", 2) != 2)
            p.raise_param("strength", "snell's orthogonal sampler has strength 2 (the one Mitsuba recommends)");
        const int64_t spp = p.get_int("sample_count", m_out.spp);
        // Range-checked before narrowing (issue 12: 2147483648 became negative, 4294967297 one).
        if (spp <= 0 || spp > kMaxSampleCount)
            p.raise_param("sample_count", "sample_count must lie in [1, " + std::to_string(kMaxSampleCount) +
                                              "] (got " + std::to_string(spp) + ")");
        const int64_t seed = p.get_int("seed", 0);
        if (seed < 0) p.raise_param("seed", "seed must be non-negative");
        p.check_unused();
        m_out.spp = int(spp);
        m_out.seed = uint64_t(seed);
        m_out.sampler = spec;
    }
};

LoadedScene instantiate(const XmlObject& root, const std::string& path) {
    LoadedScene out;
    out.path = path;
    Instantiator(out).run(root);
    return out;
}

}  // namespace

LoadedScene load_scene_file(const std::string& path, const Defines& defines,
                            const std::vector<std::string>& search_paths) {
    return instantiate(*parse_scene_xml_file(path, defines, search_paths), path);
}

LoadedScene load_scene_string(const std::string& xml, const std::string& name, const std::string& base_dir,
                              const Defines& defines) {
    return instantiate(*parse_scene_xml_string(xml, name, base_dir, defines), name);
}

}  // namespace snell
