#include "io/volume_grid.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace snell {

VolumeGrid read_volume_grid(const std::string& path) {
    auto fail = [&](const std::string& what) -> void { throw std::runtime_error(path + ": " + what); };
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) fail("volume file not found");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open volume file");
    char magic[4] = {};
    in.read(magic, 4);
    if (!in || std::memcmp(magic, "VOL", 3) != 0) fail("not a Mitsuba volume file (no 'VOL' header)");
    if (magic[3] != 3) fail("unsupported .vol version " + std::to_string(int(magic[3])) + " (expected 3)");
    int32_t head[5] = {};
    in.read(reinterpret_cast<char*>(head), sizeof(head));
    if (!in) fail("truncated .vol header");
    if (head[0] != 1) fail("unsupported .vol encoding " + std::to_string(head[0]) + " (only 1, float32)");
    VolumeGrid g;
    g.xres = head[1];
    g.yres = head[2];
    g.zres = head[3];
    g.channels = head[4];
    if (g.xres <= 0 || g.yres <= 0 || g.zres <= 0) fail("bad .vol resolution");
    if (g.channels != 1 && g.channels != 3) fail(".vol has " + std::to_string(g.channels) + " channels (1 or 3)");
    in.read(reinterpret_cast<char*>(g.bbox.data()), sizeof(float) * 6);
    if (!in) fail("truncated .vol header");
    const uint64_t n = uint64_t(g.xres) * uint64_t(g.yres) * uint64_t(g.zres) * uint64_t(g.channels);
    if (n > (uint64_t(1) << 31)) fail(".vol grid too large");
    // Checked against the file's size before allocating: a 48-byte file could ask for 8 GiB.
    const std::streamoff header_end = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff file_end = in.tellg();
    in.seekg(header_end);
    if (header_end < 0 || file_end < header_end || uint64_t(file_end - header_end) / sizeof(float) < n)
        fail("truncated .vol data (expected " + std::to_string(n) + " values)");
    g.data.resize(size_t(n));
    in.read(reinterpret_cast<char*>(g.data.data()), std::streamsize(n * sizeof(float)));
    if (!in) fail("truncated .vol data (expected " + std::to_string(n) + " values)");
    for (float v : g.data)
        if (!std::isfinite(v)) fail("non-finite value in .vol data");
    return g;
}

}  // namespace snell
