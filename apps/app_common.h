#pragma once
// Helpers shared by the `snell` sub-commands (render, diff, compare).
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "camera/film.h"
#include "io/image.h"
#include "io/stats_json.h"
#include "loader/scene_loader.h"
#include "loader/xml_scene.h"
#include "render/renderer.h"
#include "report/image_metrics.h"

namespace snell {

/// Set by the first Ctrl-C (see on_sigint); renders poll it and stop early.
extern std::atomic<bool> g_cancel;
/// SIGINT handler: the first Ctrl-C sets g_cancel, the second exits at once (status 130).
extern "C" void on_sigint(int);

/// Loads a scene file or a built-in ("builtin:NAME") with -D overrides. The loader's notices
/// (LoadedScene::notices) go to stderr unless `print_notices` is false (the Python module turns
/// them into warnings).
LoadedScene load_scene_arg(const std::string& scene_arg, const Defines& defines,
                           const std::vector<std::string>& search_paths = {}, bool print_notices = true);
/// Parses a scene file or built-in into the intermediate XML tree (no plugin is instantiated).
std::shared_ptr<XmlObject> parse_scene_arg(const std::string& scene_arg, const Defines& defines);
/// Parses -D items "name=value"; throws CLI::ValidationError on a malformed item.
Defines parse_defines(const std::vector<std::string>& items);
/// The stats report of render `r` of `scene` by `integrator` on a film of width x height
/// (counters, MNEE statistics, pixel dominance).
RenderReport make_report(const std::string& scene, const std::string& integrator, int width, int height,
                         const RenderResult& r, uint64_t spp_requested, double time_limit, int threads, uint64_t seed);
/// The window of size w x h at the offset "x,y" given to `option` (--reference-offset,
/// --image-offset); throws std::runtime_error naming the option and the text if it is not two
/// non-negative integers.
Crop offset_window(const std::string& option, const std::string& xy, int w, int h);
/// The film's linear sRGB pixels as an Image.
Image film_to_image(const Film& film, int layer = 0);

}  // namespace snell
