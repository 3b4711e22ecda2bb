// snell.load_file / snell.load_string and the integrator a render asks for (docs/python.md).
#include <pybind11/stl.h>

#include <filesystem>

#include "app_common.h"
#include "bindings.h"
#include "core/props.h"

namespace snell::py {

namespace {

// Python values of an integrator dict as scene parameters: what the XML's <boolean>,
// <integer>, <float> and <string> would give.
Props::Value param_value(const std::string& name, const pyb::handle& v) {
    if (pyb::isinstance<pyb::bool_>(v)) return v.cast<bool>();
    if (pyb::isinstance<pyb::int_>(v)) return v.cast<int64_t>();
    if (pyb::isinstance<pyb::float_>(v)) return v.cast<double>();
    if (pyb::isinstance<pyb::str>(v)) return v.cast<std::string>();
    throw SceneError("integrator parameter '" + name + "': expected a bool, int, float or str, got " +
                     std::string(pyb::str(v.get_type().attr("__name__"))));
}

}  // namespace

std::shared_ptr<Integrator> integrator_from(const pyb::handle& spec, const PyScene& scene) {
    if (spec.is_none()) {
        if (!scene.ls.integrator) throw SceneError(scene.name + ": the scene declares no <integrator>");
        return scene.ls.integrator;
    }
    const SourceLoc loc{"render(integrator=...)", 0};
    if (pyb::isinstance<pyb::str>(spec)) return create_integrator(Props("integrator", spec.cast<std::string>(), loc));
    if (!pyb::isinstance<pyb::dict>(spec))
        throw pyb::type_error("integrator: expected None, a type name or a dict with a 'type', got " +
                              std::string(pyb::str(spec.get_type().attr("__name__"))));
    const pyb::dict d = pyb::reinterpret_borrow<pyb::dict>(spec);
    if (!d.contains("type") || !pyb::isinstance<pyb::str>(d["type"]))
        throw SceneError("integrator dict: needs a 'type' (a str such as 'mnee')");
    Props props("integrator", d["type"].cast<std::string>(), loc);
    for (const auto& [k, v] : d) {
        const std::string name = pyb::str(k);
        if (name != "type") props.set(name, param_value(name, v), loc);
    }
    return create_integrator(props);
}

void bind_scene(pyb::module_& m) {
    pyb::class_<PyScene>(m, "Scene")
        .def_readonly("name", &PyScene::name)
        .def_property_readonly("width", [](const PyScene& s) { return s.ls.film.out_width(); })
        .def_property_readonly("height", [](const PyScene& s) { return s.ls.film.out_height(); })
        .def_property_readonly("spp", [](const PyScene& s) { return s.ls.spp; })
        .def_property_readonly("seed", [](const PyScene& s) { return s.ls.seed; })
        .def_property_readonly("time_limit", [](const PyScene& s) { return s.ls.time_limit; })
        .def_property_readonly("integrator",
                               [](const PyScene& s) { return s.ls.integrator ? s.ls.integrator->name() : ""; })
        .def_property_readonly("notices", [](const PyScene& s) { return s.ls.notices; });

    // The scene is built (meshes read, BVH committed) without the GIL: other threads run meanwhile.
    m.def(
        "load_file",
        [](const std::string& path, const Defines& defines, const std::vector<std::string>& search_paths) {
            auto s = std::make_unique<PyScene>();
            s->name = path;
            pyb::gil_scoped_release nogil;
            s->ls = load_scene_arg(path, defines, search_paths, false);
            return s;
        },
        pyb::arg("path"), pyb::arg("defines"), pyb::arg("search_paths"));
    m.def(
        "load_string",
        [](const std::string& xml, const Defines& defines, const std::string& base_dir) {
            auto s = std::make_unique<PyScene>();
            s->name = "<string>";
            pyb::gil_scoped_release nogil;
            s->ls = load_scene_string(xml, s->name, base_dir, defines);
            return s;
        },
        pyb::arg("xml"), pyb::arg("defines"), pyb::arg("base_dir"));
}

}  // namespace snell::py
