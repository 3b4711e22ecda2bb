#include "integrators/erpt/shape_watch.h"

#include <algorithm>
#include <utility>

#include "geometry/shape.h"
#include "integrators/mnee/mnee_integrator.h"
#include "scene/scene.h"

namespace snell {

namespace {

// Per thread: li() is not re-entrant within a thread, and the renderer never moves a pixel
// sample between threads in the middle of an evaluation.
thread_local bool t_touched = false;

/// Base (PathTracer or MneeIntegrator) with its arrival hook also checking the shape.
template <class Base>
class ShapeWatching final : public Base {
public:
    template <class... Args>
    explicit ShapeWatching(std::vector<const Shape*> watched, Args&&... args)
        : Base(std::forward<Args>(args)...), m_watched(std::move(watched)) {}

    SampledSpectrum li(const Ray& ray, const Scene& scene, Sampler& sampler,
                       const SampledWavelengths& wl) const override {
        t_touched = false;
        return Base::li(ray, scene, sampler, wl);
    }

protected:
    // on_arrival runs at every vertex of the camera subpath and at nothing else (light
    // samples and manifold walks do not arrive), which is what "touches" means.
    void on_arrival(PathState& state, const SurfaceInteraction& si, const Ray& ray,
                    const BSDFContext& ctx) const override {
        Base::on_arrival(state, si, ray, ctx);
        if (!t_touched && si.shape && std::find(m_watched.begin(), m_watched.end(), si.shape) != m_watched.end())
            t_touched = true;
    }

private:
    std::vector<const Shape*> m_watched;  // a handful: a linear search is cheapest
};

}  // namespace

std::vector<std::string> parse_shape_ids(const Props& props, const std::string& name, const std::string& list) {
    std::vector<std::string> ids;
    if (list.find_first_not_of(" \t") == std::string::npos) return ids;
    size_t start = 0;
    while (true) {
        const size_t comma = list.find(',', start);
        std::string id = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const size_t b = id.find_first_not_of(" \t"), e = id.find_last_not_of(" \t");
        if (b == std::string::npos) props.raise_param(name, "erpt: " + name + ": empty shape id in '" + list + "'");
        ids.push_back(id.substr(b, e - b + 1));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return ids;
}

std::vector<const Shape*> resolve_shape_ids(const Scene& scene, const std::vector<std::string>& ids,
                                            const SourceLoc& loc) {
    std::vector<const Shape*> shapes;
    for (const std::string& id : ids) {
        bool found = false;
        for (const auto& shape : scene.shapes())
            if (shape->id() == id) {
                shapes.push_back(shape.get());
                found = true;
            }
        if (found) continue;
        std::string known;
        for (const auto& shape : scene.shapes())
            if (!shape->id().empty()) known += (known.empty() ? "" : ", ") + shape->id();
        throw SceneError(loc, "integrator",
                         "erpt: unknown shape id '" + id + "' in shapes (" +
                             (known.empty() ? std::string("no shape of the scene has an id") : "shape ids: " + known) +
                             ")");
    }
    return shapes;
}

std::shared_ptr<PathTracer> make_watching_estimator(const std::string& sampler, const PathSettings& path,
                                                    const MneeSettings& mnee, std::vector<const Shape*> watched) {
    if (sampler == "mnee") return std::make_shared<ShapeWatching<MneeIntegrator>>(std::move(watched), path, mnee);
    return std::make_shared<ShapeWatching<PathTracer>>(std::move(watched), path, true);
}

bool camera_path_touched() { return t_touched; }

}  // namespace snell
