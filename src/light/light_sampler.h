#pragma once
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/distribution.h"
#include "light/light.h"

namespace snell {

/// Chooses one light for next event estimation, proportionally to emitted power.
class LightSampler {
public:
    LightSampler() = default;
    explicit LightSampler(const std::vector<std::shared_ptr<Light>>& lights) {
        std::vector<double> w;
        for (size_t i = 0; i < lights.size(); ++i) {
            m_lights.push_back(lights[i].get());
            m_index[lights[i].get()] = i;
            const double p = lights[i]->power();
            w.push_back(std::isfinite(p) && p > 0 ? p : 0.0);
        }
        double total = 0;
        for (double x : w) total += x;
        if (!(total > 0)) std::fill(w.begin(), w.end(), 1.0);  // fall back to uniform
        if (!w.empty()) m_dist = Distribution1D(w);
    }
    bool empty() const { return m_lights.empty(); }
    /// Returns a light and its discrete probability, or nullptr if there are none.
    const Light* sample(double u, double* pmf) const {
        if (m_lights.empty()) return nullptr;
        return m_lights[m_dist.sample_discrete(u, pmf)];
    }
    double pmf(const Light* l) const {
        auto it = m_index.find(l);
        return it == m_index.end() ? 0.0 : m_dist.pmf(it->second);
    }

private:
    std::vector<const Light*> m_lights;
    std::unordered_map<const Light*, size_t> m_index;
    Distribution1D m_dist;
};

}  // namespace snell
