#pragma once
// The extension `snell._snell` (issue 28): one file per concept, each adding its part to the
// module. The Python package python/snell/ is the API users see (docstrings, types); these are
// its native halves.
#include <pybind11/pybind11.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "loader/scene_loader.h"
#include "render/renderer.h"

namespace snell::py {

namespace pyb = pybind11;

/// A loaded scene (python/snell/_scene.py wraps it): the BVH, lights and film spec, kept so that
/// every render of a sweep reuses them.
struct PyScene {
    LoadedScene ls;
    std::string name;  ///< the path or "builtin:NAME" or "<string>"
};

/// A finished (or stopped) render: the film with its samples and the image buffers Python views
/// without copying (the numpy arrays' base).
struct PyFilm {
    RenderResult result;
    int width = 0, height = 0;
    std::vector<float> rgb;                  ///< linear sRGB, H x W x 3, row-major (layer 0)
    std::vector<std::vector<float>> layers;  ///< debug layers 1, 2, ... (BDPT's strategies)
    nlohmann::json stats;                    ///< the stats JSON `snell render --stats` writes
};

/// A handle another thread (or a progress callback) stops a render with.
struct StopHandle {
    std::atomic<bool> requested{false};
};

/// The integrator a render uses: the scene's (`spec` None), a type name ("mnee"), or a dict of
/// parameters with its "type" ({"type": "mnee", "biased": True}), built like the scene's own
/// <integrator> would be, with the same errors (SceneError naming the parameter).
std::shared_ptr<Integrator> integrator_from(const pyb::handle& spec, const PyScene& scene);

/// A JSON value as Python's dict, list, str, int, float, bool or None; unlike a round trip
/// through JSON text, infinities stay floats (an identical image's PSNR is inf, not null).
pyb::object to_python(const nlohmann::json& j);

void bind_scene(pyb::module_& m);
void bind_film(pyb::module_& m);
void bind_render(pyb::module_& m);
void bind_images(pyb::module_& m);
void bind_compare(pyb::module_& m);

}  // namespace snell::py
