#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "core/props.h"
#include "integrators/integrator.h"
#include "sampler/factory.h"
#include "scene/scene.h"

namespace snell {

/// Everything a render needs from a scene file.
struct LoadedScene {
    std::unique_ptr<Scene> scene;  ///< built (BVH committed), camera set
    /// The scene file's <integrator> (`path` without one, as in Mitsuba). Kept beside the Scene,
    /// not in it: the integrators sit above the Scene they render (pbrt-v4 keeps them apart too).
    /// Declared after `scene`, so it is destroyed first.
    std::shared_ptr<Integrator> integrator;
    FilmSpec film;
    int spp = 16;         ///< sampler sample_count
    uint64_t seed = 0;    ///< sampler seed (offsets every random stream of the render)
    SamplerSpec sampler;  ///< sampler type and jitter; `independent` without a <sampler> (Mitsuba's default)
    std::string path;     ///< file it came from ("builtin:<name>" for built-ins)
    /// "file:line: ..." lines on what renders differently from Mitsuba (an unwrapped AOV
    /// integrator, an SMS integrator rendered as mnee, ignored SMS flags); the apps print them.
    std::vector<std::string> notices;
    /// Mitsuba's integrator `timeout` in seconds (0: none): `snell render` stops there unless
    /// --spp or --time says otherwise.
    double time_limit = 0;
};

/// Parameter overrides (-D name=value), applied like Mitsuba's <default> substitution.
using Defines = std::map<std::string, std::string>;

/// Loads a Mitsuba 2/3-style XML scene. Errors are SceneError "file:line: <element>: what".
/// `search_paths` (the command line's -a, as in Mitsuba) are tried for relative file names after
/// the scene's own folders.
LoadedScene load_scene_file(const std::string& path, const Defines& defines = {},
                            const std::vector<std::string>& search_paths = {});
/// Loads from a string; relative paths resolve against `base_dir`; `name` labels errors.
LoadedScene load_scene_string(const std::string& xml, const std::string& name, const std::string& base_dir,
                              const Defines& defines = {});

}  // namespace snell
