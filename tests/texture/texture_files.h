#pragma once
// Small image files written by the tests themselves (nothing is fetched): 8-bit sRGB PNGs and
// float EXRs through OpenImageIO, in a fresh temporary folder per test binary.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace snell::test {

inline std::filesystem::path texture_dir() {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("snell-textures-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

/// Writes `pixels` (row-major from the top row, `channels` per pixel) as `name` in texture_dir()
/// with OpenImageIO: uint8 for .png/.jpg/.tif, float for .exr/.hdr. Returns the full path.
template <typename T>
inline std::string write_texture(const std::string& name, int w, int h, int channels, const std::vector<T>& pixels) {
    const std::string path = (texture_dir() / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out) << OIIO::geterror();
    if (!out) return path;
    const OIIO::TypeDesc type = std::is_same_v<T, uint8_t> ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(w, h, channels, type);
    EXPECT_TRUE(out->open(path, spec)) << out->geterror();
    EXPECT_TRUE(out->write_image(type, pixels.data())) << out->geterror();
    out->close();
    return path;
}

}  // namespace snell::test
