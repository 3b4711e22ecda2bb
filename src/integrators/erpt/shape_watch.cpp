#include "integrators/erpt/shape_watch.h"

#include <algorithm>
#include <utility>

#include "geometry/shape.h"
#include "integrators/mnee/mnee_integrator.h"
#include "integrators/path/path_tracer.h"
#include "scene/scene.h"

namespace snell {

namespace {

// Per thread: li() is not re-entrant within a thread, and the renderer never moves a pixel
// sample between threads in the middle of an evaluation.
thread_local bool t_touched = false;

/// Sets the flag when the path arrives on a watched shape.
class ShapeObserver final : public PathObserver {
public:
    explicit ShapeObserver(const std::vector<const Shape*>& watched) : m_watched(&watched) {}
    void arrived(const SurfaceInteraction& si) override {
        if (!t_touched && si.shape && std::find(m_watched->begin(), m_watched->end(), si.shape) != m_watched->end())
            t_touched = true;
    }

private:
    const std::vector<const Shape*>* m_watched;  // a handful: a linear search is cheapest
};

/// The inner estimator, its camera subpaths watched (the observer sees every vertex of the
/// camera subpath and nothing else: light samples and manifold walks do not arrive).
class ShapeWatching final : public RadianceEstimator {
public:
    ShapeWatching(std::vector<const Shape*> watched, std::shared_ptr<const RadianceEstimator> inner)
        : m_watched(std::move(watched)), m_inner(std::move(inner)) {}

    SampleEstimate radiance(const Ray& ray, const Scene& scene, Sampler& sampler, const SampledWavelengths& wl,
                            PathObserver* /*observer*/) const override {
        t_touched = false;
        ShapeObserver watch(m_watched);
        return m_inner->radiance(ray, scene, sampler, wl, &watch);
    }
    std::unique_ptr<SampleTracer> prepare(const Scene& /*scene*/, const FilmSpec& /*film*/,
                                          const RenderOptions& /*options*/) const override {
        return std::make_unique<RadianceTracer>(*this);
    }
    std::string name() const override { return m_inner->name(); }
    const PathSettings& settings() const override { return m_inner->settings(); }

private:
    std::vector<const Shape*> m_watched;
    std::shared_ptr<const RadianceEstimator> m_inner;
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

std::shared_ptr<RadianceEstimator> make_watching_estimator(const std::string& sampler, const PathSettings& path,
                                                           const MneeSettings& mnee,
                                                           std::vector<const Shape*> watched) {
    std::shared_ptr<const RadianceEstimator> inner;
    if (sampler == "mnee")
        inner = std::make_shared<MneeIntegrator>(path, mnee);
    else
        inner = std::make_shared<PathTracer>(path, true);
    return std::make_shared<ShapeWatching>(std::move(watched), std::move(inner));
}

bool camera_path_touched() { return t_touched; }

}  // namespace snell
