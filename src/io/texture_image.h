#pragma once
// Image files for textures, read with OpenImageIO: PNG, JPEG, OpenEXR, Radiance HDR, TIFF and
// whatever else the installed OpenImageIO reads. Only the pixels: filtering, wrapping and colour
// handling belong to texture/.
#include <cstdint>
#include <string>
#include <vector>

namespace snell {

struct TextureImage {
    int width = 0, height = 0;
    int channels = 0;           ///< 1 (grey) or 3 (RGB): alpha is dropped, grey+alpha is grey
    std::vector<float> texels;  ///< row-major from the file's first (top) row, `channels` per texel
    /// The values are sRGB-encoded (8- and 16-bit integer files unless the file says it is
    /// linear): the texture layer linearises them unless told the data is raw.
    bool srgb_encoded = false;
};

/// The most pixels one byte of an image file can encode, and the pixels any file may claim on top.
constexpr int64_t kMaxPixelsPerByte = 16384;
constexpr int64_t kFreePixels = int64_t(1) << 20;
/// Throws naming the path unless a w x h image fits in a file of `bytes` bytes by that bound.
void check_image_size_against_file(const std::string& path, int64_t w, int64_t h, uintmax_t bytes);

/// Reads the first subimage; throws std::runtime_error naming the path and OpenImageIO's reason.
TextureImage read_texture_image(const std::string& path);

}  // namespace snell
