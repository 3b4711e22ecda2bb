#pragma once
// False-colour relative-error images for comparison reports: how far each pixel of a render is
// from the reference, on the viridis colour map (perceptually uniform, readable in greyscale and
// by colour-blind readers; van der Walt & Smith's matplotlib default).
#include <array>
#include <cstdint>
#include <string>

#include "io/image.h"

namespace snell {

/// 8-bit sRGB-encoded colour (already display-ready; no transfer function is applied to it).
using Rgb8 = std::array<uint8_t, 3>;

/// Viridis at t in [0, 1] (clamped; NaN maps to t = 1), linearly interpolated between 9 samples
/// of the matplotlib table. t = 0 is dark purple, 0.5 teal, 1 yellow.
Rgb8 viridis(double t);

/// Per-pixel relative error sqrt(mean over RGB of (a - r)^2 / (r^2 + 0.01)): the square root of
/// the pixel's share of relMSE (report/image_metrics.h), so the image shows where relMSE comes from.
/// Both images must be the same size (not checked here).
double pixel_relative_error(const Image& img, const Image& ref, int x, int y);

/// Writes the relative error of `img` against `ref` as a PNG in viridis, pixel_relative_error
/// divided by `max_error` (errors >= max_error saturate to yellow). Throws std::invalid_argument
/// on a size mismatch and std::runtime_error naming the path when it cannot write.
void write_relative_error_png(const std::string& path, const Image& img, const Image& ref, double max_error = 1.0);

/// Writes 8-bit sRGB pixels (3 per pixel, row-major) as a PNG; throws naming the path.
void write_png_rgb8(const std::string& path, int width, int height, const uint8_t* rgb);

}  // namespace snell
