#pragma once
#include <string>
#include <vector>

#include "core/vector.h"

namespace snell {

/// Accumulates XYZ per pixel (box filter: each sample lands in the pixel it was taken in).
/// Sample weights are counted per pixel so a partially rendered (interrupted or time-limited)
/// film still resolves to an unbiased average for the pixels it reached.
class Film {
public:
    Film(int width, int height) : m_w(width), m_h(height), m_xyz(size_t(width) * height), m_n(size_t(width) * height, 0) {}
    int width() const { return m_w; }
    int height() const { return m_h; }
    void add(int x, int y, const Vec3& xyz) {
        const size_t i = size_t(y) * m_w + x;
        m_xyz[i] += xyz;
        m_n[i] += 1;
    }
    /// Adds `count` samples at once (whole-pixel sums from a tile).
    void add_sum(int x, int y, const Vec3& xyz_sum, uint64_t count) {
        const size_t i = size_t(y) * m_w + x;
        m_xyz[i] += xyz_sum;
        m_n[i] += count;
    }
    uint64_t samples(int x, int y) const { return m_n[size_t(y) * m_w + x]; }
    /// Mean XYZ of the pixel (zero if it has no samples).
    Vec3 xyz(int x, int y) const {
        const size_t i = size_t(y) * m_w + x;
        return m_n[i] ? m_xyz[i] / double(m_n[i]) : Vec3();
    }
    /// Linear sRGB image, row-major, 3 floats per pixel.
    std::vector<float> to_linear_srgb() const;

private:
    int m_w, m_h;
    std::vector<Vec3> m_xyz;
    std::vector<uint64_t> m_n;
};

}  // namespace snell
