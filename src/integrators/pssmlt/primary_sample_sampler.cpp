#include "integrators/pssmlt/primary_sample_sampler.h"

#include <cmath>

namespace snell {

PrimarySampleSampler::PrimarySampleSampler(uint64_t seed, uint64_t stream, double large_step_probability, double s1,
                                           double s2)
    : m_rng(seed, stream), m_p_large(large_step_probability), m_s1(s1), m_s2(s2) {}

void PrimarySampleSampler::start_pixel_sample(int, int, uint64_t) { m_next = 0; }

void PrimarySampleSampler::start_iteration() {
    ++m_iteration;
    m_large_step = m_rng.next_double() < m_p_large;
    m_next = 0;
}

double PrimarySampleSampler::small_step(double x) {
    // Kelemen's exponential perturbation: magnitudes log-uniform in [s1, s2].
    const double sign = m_rng.next_double() < 0.5 ? -1.0 : 1.0;
    const double d = m_s2 * std::exp(-std::log(m_s2 / m_s1) * m_rng.next_double());
    x += sign * d;
    x -= std::floor(x);
    return x < 1.0 ? x : 0.0;  // x - floor(x) may round up to 1
}

void PrimarySampleSampler::update(size_t i) {
    Dim& d = m_dims[i];
    if (d.modified == m_iteration) return;
    d.backup = d.value;
    d.modified_backup = d.modified;
    if (m_large_step || d.modified < m_last_large_step) {
        // A large step, or one accepted since this dimension was last used, replaced it.
        d.value = m_rng.next_double();
    } else {
        // The small steps of the iterations this dimension sat out, then the current one.
        for (int64_t k = d.modified; k < m_iteration; ++k) d.value = small_step(d.value);
    }
    d.modified = m_iteration;
}

double PrimarySampleSampler::next_1d() {
    const size_t i = m_next++;
    if (i >= m_dims.size()) m_dims.resize(i + 1);  // new dimension: modified = -1 < any large step
    update(i);
    return m_dims[i].value;
}

void PrimarySampleSampler::accept() {
    if (m_large_step) m_last_large_step = m_iteration;
}

void PrimarySampleSampler::reject() {
    for (Dim& d : m_dims)
        if (d.modified == m_iteration) {
            d.value = d.backup;
            d.modified = d.modified_backup;
        }
    --m_iteration;
}

void PrimarySampleSampler::set_state(const std::vector<double>& values) {
    m_dims.assign(values.size(), Dim());
    for (size_t i = 0; i < values.size(); ++i) {
        m_dims[i].value = m_dims[i].backup = values[i];
        m_dims[i].modified = m_dims[i].modified_backup = m_iteration;
    }
    // Marking the state as a just-accepted large step makes update() draw every dimension
    // not in `values` fresh, and small-step the others from here on.
    m_last_large_step = m_iteration;
    m_large_step = false;
    m_next = 0;
}

}  // namespace snell
