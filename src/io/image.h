#pragma once
#include <cstdint>
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
/// Largest image snell reads (textures, environment maps, references): 2^27 pixels (16384 x 8192)
/// and 2^29 floats in all channels. Checked from the header, before any pixel buffer is allocated
/// (issue 12: a tiny file whose header claimed 7 GB of pixels made the allocation fail).
constexpr int64_t kMaxImagePixels = int64_t(1) << 27;
constexpr int64_t kMaxImageFloats = int64_t(1) << 29;
/// Throws "<what> '<path>': ..." unless a w x h image of `channels` channels is within the limits.
void check_image_size(const std::string& what, const std::string& path, int64_t w, int64_t h, int64_t channels);
/// Any image OpenImageIO reads (OpenEXR, Radiance .hdr, PNG, JPEG, TIFF, ...) through
/// read_texture_image's checks, as linear RGB: sRGB-encoded files are linearised, grey is spread
/// to three channels, alpha dropped. Throws naming the path.
Image read_image(const std::string& path);
/// Writes an 8-bit sRGB-encoded PNG after multiplying by 2^exposure; throws naming the path.
void write_png(const std::string& path, const Image& img, double exposure = 0.0);

}  // namespace snell
