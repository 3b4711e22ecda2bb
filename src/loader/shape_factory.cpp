#include "loader/shape_factory.h"

#include <filesystem>

#include "bsdf/factory.h"
#include "geometry/builders.h"
#include "geometry/cylinder.h"
#include "geometry/mesh.h"
#include "geometry/sphere.h"
#include "io/mesh_obj.h"
#include "io/mesh_ply.h"
#include "io/mesh_serialized.h"
#include "light/light.h"

namespace snell {
namespace {

/// The uniform scale of `xf`, which may only translate, rotate and scale uniformly for shapes
/// that must stay what they are (a sphere, a circular cylinder); raises on `to_world` otherwise.
double uniform_scale(const Props& props, const Transform& xf, const char* what) {
    const Vec3 ax = xf.vector({1, 0, 0}), ay = xf.vector({0, 1, 0}), az = xf.vector({0, 0, 1});
    const double s = length(ax);
    const double tol = 1e-6 * s;
    if (std::abs(length(ay) - s) > tol || std::abs(length(az) - s) > tol || std::abs(dot(ax, ay)) > tol * s ||
        std::abs(dot(ax, az)) > tol * s || std::abs(dot(ay, az)) > tol * s || !(s > 0))
        props.raise_param("to_world",
                          std::string("a ") + what + "'s to_world may only rotate, translate and scale uniformly");
    return s;
}

/// Sphere: Mitsuba composes `center`/`radius` with `to_world`.
std::shared_ptr<Shape> make_sphere(const Props& props, const Transform& xf, bool flip) {
    const Vec3 c = props.get_vec3("center", Vec3(0, 0, 0));
    const double r = props.get_float("radius", 1.0);
    if (!(r > 0)) props.raise_param("radius", "sphere radius must be positive");
    return std::make_shared<Sphere>(xf.point(c), r * uniform_scale(props, xf, "sphere"), flip);
}

/// Cylinder (open, Mitsuba's): `p0`, `p1` (the axis' ends) and `radius`, composed with
/// `to_world`. As in Mitsuba, the transform may scale the axis differently from the cross
/// section, but must keep the cross section circular.
std::shared_ptr<Shape> make_cylinder(const Props& props, const Transform& xf, bool flip) {
    const Vec3 p0 = props.get_vec3("p0", Vec3(0, 0, 0)), p1 = props.get_vec3("p1", Vec3(0, 0, 1));
    const double r = props.get_float("radius", 1.0);
    if (!(r > 0)) props.raise_param("radius", "cylinder radius must be positive");
    if (!(length(p1 - p0) > 0)) props.raise_param("p1", "a cylinder's p0 and p1 must differ");
    const Frame f = Frame::from_normal(normalize(p1 - p0));
    const Vec3 r1 = xf.vector(f.s), r2 = xf.vector(f.t), axis = xf.vector(f.n);
    const double s = length(r1), tol = 1e-6 * s;
    if (!(s > 0) || std::abs(length(r2) - s) > tol || std::abs(dot(r1, r2)) > tol * s ||
        std::abs(dot(r1, axis)) > tol * length(axis) || std::abs(dot(r2, axis)) > tol * length(axis))
        props.raise_param("to_world",
                          "a cylinder's to_world must keep its cross section circular (it may rotate, "
                          "translate, scale uniformly, and scale the axis on its own)");
    return std::make_shared<Cylinder>(xf.point(p0), xf.point(p1), r * s, flip);
}

std::string resolve(const Props& props) {
    const std::filesystem::path f = props.get_string("filename");
    const std::string base = props.get_string("__base_dir", "");
    if (f.is_absolute() || base.empty()) return f.string();
    return (std::filesystem::path(base) / f).string();
}

}  // namespace

std::shared_ptr<Shape> create_shape(const Props& props) {
    const std::string& type = props.type();
    const Transform xf = props.get_transform("to_world");
    const bool flip = props.get_bool("flip_normals", false);

    std::shared_ptr<Shape> shape;
    if (type == "sphere") {
        shape = make_sphere(props, xf, flip);
    } else if (type == "cylinder") {
        shape = make_cylinder(props, xf, flip);
    } else if (type == "rectangle" || type == "disk" || type == "cube" || type == "obj" || type == "ply" ||
               type == "serialized") {
        bool face_normals = props.get_bool("face_normals", false);
        MeshData data;
        std::string name = type;
        try {
            if (type == "rectangle") {
                data = make_rectangle(xf);
            } else if (type == "disk") {
                data = make_disk(xf);
            } else if (type == "cube") {
                data = make_cube(xf);
            } else {
                name = resolve(props);
                if (type == "obj") {
                    // Mitsuba's default: OBJ texture v runs downwards.
                    const bool flip_tex = props.get_bool("flip_tex_coords", true);
                    data = load_obj(name);
                    if (flip_tex)
                        for (Vec2& uv : data.uvs) uv.y = 1 - uv.y;
                } else if (type == "serialized") {
                    // Mitsuba's compressed meshes; the file may ask for face normals itself.
                    const int64_t index = props.get_int("shape_index", 0);
                    bool file_face_normals = false;
                    data = load_serialized(name, index, &file_face_normals);
                    face_normals = face_normals || file_face_normals;
                } else {
                    data = load_ply(name);
                }
                transform_mesh(data, xf);
            }
            shape = std::make_shared<TriangleMesh>(std::move(data), face_normals, flip, name);
        } catch (const SceneError&) {
            throw;
        } catch (const std::exception& e) {
            props.raise(e.what());  // the reader's message names the file and the problem
        }
    } else {
        props.raise("unknown shape type '" + type + "'");
    }

    std::shared_ptr<BSDF> bsdf = props.child<BSDF>("bsdf");
    if (!bsdf) bsdf = create_bsdf(Props("bsdf", "diffuse", props.loc()));
    shape->set_bsdf(std::move(bsdf));
    // A nested <emitter> is linked to this shape by the loader; it is not ours to consume.
    (void)props.children<Light>();
    props.check_unused();
    return shape;
}

}  // namespace snell
