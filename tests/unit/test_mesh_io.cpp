#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "io/mesh_obj.h"
#include "io/mesh_ply.h"
#include "io/mesh_serialized.h"

#include <zlib.h>

using namespace snell;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
    const fs::path d = fs::temp_directory_path() / ("snell_mesh_io_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

void write(const fs::path& p, const std::string& s) {
    std::ofstream f(p, std::ios::binary);
    f << s;
}

template <typename T>
void put(std::string& out, T v, bool big_endian) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_endian == (std::endian::native == std::endian::little))
        for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

void expect_throws_naming(const std::function<void()>& f, const std::string& path, const std::string& what = "") {
    try {
        f();
        ADD_FAILURE() << "no exception for " << path;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
        if (!what.empty()) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    }
}

}  // namespace

TEST(MeshIo, ObjQuadsNormalsUvs) {
    const fs::path p = temp_dir() / "quad.obj";
    write(p,
          "# two quads sharing an edge\n"
          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "vn 0 0 1\n"
          "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
          "f 2/1/1 5/2/1 6/3/1 3/4/1\n");
    const MeshData m = load_obj(p.string());
    EXPECT_EQ(m.triangles.size(), 4u);
    // Vertex 2 appears with two different uvs, so it is split: 8 unique corners.
    EXPECT_EQ(m.positions.size(), 8u);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    for (const auto& t : m.triangles) {
        const Vec3 n = cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(n.z, 0);  // winding preserved
        for (uint32_t k : t) EXPECT_EQ(m.normals[k], Vec3(0, 0, 1));
    }
}

TEST(MeshIo, ObjErrorsNameThePath) {
    const fs::path missing = temp_dir() / "does_not_exist.obj";
    expect_throws_naming([&] { load_obj(missing.string()); }, missing.string(), "not found");
    const fs::path bad = temp_dir() / "bad.obj";
    write(bad, "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    expect_throws_naming([&] { load_obj(bad.string()); }, bad.string());
}

TEST(MeshIo, PlyAscii) {
    const fs::path p = temp_dir() / "ascii.ply";
    write(p,
          "ply\nformat ascii 1.0\ncomment test\n"
          "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float "
          "t\n"
          "element face 2\nproperty list uchar int vertex_indices\n"
          "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
          "end_header\n"
          "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n0.5 2 0 0 0 1 0.5 1\n"
          "4 0 1 2 3\n3 3 2 4\n"
          "0 1\n");
    const MeshData m = load_ply(p.string());
    EXPECT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.normals.size(), 5u);
    ASSERT_EQ(m.uvs.size(), 5u);
    EXPECT_EQ(m.uvs[4].x, 0.5);
    EXPECT_EQ(m.positions[4].y, 2.0);
    EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{3, 2, 4}));
}

class MeshIoBinary : public ::testing::TestWithParam<bool> {};

TEST_P(MeshIoBinary, PlyBinary) {
    const bool big = GetParam();
    std::string body;
    const double pos[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0.5}};
    for (int i = 0; i < 4; ++i) {
        put<double>(body, pos[i][0], big);
        put<double>(body, pos[i][1], big);
        put<double>(body, pos[i][2], big);
        put<float>(body, 0.25f * float(i), big);  // u
        put<float>(body, 0.5f, big);              // v
        put<uint8_t>(body, 7, big);               // an ignored property
    }
    put<uint8_t>(body, 4, big);  // one quad with uint indices
    for (uint32_t k : {0u, 1u, 2u, 3u}) put<uint32_t>(body, k, big);
    put<int16_t>(body, -3, big);  // an ignored per-face property
    const std::string header = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                               " 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                               "property float u\nproperty float v\nproperty uchar flags\n"
                               "element face 1\nproperty list uchar uint vertex_index\nproperty short tag\n"
                               "end_header\n";
    const fs::path p = temp_dir() / (big ? "be.ply" : "le.ply");
    write(p, header + body);
    const MeshData m = load_ply(p.string());
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
    EXPECT_TRUE(m.normals.empty());
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.positions[3], Vec3(0, 1, 0.5));
    EXPECT_EQ(m.uvs[2].x, 0.5);

    // Truncated body: the error names the file.
    const fs::path t = temp_dir() / (big ? "be_trunc.ply" : "le_trunc.ply");
    write(t, header + body.substr(0, body.size() - 5));
    expect_throws_naming([&] { load_ply(t.string()); }, t.string(), "end of file");
}
INSTANTIATE_TEST_SUITE_P(Endianness, MeshIoBinary, ::testing::Values(false, true));

TEST(MeshIo, PlyErrorsNameThePath) {
    const fs::path missing = temp_dir() / "nope.ply";
    expect_throws_naming([&] { load_ply(missing.string()); }, missing.string(), "not found");
    const fs::path bad = temp_dir() / "bad_header.ply";
    write(bad, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n");
    expect_throws_naming([&] { load_ply(bad.string()); }, bad.string(), "x, y or z");
    const fs::path idx = temp_dir() / "bad_index.ply";
    write(idx,
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
          "float z\n"
          "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 "
          "0\n3 0 1 5\n");
    expect_throws_naming([&] { load_ply(idx.string()); }, idx.string(), "vertex 5");
    // Issue 12: a vertex index of 2^32, NaN or 2.7 (a float list) became some other vertex;
    // each is now an error naming the face. A vertex count of NaN too.
    for (const std::string bad_index : {"4294967296", "nan", "2.7"}) {
        const fs::path f = temp_dir() / "bad_float_index.ply";
        write(f,
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
              "float z\nelement face 1\nproperty list uchar double vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 "
              "0\n3 0 1 " +
                  bad_index + "\n");
        expect_throws_naming([&] { load_ply(f.string()); }, f.string(), "invalid vertex index");
    }
    const fs::path count = temp_dir() / "bad_count.ply";
    write(count,
          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty "
          "float z\nelement face 1\nproperty list double int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 "
          "0\nnan 0 1 2\n");
    expect_throws_naming([&] { load_ply(count.string()); }, count.string(), "bad PLY face vertex count");
    // Found by fuzz_loader under UBSan: a list length of -1 or NaN in a vertex or an unknown
    // element was converted to size_t (undefined behaviour), now it is an error naming the element.
    for (const std::string element : {"vertex", "edge"}) {
        const fs::path f = temp_dir() / "bad_list_length.ply";
        const bool in_vertex = element == "vertex";
        write(f, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" +
                     std::string(in_vertex ? "property list double int extra\n" : "") +
                     (in_vertex ? "" : "element edge 1\nproperty list double int ends\n") + "end_header\n" +
                     (in_vertex ? "0 0 0 -1\n1 0 0 0\n0 1 0 0\n" : "0 0 0\n1 0 0\n0 1 0\nnan 0 1\n"));
        expect_throws_naming([&] { load_ply(f.string()); }, f.string(), "bad PLY list length");
    }
}

// Found by fuzz_loader: a header claiming 10^12 vertices reserved terabytes (an abort under
// ASan, std::bad_alloc at best) before reading any vertex; now the file ends first, an error.
TEST(MeshIO, PlyHugeVertexCountIsAnErrorNotAnAllocation) {
    const fs::path f = temp_dir() / "huge_count.ply";
    write(f,
          "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
          "property float y\nproperty float z\nend_header\n");
    expect_throws_naming([&] { load_ply(f.string()); }, f.string(), "");
}

namespace {

// One mesh of Mitsuba's serialized format: header, then the zlib stream of its body.
std::string serialized_mesh(uint16_t version, uint32_t flags, const std::vector<Vec3>& p,
                            const std::vector<std::array<uint32_t, 3>>& tris, const std::vector<Vec2>& uv = {}) {
    std::string body;
    put<uint32_t>(body, flags, false);
    if (version == 4) body += std::string("mesh") + '\0';
    put<uint64_t>(body, p.size(), false);
    put<uint64_t>(body, tris.size(), false);
    const bool dbl = flags & serialized::kDoublePrecision;
    const auto real = [&](double x) { dbl ? put<double>(body, x, false) : put<float>(body, float(x), false); };
    for (const Vec3& v : p) real(v.x), real(v.y), real(v.z);
    for (const Vec2& t : uv) real(t.x), real(t.y);
    for (const auto& t : tris)
        for (uint32_t i : t) put<uint32_t>(body, i, false);
    uLongf n = compressBound(uLong(body.size()));
    std::string z(n, '\0');
    EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(body.data()),
                        uLong(body.size()), 6),
              Z_OK);
    z.resize(n);
    std::string out;
    put<uint16_t>(out, 0x041C, false);
    put<uint16_t>(out, version, false);
    return out + z;
}

// A file of meshes with the offset table at its end.
std::string serialized_file(uint16_t version, const std::vector<std::string>& meshes) {
    std::string out;
    std::vector<uint64_t> offsets;
    for (const auto& m : meshes) {
        offsets.push_back(out.size());
        out += m;
    }
    for (uint64_t o : offsets) version == 4 ? put<uint64_t>(out, o, false) : put<uint32_t>(out, uint32_t(o), false);
    put<uint32_t>(out, uint32_t(meshes.size()), false);
    return out;
}

const std::vector<Vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::array<uint32_t, 3>> kQuadTris = {{0, 1, 2}, {0, 2, 3}};

}  // namespace

// Mitsuba's serialized meshes: several per file (shape_index), versions 3 and 4, single and
// double precision, texture coordinates, the face-normal flag.
TEST(MeshIo, SerializedMeshes) {
    const fs::path f4 = temp_dir() / "two.serialized";
    write(f4,
          serialized_file(
              4, {serialized_mesh(4, serialized::kSinglePrecision, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}),
                  serialized_mesh(4, serialized::kDoublePrecision | serialized::kTexcoords | serialized::kFaceNormals,
                                  kQuad, kQuadTris, {{0, 0}, {1, 0}, {1, 1}, {0.25, 1}})}));
    bool face = true;
    const MeshData a = load_serialized(f4.string(), 0, &face);
    EXPECT_EQ(a.positions.size(), 3u);
    EXPECT_EQ(a.triangles.size(), 1u);
    EXPECT_FALSE(face);
    const MeshData b = load_serialized(f4.string(), 1, &face);
    ASSERT_EQ(b.positions.size(), 4u);
    ASSERT_EQ(b.triangles.size(), 2u);
    EXPECT_EQ(b.positions[2].x, 1.0);
    EXPECT_EQ(b.triangles[1][2], 3u);
    ASSERT_EQ(b.uvs.size(), 4u);
    EXPECT_EQ(b.uvs[3].x, 0.25);
    EXPECT_TRUE(face);
    const fs::path f3 = temp_dir() / "one.serialized";
    write(f3, serialized_file(3, {serialized_mesh(3, serialized::kSinglePrecision, kQuad, kQuadTris)}));
    EXPECT_EQ(load_serialized(f3.string(), 0).triangles.size(), 2u);
}

TEST(MeshIo, SerializedErrorsNameThePath) {
    const auto error = [](const std::string& bytes, int64_t index = 0) {
        const fs::path f = temp_dir() / "bad.serialized";
        write(f, bytes);
        try {
            load_serialized(f.string(), index);
        } catch (const std::runtime_error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("bad.serialized"), std::string::npos) << msg;
            return msg;
        }
        return std::string("no error");
    };
    const std::string good = serialized_file(4, {serialized_mesh(4, serialized::kSinglePrecision, kQuad, kQuadTris)});
    EXPECT_NE(error(good, 1).find("shape_index 1 out of range (the file has 1 mesh)"), std::string::npos);
    EXPECT_NE(error(good, -1).find("out of range"), std::string::npos);
    EXPECT_NE(error("PLY\n" + good).find("bad identifier"), std::string::npos);
    EXPECT_NE(error(good.substr(0, 6)).find("too short"), std::string::npos);
    // A corrupt compressed stream, and one cut short.
    std::string corrupt = good;
    corrupt[10] = char(corrupt[10] ^ 0x5a);
    corrupt[11] = char(corrupt[11] ^ 0x5a);
    EXPECT_NE(error(corrupt).find("bad.serialized"), std::string::npos);
    // Counts larger than the data, and an index past the vertices.
    EXPECT_NE(error(serialized_file(4, {serialized_mesh(4, serialized::kSinglePrecision, kQuad, {{0, 1, 7}})}))
                  .find("index 7 out of range"),
              std::string::npos);
    std::string missing_table = good;
    missing_table.resize(missing_table.size() - 4);
    put<uint32_t>(missing_table, 1000000, false);
    EXPECT_NE(error(missing_table).find("corrupt offset table"), std::string::npos);
    EXPECT_NE(error("").find("too short"), std::string::npos);
}

namespace {

// A version-4 file of one mesh whose zlib stream holds `body` and then `zeros` zero bytes
// (deflated piecewise: the zeros never sit in memory whole).
std::string serialized_with_tail(const std::string& body, size_t zeros) {
    z_stream z{};
    EXPECT_EQ(deflateInit(&z, 9), Z_OK);
    std::string out;
    std::vector<unsigned char> buf(1 << 16);
    const auto pump = [&](const unsigned char* in, size_t n, int flush) {
        z.next_in = const_cast<unsigned char*>(in);
        z.avail_in = uInt(n);
        do {
            z.next_out = buf.data();
            z.avail_out = uInt(buf.size());
            deflate(&z, flush);
            out.append(reinterpret_cast<const char*>(buf.data()), buf.size() - z.avail_out);
        } while (z.avail_out == 0);
    };
    pump(reinterpret_cast<const unsigned char*>(body.data()), body.size(), Z_NO_FLUSH);
    const std::vector<unsigned char> chunk(1 << 20, 0);
    for (size_t left = zeros; left > 0; left -= std::min(left, chunk.size()))
        pump(chunk.data(), std::min(left, chunk.size()), Z_NO_FLUSH);
    pump(nullptr, 0, Z_FINISH);
    deflateEnd(&z);
    std::string mesh;
    put<uint16_t>(mesh, 0x041C, false);
    put<uint16_t>(mesh, 4, false);
    return serialized_file(4, {mesh + out});
}

std::string quad_body(uint64_t nv, uint64_t nt) {
    std::string body;
    put<uint32_t>(body, serialized::kSinglePrecision, false);
    body += std::string("bomb") + '\0';
    put<uint64_t>(body, nv, false);
    put<uint64_t>(body, nt, false);
    for (const Vec3& v : kQuad)
        put<float>(body, float(v.x), false), put<float>(body, float(v.y), false), put<float>(body, float(v.z), false);
    for (const auto& t : kQuadTris)
        for (uint32_t i : t) put<uint32_t>(body, i, false);
    return body;
}

long peak_rss_kb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

}  // namespace

// Issue 30: an offset-table entry near 2^64 wrapped `begin + 4 < end` and read before the buffer.
TEST(MeshIo, SerializedOffsetNearTwoToTheSixtyFourIsCorrupt) {
    const fs::path f = temp_dir() / "wrap.serialized";
    std::string bytes = serialized_file(4, {serialized_mesh(4, serialized::kSinglePrecision, kQuad, kQuadTris)});
    bytes.replace(bytes.size() - 12, 8, std::string("\xfe\xff\xff\xff\xff\xff\xff\xff", 8));
    write(f, bytes);
    expect_throws_naming([&] { load_serialized(f.string(), 0); }, f.string(), "corrupt offset table");
}

// Issue 30: a small file inflating to gigabytes. The body is inflated only as far as its counts
// reach (a valid quad followed by 256 MB of zeros loads, without inflating the zeros), and counts
// that no deflate stream of the file's size can hold are refused before inflating anything.
// The bombs stay within 100 MB (the whole stream took more than 512 MB before).
TEST(MeshIo, SerializedBombsAreNotInflated) {
    const long before = peak_rss_kb();
    const fs::path tail = temp_dir() / "tail.serialized";
    write(tail, serialized_with_tail(quad_body(4, 2), size_t(256) << 20));
    const MeshData m = load_serialized(tail.string(), 0);
    EXPECT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
    const fs::path claims = temp_dir() / "claims.serialized";
    write(claims, serialized_with_tail(quad_body(uint64_t(1) << 33, uint64_t(1) << 33), size_t(16) << 20));
    expect_throws_naming([&] { load_serialized(claims.string(), 0); }, claims.string(), "compressed bytes can hold");
    EXPECT_LT(peak_rss_kb() - before, 100 * 1024) << "kB of peak memory";
}
