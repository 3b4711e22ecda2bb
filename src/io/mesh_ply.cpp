#include "io/mesh_ply.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace snell {
namespace {

enum class PlyType { I8, U8, I16, U16, I32, U32, F32, F64, Invalid };

PlyType parse_type(const std::string& s) {
    if (s == "char" || s == "int8") return PlyType::I8;
    if (s == "uchar" || s == "uint8") return PlyType::U8;
    if (s == "short" || s == "int16") return PlyType::I16;
    if (s == "ushort" || s == "uint16") return PlyType::U16;
    if (s == "int" || s == "int32") return PlyType::I32;
    if (s == "uint" || s == "uint32") return PlyType::U32;
    if (s == "float" || s == "float32") return PlyType::F32;
    if (s == "double" || s == "float64") return PlyType::F64;
    return PlyType::Invalid;
}

size_t type_size(PlyType t) {
    switch (t) {
        case PlyType::I8:
        case PlyType::U8:
            return 1;
        case PlyType::I16:
        case PlyType::U16:
            return 2;
        case PlyType::I32:
        case PlyType::U32:
        case PlyType::F32:
            return 4;
        case PlyType::F64:
            return 8;
        default:
            return 0;
    }
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Invalid;
    bool is_list = false;
    PlyType count_type = PlyType::Invalid;
};

struct PlyElement {
    std::string name;
    size_t count = 0;
    std::vector<PlyProperty> props;
};

enum class PlyFormat { Ascii, BinaryLE, BinaryBE };

/// Which properties of an element form a mesh attribute, and which of them go in which channel.
struct AttributeGroup {
    MeshAttribute attr;
    std::vector<size_t> props;  ///< property index per channel
    double scale = 1;           ///< 1/255 for 8-bit colours
};

// Mitsuba 3's grouping of a PLY element's extra properties into attributes ("{prefix}_{x|y|z}",
// "_{r|g|b}", "_{0|1|2}", "_{1|2|3}" in a row, 1 or 3 of them; r, g, b or red, green, blue
// alone form "color"), named "{element}_{prefix}" ("_color" added for the r|g|b postfixes).
// Properties outside these patterns are skipped, as Mitsuba skips them. 8-bit colours are
// scaled to [0, 1] (Mitsuba keeps 0..255 and warns; every other reader scales them).
std::vector<AttributeGroup> attribute_groups(const PlyElement& e, const std::string& element,
                                             const std::vector<std::string>& reserved) {
    std::vector<AttributeGroup> out;
    auto index_of = [&](const std::string& n) -> long {
        for (size_t i = 0; i < e.props.size(); ++i)
            if (!e.props[i].is_list && e.props[i].name == n) return long(i);
        return -1;
    };
    auto is_reserved = [&](const std::string& n) {
        for (const auto& r : reserved)
            if (n == r) return true;
        return n == "r" || n == "g" || n == "b" || n == "a" || n == "red" || n == "green" || n == "blue" ||
               n == "alpha";
    };
    for (const auto& names :
         {std::array<const char*, 3>{"r", "g", "b"}, std::array<const char*, 3>{"red", "green", "blue"}}) {
        const long r = index_of(names[0]), g = index_of(names[1]), b = index_of(names[2]);
        if (r < 0 || g < 0 || b < 0) continue;
        AttributeGroup grp;
        grp.attr.name = element + "_color";
        grp.attr.per_face = element == "face";
        grp.attr.channels = 3;
        grp.props = {size_t(r), size_t(g), size_t(b)};
        if (e.props[size_t(r)].type == PlyType::U8) grp.scale = 1.0 / 255;
        out.push_back(grp);
        break;
    }
    static const char* kPostfix[4] = {"xr01", "yg12", "zb23", "wa34"};
    size_t i = 0;
    while (i < e.props.size()) {
        const PlyProperty& p = e.props[i];
        const size_t us = p.name.find_last_of('_');
        if (p.is_list || is_reserved(p.name) || us == std::string::npos || us + 2 != p.name.size()) {
            ++i;
            continue;
        }
        const std::string prefix = p.name.substr(0, us);
        const char* cat = std::strchr(kPostfix[0], p.name.back());
        if (!cat) {
            ++i;
            continue;
        }
        const size_t c = size_t(cat - kPostfix[0]);
        // The run of properties prefix_<postfix k> for k = 0, 1, ... in this category.
        std::vector<size_t> run;
        while (i + run.size() < e.props.size() && run.size() < 4) {
            const PlyProperty& q = e.props[i + run.size()];
            if (q.is_list || q.name != prefix + "_" + kPostfix[run.size()][c]) break;
            run.push_back(i + run.size());
        }
        i += run.size();
        if (run.size() != 1 && run.size() != 3) continue;  // Mitsuba: 1 or 3 fields
        AttributeGroup grp;
        grp.attr.name = element + "_" + prefix + (c == 1 ? "_color" : "");
        grp.attr.per_face = element == "face";
        grp.attr.channels = int(run.size());
        grp.props = run;
        if (run.size() == 3 && e.props[run[0]].type == PlyType::U8) grp.scale = 1.0 / 255;
        bool seen = false;
        for (const auto& g : out) seen = seen || g.attr.name == grp.attr.name;
        if (!seen) out.push_back(grp);
    }
    return out;
}

/// Reads scalar values of the body in any of the three encodings, as doubles (exact for
/// every PLY integer type and float).
class PlyBody {
public:
    PlyBody(std::istream& in, PlyFormat fmt, const std::string& path) : m_in(in), m_fmt(fmt), m_path(path) {}

    double read(PlyType t, const std::string& where) {
        if (m_fmt == PlyFormat::Ascii) {
            // A token read by strtod, which (unlike operator>>) reads "nan" and "inf": the
            // callers then reject them with what they mean there.
            std::string token;
            if (!(m_in >> token)) fail(where);
            char* end = nullptr;
            const double v = std::strtod(token.c_str(), &end);
            if (end == token.c_str() || *end != '\0') fail(where);
            return v;
        }
        unsigned char b[8];
        const size_t n = type_size(t);
        if (!m_in.read(reinterpret_cast<char*>(b), std::streamsize(n))) fail(where);
        const bool file_le = m_fmt == PlyFormat::BinaryLE;
        if (file_le != (std::endian::native == std::endian::little))
            for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
            case PlyType::I8: {
                int8_t v;
                std::memcpy(&v, b, 1);
                return v;
            }
            case PlyType::U8:
                return b[0];
            case PlyType::I16: {
                int16_t v;
                std::memcpy(&v, b, 2);
                return v;
            }
            case PlyType::U16: {
                uint16_t v;
                std::memcpy(&v, b, 2);
                return v;
            }
            case PlyType::I32: {
                int32_t v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::U32: {
                uint32_t v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::F32: {
                float v;
                std::memcpy(&v, b, 4);
                return v;
            }
            case PlyType::F64: {
                double v;
                std::memcpy(&v, b, 8);
                return v;
            }
            default:
                fail(where);
        }
    }

private:
    [[noreturn]] void fail(const std::string& where) const {
        throw std::runtime_error(m_path + ": unexpected end of file or bad value in PLY element '" + where + "'");
    }
    std::istream& m_in;
    PlyFormat m_fmt;
    const std::string& m_path;
};

}  // namespace

MeshData load_ply(const std::string& path) {
    if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": mesh file not found");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open mesh file");
    auto fail = [&](const std::string& msg) -> void { throw std::runtime_error(path + ": " + msg); };
    // Every vertex takes at least one byte of the file: a bound on what a header's count may
    // make us reserve (a count of 10^12 asked for terabytes before reading a single vertex).
    std::error_code size_ec;
    const uintmax_t file_bytes = std::filesystem::file_size(path, size_ec);
    // A list's length, read as a double: a whole number within [0, 10^6] (a negative, NaN or
    // huge length converted to size_t is undefined behaviour).
    auto list_length = [&](double c, const std::string& element) -> size_t {
        if (!(c >= 0 && c <= 1e6) || c != std::floor(c))
            fail("bad PLY list length " + std::to_string(c) + " in element '" + element + "'");
        return size_t(c);
    };

    // ---- header
    std::string line;
    auto next_line = [&]() {
        if (!std::getline(in, line)) fail("PLY header ends before 'end_header'");
        if (!line.empty() && line.back() == '\r') line.pop_back();
    };
    next_line();
    if (line != "ply") fail("not a PLY file (missing 'ply' magic)");
    PlyFormat fmt = PlyFormat::Ascii;
    bool have_format = false;
    std::vector<PlyElement> elements;
    for (;;) {
        next_line();
        std::istringstream ls(line);
        std::string kw;
        ls >> kw;
        if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
        if (kw == "end_header") break;
        if (kw == "format") {
            std::string f, version;
            ls >> f >> version;
            if (f == "ascii")
                fmt = PlyFormat::Ascii;
            else if (f == "binary_little_endian")
                fmt = PlyFormat::BinaryLE;
            else if (f == "binary_big_endian")
                fmt = PlyFormat::BinaryBE;
            else
                fail("unknown PLY format '" + f + "'");
            have_format = true;
        } else if (kw == "element") {
            PlyElement e;
            long long count = -1;
            ls >> e.name >> count;
            if (e.name.empty() || count < 0) fail("malformed PLY element line '" + line + "'");
            e.count = size_t(count);
            elements.push_back(e);
        } else if (kw == "property") {
            if (elements.empty()) fail("PLY property before any element");
            PlyProperty p;
            std::string t;
            ls >> t;
            if (t == "list") {
                std::string ct, it;
                ls >> ct >> it >> p.name;
                p.is_list = true;
                p.count_type = parse_type(ct);
                p.type = parse_type(it);
                if (p.count_type == PlyType::Invalid || p.type == PlyType::Invalid)
                    fail("unknown PLY list type in '" + line + "'");
            } else {
                p.type = parse_type(t);
                ls >> p.name;
                if (p.type == PlyType::Invalid) fail("unknown PLY property type '" + t + "'");
            }
            if (p.name.empty()) fail("malformed PLY property line '" + line + "'");
            elements.back().props.push_back(p);
        } else {
            fail("unexpected PLY header line '" + line + "'");
        }
    }
    if (!have_format) fail("PLY header has no 'format' line");

    // ---- body
    MeshData m;
    PlyBody body(in, fmt, path);
    bool saw_vertex = false, saw_face = false;
    for (const PlyElement& e : elements) {
        if (e.name == "vertex") {
            saw_vertex = true;
            // Slots: 0-2 position, 3-5 normal, 6-7 uv; -1 = ignored property.
            std::vector<int> slot(e.props.size(), -1);
            bool has[8] = {};
            for (size_t i = 0; i < e.props.size(); ++i) {
                const std::string& n = e.props[i].name;
                int s = -1;
                if (n == "x")
                    s = 0;
                else if (n == "y")
                    s = 1;
                else if (n == "z")
                    s = 2;
                else if (n == "nx")
                    s = 3;
                else if (n == "ny")
                    s = 4;
                else if (n == "nz")
                    s = 5;
                else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
                    s = 6;
                else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
                    s = 7;
                if (s >= 0 && !e.props[i].is_list) {
                    slot[i] = s;
                    has[s] = true;
                }
            }
            if (!(has[0] && has[1] && has[2])) fail("PLY vertex element lacks x, y or z");
            const bool with_n = has[3] && has[4] && has[5], with_uv = has[6] && has[7];
            std::vector<AttributeGroup> groups = attribute_groups(e, "vertex",
                                                                  {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t",
                                                                   "texture_u", "texture_v", "texture_s", "texture_t"});
            m.positions.reserve(size_ec ? 0 : std::min<uintmax_t>(e.count, file_bytes));
            std::vector<double> row(e.props.size());
            for (size_t k = 0; k < e.count; ++k) {
                double v[8] = {};
                for (size_t i = 0; i < e.props.size(); ++i) {
                    const PlyProperty& p = e.props[i];
                    if (p.is_list) {
                        const size_t c = list_length(body.read(p.count_type, e.name), e.name);
                        for (size_t j = 0; j < c; ++j) body.read(p.type, e.name);
                        continue;
                    }
                    const double x = body.read(p.type, e.name);
                    row[i] = x;
                    if (slot[i] >= 0) v[slot[i]] = x;
                }
                m.positions.emplace_back(v[0], v[1], v[2]);
                if (with_n) m.normals.emplace_back(v[3], v[4], v[5]);
                if (with_uv) m.uvs.emplace_back(v[6], v[7]);
                for (AttributeGroup& g : groups)
                    for (size_t idx : g.props) g.attr.values.push_back(float(row[idx] * g.scale));
            }
            for (AttributeGroup& g : groups) m.attributes.push_back(std::move(g.attr));
        } else if (e.name == "face") {
            saw_face = true;
            bool found = false;
            for (const PlyProperty& p : e.props)
                found = found || (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index"));
            if (!found) fail("PLY face element lacks a 'vertex_indices' list");
            std::vector<AttributeGroup> groups = attribute_groups(e, "face", {});
            std::vector<double> row(e.props.size());
            std::vector<uint32_t> poly;
            for (size_t k = 0; k < e.count; ++k) {
                const size_t tris_before = m.triangles.size();
                for (size_t pi = 0; pi < e.props.size(); ++pi) {
                    const PlyProperty& p = e.props[pi];
                    if (!p.is_list) {
                        row[pi] = body.read(p.type, e.name);
                        continue;
                    }
                    const double c = body.read(p.count_type, e.name);
                    if (!(c >= 0 && c <= 1e6) || c != std::floor(c)) fail("bad PLY face vertex count");
                    poly.clear();
                    for (size_t j = 0; j < size_t(c); ++j) {
                        const double idx = body.read(p.type, e.name);
                        // A whole number in uint32's range, else an error (issue 12: 2^32, NaN
                        // and 2.7 became some other vertex); validate_mesh checks the vertex count.
                        if (!(idx >= 0) || idx != std::floor(idx) || idx > 4294967295.0)
                            fail("PLY face " + std::to_string(k) + " has an invalid vertex index " +
                                 std::to_string(idx));
                        poly.push_back(uint32_t(idx));
                    }
                    if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
                    if (poly.size() < 3) fail("PLY face " + std::to_string(k) + " has fewer than 3 vertices");
                    for (size_t j = 1; j + 1 < poly.size(); ++j) m.triangles.push_back({poly[0], poly[j], poly[j + 1]});
                }
                // A face attribute holds for every triangle the face was cut into.
                for (size_t t = tris_before; t < m.triangles.size(); ++t)
                    for (AttributeGroup& g : groups)
                        for (size_t idx : g.props) g.attr.values.push_back(float(row[idx] * g.scale));
            }
            for (AttributeGroup& g : groups) m.attributes.push_back(std::move(g.attr));
        } else {
            // Unknown element (edges, materials...): read and drop.
            for (size_t k = 0; k < e.count; ++k)
                for (const PlyProperty& p : e.props) {
                    if (p.is_list) {
                        const size_t c = list_length(body.read(p.count_type, e.name), e.name);
                        for (size_t j = 0; j < c; ++j) body.read(p.type, e.name);
                    } else {
                        body.read(p.type, e.name);
                    }
                }
        }
    }
    if (!saw_vertex) fail("PLY file has no vertex element");
    if (!saw_face) fail("PLY file has no face element");
    validate_mesh(m, path);
    return m;
}

}  // namespace snell
