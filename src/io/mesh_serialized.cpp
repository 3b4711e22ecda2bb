#include "io/mesh_serialized.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace snell {

namespace {

constexpr uint16_t kMagic = 0x041C;

// Little-endian reads from a byte buffer, with bounds checks that name the file.
class Reader {
public:
    Reader(const std::vector<unsigned char>& data, std::string what) : m_data(data), m_what(std::move(what)) {}
    template <typename T>
    T get() {
        need(sizeof(T));
        T v = 0;
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, m_data.data() + m_pos, sizeof(T));
        if constexpr (std::is_integral_v<T>) {
            using U = std::make_unsigned_t<T>;
            U u = 0;
            for (size_t i = 0; i < sizeof(T); ++i) u |= U(bytes[i]) << (8 * i);
            v = T(u);
        } else {
            // Floats: the host is little endian (x86-64, arm64), as the format.
            std::memcpy(&v, bytes, sizeof(T));
        }
        m_pos += sizeof(T);
        return v;
    }
    std::string cstring() {
        std::string s;
        for (;;) {
            need(1);
            const char c = char(m_data[m_pos++]);
            if (c == 0) return s;
            s += c;
        }
    }
    void need(size_t n) const {
        if (m_data.size() - m_pos < n) throw std::runtime_error(m_what + ": truncated mesh data");
    }
    size_t pos() const { return m_pos; }
    void seek(size_t p) { m_pos = p; }

private:
    const std::vector<unsigned char>& m_data;
    std::string m_what;
    size_t m_pos = 0;
};

std::vector<unsigned char> read_all(const std::string& path) {
    std::error_code ec;  // only regular files: opening a FIFO would block (issue 12)
    if (!std::filesystem::is_regular_file(path, ec))
        throw std::runtime_error("cannot open serialized mesh '" + path + "'");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open serialized mesh '" + path + "'");
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string s = ss.str();
    return std::vector<unsigned char>(s.begin(), s.end());
}

// zlib inflation on demand: the mesh body is inflated only as far as its header's counts say it
// reaches, so a small file cannot expand into gigabytes before those counts are checked (issue
// 30: 1.5 MB of zeros inflated to a 4.8 GB peak before the mesh was looked at).
class Inflater {
public:
    Inflater(const unsigned char* in, size_t n, std::string path) : m_path(std::move(path)) {
        if (inflateInit(&m_z) != Z_OK) throw std::runtime_error(m_path + ": zlib initialisation failed");
        m_z.next_in = const_cast<unsigned char*>(in);
        m_z.avail_in = uInt(std::min<size_t>(n, std::numeric_limits<uInt>::max()));
    }
    ~Inflater() { inflateEnd(&m_z); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    /// Inflates until `bytes` are out (or the stream ends first); returns what is out so far.
    const std::vector<unsigned char>& inflate_to(size_t bytes) {
        if (bytes > m_out.size()) m_out.resize(bytes);
        while (!m_ended && m_z.total_out < bytes) {
            m_z.next_out = m_out.data() + m_z.total_out;
            m_z.avail_out = uInt(std::min<size_t>(bytes - m_z.total_out, std::numeric_limits<uInt>::max()));
            int rc = inflate(&m_z, Z_NO_FLUSH);
            if (rc == Z_BUF_ERROR && m_z.avail_in == 0) rc = Z_DATA_ERROR;  // the stream ends early
            if (rc == Z_STREAM_END) m_ended = true;
            if (rc != Z_OK && rc != Z_STREAM_END)
                throw std::runtime_error(m_path + ": corrupt compressed mesh data (zlib error " + std::to_string(rc) +
                                         ")");
        }
        m_out.resize(size_t(m_z.total_out));
        return m_out;
    }

private:
    z_stream m_z{};
    std::vector<unsigned char> m_out;
    bool m_ended = false;
    std::string m_path;
};

// Deflate's densest stream expands 1032-fold (zlib's technical notes): a body longer than that
// times its compressed size cannot be in the file, whatever its header claims.
constexpr uint64_t kMaxDeflateRatio = 1032;

template <typename T>
Vec3 get_vec3(Reader& r) {
    const double x = double(r.get<T>()), y = double(r.get<T>()), z = double(r.get<T>());
    return {x, y, z};
}

}  // namespace

MeshData load_serialized(const std::string& path, int64_t shape_index, bool* face_normals) {
    const std::vector<unsigned char> file = read_all(path);
    Reader head(file, path);
    if (file.size() < 8) throw std::runtime_error(path + ": not a serialized mesh (file too short)");
    if (head.get<uint16_t>() != kMagic) throw std::runtime_error(path + ": not a serialized mesh (bad identifier)");
    const uint16_t version = head.get<uint16_t>();
    if (version != 3 && version != 4)
        throw std::runtime_error(path + ": serialized mesh version " + std::to_string(version) + " (3 and 4 are read)");
    // The offset table at the end: one offset per mesh (u64 in version 4, u32 in 3), then the count.
    head.seek(file.size() - 4);
    const uint32_t count = head.get<uint32_t>();
    const size_t entry = version == 4 ? 8 : 4;
    if (count == 0 || uint64_t(count) * entry + 4 > file.size())
        throw std::runtime_error(path + ": corrupt offset table (" + std::to_string(count) + " meshes)");
    if (shape_index < 0 || shape_index >= int64_t(count))
        throw std::runtime_error(path + ": shape_index " + std::to_string(shape_index) +
                                 " out of range (the file has " + std::to_string(count) + " mesh" +
                                 (count == 1 ? "" : "es") + ")");
    const size_t table = file.size() - 4 - size_t(count) * entry;
    const auto offset_of = [&](size_t i) -> uint64_t {
        head.seek(table + i * entry);
        return version == 4 ? head.get<uint64_t>() : head.get<uint32_t>();
    };
    const uint64_t begin = offset_of(size_t(shape_index));
    const uint64_t end = size_t(shape_index) + 1 < count ? offset_of(size_t(shape_index) + 1) : table;
    // Subtractions that cannot wrap: an entry near 2^64 made begin + 4 overflow (issue 30).
    if (!(begin < end && end <= table && end - begin > 4))
        throw std::runtime_error(path + ": corrupt offset table (mesh " + std::to_string(shape_index) + ")");
    head.seek(size_t(begin));
    if (head.get<uint16_t>() != kMagic || head.get<uint16_t>() != version)
        throw std::runtime_error(path + ": mesh " + std::to_string(shape_index) + " has a bad header");

    const size_t compressed = size_t(end - begin - 4);
    Inflater body(file.data() + begin + 4, compressed, path);
    // The header first: flags, the name (version 4), the counts. Names longer than this are refused.
    constexpr size_t kHeaderBytes = 4 + 65536 + 16;
    std::vector<unsigned char> header = body.inflate_to(kHeaderBytes);
    Reader h(header, path);
    const uint32_t flags = h.get<uint32_t>();
    if (version == 4) (void)h.cstring();  // the mesh's name
    const uint64_t nv = h.get<uint64_t>(), nt = h.get<uint64_t>();
    const size_t header_size = h.pos();
    const bool dbl = flags & serialized::kDoublePrecision;
    const size_t real = dbl ? 8 : 4;
    // Every count is checked against the bytes the stream can hold before it is inflated, and
    // against the bytes it does hold before anything is allocated.
    const uint64_t per_vertex = 3 * real + ((flags & serialized::kVertexNormals) ? 3 * real : 0) +
                                ((flags & serialized::kTexcoords) ? 2 * real : 0) +
                                ((flags & serialized::kVertexColors) ? 3 * real : 0);
    const size_t index_size = nv > std::numeric_limits<uint32_t>::max() ? 8 : 4;
    const uint64_t can_hold = kMaxDeflateRatio * uint64_t(compressed) + 64;
    const auto too_many = [&](const std::string& than) {
        return std::runtime_error(path + ": mesh " + std::to_string(shape_index) + " claims " + std::to_string(nv) +
                                  " vertices and " + std::to_string(nt) + " triangles, more than " + than);
    };
    if (header_size > can_hold || nv == 0 || nt == 0 || nv > can_hold / per_vertex ||
        nt > can_hold / (3 * index_size) || nv * per_vertex + nt * 3 * index_size > can_hold - header_size)
        throw too_many("its " + std::to_string(compressed) + " compressed bytes can hold");
    const std::vector<unsigned char>& data =
        body.inflate_to(size_t(header_size + nv * per_vertex + nt * 3 * index_size));
    if (data.size() < header_size + nv * per_vertex + nt * 3 * index_size) throw too_many("its data holds");
    Reader r(data, path);
    r.seek(header_size);
    if (nv > std::numeric_limits<uint32_t>::max())
        throw std::runtime_error(path + ": more than 2^32 vertices in one mesh");

    MeshData m;
    m.positions.resize(size_t(nv));
    for (Vec3& p : m.positions) p = dbl ? get_vec3<double>(r) : get_vec3<float>(r);
    if (flags & serialized::kVertexNormals) {
        m.normals.resize(size_t(nv));
        for (Vec3& n : m.normals) n = dbl ? get_vec3<double>(r) : get_vec3<float>(r);
    }
    if (flags & serialized::kTexcoords) {
        m.uvs.resize(size_t(nv));
        for (Vec2& uv : m.uvs) {
            const double u = dbl ? r.get<double>() : double(r.get<float>());
            const double v = dbl ? r.get<double>() : double(r.get<float>());
            uv = Vec2(u, v);
        }
    }
    if (flags & serialized::kVertexColors)
        for (uint64_t i = 0; i < nv; ++i) (void)(dbl ? get_vec3<double>(r) : get_vec3<float>(r));  // not used
    m.triangles.resize(size_t(nt));
    for (auto& t : m.triangles)
        for (uint32_t& i : t) {
            const uint64_t v = index_size == 8 ? r.get<uint64_t>() : r.get<uint32_t>();
            if (v >= nv)
                throw std::runtime_error(path + ": triangle index " + std::to_string(v) + " out of range (" +
                                         std::to_string(nv) + " vertices)");
            i = uint32_t(v);
        }
    if (face_normals) *face_normals = flags & serialized::kFaceNormals;
    validate_mesh(m, path);
    return m;
}

}  // namespace snell
