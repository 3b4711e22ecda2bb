#pragma once
#include <string>
#include <vector>

namespace snell {

/// An RGB(A-less) float image, row-major, 3 channels per pixel, linear values.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  ///< size 3 * width * height
    float& at(int x, int y, int c) { return rgb[(size_t(y) * width + x) * 3 + c]; }
    float at(int x, int y, int c) const { return rgb[(size_t(y) * width + x) * 3 + c]; }
};

/// Writes a linear half/float RGB OpenEXR file; throws std::runtime_error naming the path.
void write_exr(const std::string& path, const Image& img);
/// Reads an RGB(A) OpenEXR file (missing channels are zero); throws naming the path.
Image read_exr(const std::string& path);
/// Reads a Radiance RGBE (.hdr) file; throws naming the path.
Image read_hdr(const std::string& path);
/// read_exr or read_hdr by the file's extension (.exr, .hdr); anything else throws naming it.
Image read_image(const std::string& path);
/// Writes an 8-bit sRGB-encoded PNG after multiplying by 2^exposure; throws naming the path.
void write_png(const std::string& path, const Image& img, double exposure = 0.0);

}  // namespace snell
