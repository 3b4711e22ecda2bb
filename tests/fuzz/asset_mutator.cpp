#include "fuzz/asset_mutator.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <random>
#include <vector>

namespace snell::fuzz {

namespace {

// Edge values of an unsigned field: zero, one, small, the 8/16/32/64-bit limits and their
// neighbours (a count of 2^32 - 1 wraps a 32-bit multiplication, 2^63 a signed one).
const uint64_t kEdges[] = {0,
                           1,
                           2,
                           3,
                           7,
                           255,
                           256,
                           65535,
                           65536,
                           8192,
                           1u << 20,
                           0x7fffffffu,
                           0x80000000u,
                           0xffffffffu,
                           0x100000000ull,
                           0x7fffffffffffffffull,
                           0x8000000000000000ull,
                           0xfffffffffffffff0ull,
                           0xffffffffffffffffull};

struct Rng {
    std::mt19937_64 g;
    size_t pick(size_t n) { return n ? std::uniform_int_distribution<size_t>(0, n - 1)(g) : 0; }
    uint64_t edge() { return kEdges[pick(std::size(kEdges))]; }
};

std::string lower_extension(const std::string& name) {
    const size_t dot = name.rfind('.');
    std::string e = dot == std::string::npos ? "" : name.substr(dot);
    for (char& c : e) c = char(std::tolower((unsigned char)c));
    return e;
}

void put_le(std::string& d, size_t at, uint64_t v, size_t bytes) {
    for (size_t i = 0; i < bytes && at + i < d.size(); ++i) d[at + i] = char((v >> (8 * i)) & 0xff);
}
void put_be(std::string& d, size_t at, uint64_t v, size_t bytes) {
    for (size_t i = 0; i < bytes && at + i < d.size(); ++i) d[at + i] = char((v >> (8 * (bytes - 1 - i))) & 0xff);
}

// The file cut at a random point (a truncated download or copy): the readers must notice.
bool truncate(std::string& d, Rng& r) {
    if (d.size() < 2) return false;
    d.resize(1 + r.pick(d.size() - 1));
    return true;
}

// A decimal number in a text line that starts with `prefix` ("element vertex", "f ", "-Y")
// replaced by an edge value (or its negative).
bool patch_text_number(std::string& d, const std::string& prefix, Rng& r, size_t limit = std::string::npos) {
    std::vector<size_t> lines;
    for (size_t at = 0; at < std::min(d.size(), limit) && lines.size() < 4096;) {
        if (d.compare(at, prefix.size(), prefix) == 0) lines.push_back(at);
        const size_t nl = d.find('\n', at);
        if (nl == std::string::npos) break;
        at = nl + 1;
    }
    if (lines.empty()) return false;
    const size_t start = lines[r.pick(lines.size())], end = std::min(d.find('\n', start), d.size());
    std::vector<std::pair<size_t, size_t>> numbers;  // [begin, end) of each digit run
    for (size_t i = start + prefix.size(); i < end;) {
        if (std::isdigit((unsigned char)d[i])) {
            size_t j = i;
            while (j < end && std::isdigit((unsigned char)d[j])) ++j;
            numbers.push_back({i, j});
            i = j;
        } else {
            ++i;
        }
    }
    if (numbers.empty()) return false;
    const auto [b, e] = numbers[r.pick(numbers.size())];
    std::string v = std::to_string(r.edge());
    if (r.pick(4) == 0) v = "-" + v;
    d.replace(b, e - b, v);
    return true;
}

// zlib, for the streams of .serialized meshes and PNG's IDAT.
bool inflate_prefix(const std::string& in, size_t offset, std::string& out, size_t limit) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return false;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + offset));
    z.avail_in = uInt(in.size() - offset);
    out.assign(limit, '\0');
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(limit);
    const int rc = inflate(&z, Z_FINISH);
    out.resize(z.total_out);
    inflateEnd(&z);
    return (rc == Z_STREAM_END || rc == Z_BUF_ERROR || rc == Z_OK) && !out.empty();
}
std::string deflate_all(const std::string& in) {
    uLongf n = compressBound(uLong(in.size()));
    std::string out(n, '\0');
    if (compress(reinterpret_cast<Bytef*>(out.data()), &n, reinterpret_cast<const Bytef*>(in.data()),
                 uLong(in.size())) != Z_OK)
        return {};
    out.resize(n);
    return out;
}

// Mitsuba's serialized mesh: u16 0x041C, u16 version, a zlib stream (u32 flags, [name], u64
// vertex count, u64 triangle count, arrays), and for several meshes an offset table at the end
// (one offset per mesh, u64 in version 4, then a u32 count).
bool mutate_serialized(std::string& d, Rng& r) {
    if (d.size() < 8) return false;
    switch (r.pick(3)) {
        case 0: {  // the offset table: the count (last 4 bytes) or an entry before it
            const size_t back = r.pick(2) == 0 ? 4 : 4 + 8 * (1 + r.pick(4));
            if (back > d.size()) return false;
            put_le(d, d.size() - back, r.edge(), back == 4 ? 4 : 8);
            return true;
        }
        case 1: {  // a field of the first mesh's header, its stream compressed again
            std::string body;
            if (!inflate_prefix(d, 4, body, size_t(1) << 22) || body.size() < 24) return false;
            // The counts follow the flags and, in version 4, the name's NUL: patch a u64 near
            // the start, aligned to any byte (the name's length moves them).
            const size_t at = 4 + r.pick(std::min<size_t>(body.size() - 8, 64));
            put_le(body, at, r.edge(), r.pick(2) == 0 ? 8 : 4);
            const std::string z = deflate_all(body);
            if (z.empty()) return false;
            // The first mesh alone, with its one-entry table (offset 0, count 1).
            const size_t entry = uint8_t(d[2]) == 4 ? 8 : 4;
            d = d.substr(0, 4) + z + std::string(entry + 4, '\0');
            put_le(d, d.size() - 4, 1, 4);
            return true;
        }
        default:
            return truncate(d, r);
    }
}

// A PNG chunk's 32-bit fields patched, its CRC recomputed, so that libpng reads the lie.
bool mutate_png(std::string& d, Rng& r) {
    if (d.size() < 33 || d.compare(12, 4, "IHDR") != 0) return truncate(d, r);
    if (r.pick(3) == 0) return truncate(d, r);
    const size_t field = r.pick(3);  // width, height, or bit depth / colour type
    if (field < 2)
        put_be(d, 16 + 4 * field, r.edge(), 4);
    else
        d[24 + r.pick(2)] = char(r.pick(2) ? r.edge() : r.pick(17));
    const uLong crc = crc32(0, reinterpret_cast<const Bytef*>(d.data() + 12), 17);
    put_be(d, 29, crc, 4);
    return true;
}

// OpenEXR: the box2i of dataWindow or displayWindow (four i32 after "NAME\0box2i\0" and a size),
// or an entry of the scanline offset table that follows the header.
bool mutate_exr(std::string& d, Rng& r) {
    if (r.pick(4) == 0) return truncate(d, r);
    const char* names[] = {"dataWindow", "displayWindow"};
    const std::string key = std::string(names[r.pick(2)]) + std::string("\0box2i\0", 7);
    const size_t at = d.find(key);
    if (at == std::string::npos) return truncate(d, r);
    const size_t box = at + key.size() + 4;
    if (r.pick(3) == 0) {  // an offset table entry: the header ends with a NUL after the last attribute
        const size_t end = d.find(std::string("\0", 1), box + 16);
        if (end != std::string::npos && end + 9 < d.size()) {
            put_le(d, end + 1 + 8 * r.pick(4), r.edge(), 8);
            return true;
        }
    }
    uint64_t v = r.edge();
    if (r.pick(3) == 0) v = uint64_t(-int64_t(v & 0xffffffff));
    put_le(d, box + 4 * r.pick(4), v, 4);
    return true;
}

// JPEG: the frame header's height and width (SOF0..SOF2: FF C0..C2, length, precision, h, w).
bool mutate_jpeg(std::string& d, Rng& r) {
    if (r.pick(3) == 0) return truncate(d, r);
    for (size_t i = 2; i + 9 < d.size(); ++i)
        if (uint8_t(d[i]) == 0xFF && uint8_t(d[i + 1]) >= 0xC0 && uint8_t(d[i + 1]) <= 0xC2) {
            put_be(d, i + 5 + 2 * r.pick(2), r.edge(), 2);
            return true;
        }
    return truncate(d, r);
}

// Radiance .hdr: the resolution line's numbers, or a run-length scanline header (2, 2, width).
bool mutate_hdr(std::string& d, Rng& r) {
    const size_t body = d.find("\n-Y ");
    if (body == std::string::npos || r.pick(3) == 0) return truncate(d, r);
    if (r.pick(2) == 0) return patch_text_number(d, "-Y ", r, body + 64);
    const size_t line_end = d.find('\n', body + 1);
    if (line_end == std::string::npos || line_end + 5 > d.size()) return truncate(d, r);
    const size_t at = line_end + 1 + (r.pick(2) ? 0 : r.pick(d.size() - line_end - 4));
    put_be(d, at + 2, r.edge(), 2);
    return true;
}

// Mitsuba .vol: "VOL" 3, then i32 encoding, x, y, z resolution and channel count.
bool mutate_vol(std::string& d, Rng& r) {
    if (d.size() < 24 || d.compare(0, 3, "VOL") != 0 || r.pick(4) == 0) return truncate(d, r);
    put_le(d, 4 + 4 * r.pick(5), r.edge(), 4);
    return true;
}

}  // namespace

bool mutate_asset(const std::string& name, std::string& data, uint64_t seed) {
    Rng r{std::mt19937_64(seed)};
    const std::string e = lower_extension(name);
    if (e == ".serialized") return mutate_serialized(data, r);
    if (e == ".png") return mutate_png(data, r);
    if (e == ".exr") return mutate_exr(data, r);
    if (e == ".jpg" || e == ".jpeg") return mutate_jpeg(data, r);
    if (e == ".hdr" || e == ".rgbe" || e == ".pic") return mutate_hdr(data, r);
    if (e == ".vol") return mutate_vol(data, r);
    if (e == ".ply") {
        const size_t header = data.find("end_header");
        if (r.pick(3) == 0 || header == std::string::npos) return truncate(data, r);
        return patch_text_number(data, "element ", r, header) || truncate(data, r);
    }
    if (e == ".obj") return r.pick(3) == 0 ? truncate(data, r) : patch_text_number(data, "f ", r) || truncate(data, r);
    if (e == ".xml") return false;  // the tree mutator's, or bytes
    return truncate(data, r);
}

}  // namespace snell::fuzz
