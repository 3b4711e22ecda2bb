#pragma once
// sRGB's transfer functions (IEC 61966-2-1): 8-bit images store encoded values, snell computes in
// linear ones. Shared by the image reader (io/), the bitmap texture (texture/) and the PNG writer.
#include <algorithm>
#include <cmath>

namespace snell {

/// sRGB's decoding curve, from encoded [0, 1] to linear.
inline double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

/// sRGB's encoding curve, from linear to encoded; the input is clamped to [0, 1].
inline double linear_to_srgb(double v) {
    v = std::clamp(v, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

}  // namespace snell
