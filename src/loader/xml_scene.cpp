#include "loader/xml_scene.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

namespace snell {

const XmlParam* XmlObject::param(const std::string& name) const {
    for (const auto& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

namespace {

namespace fs = std::filesystem;

const std::set<std::string> kObjectTags = {"integrator", "sensor", "film",    "sampler", "rfilter",
                                           "bsdf",       "shape",  "emitter", "texture", "volume"};
const std::set<std::string> kValueTags = {"float",  "integer", "boolean",  "string",   "point",
                                          "vector", "rgb",     "spectrum", "transform"};
const std::set<std::string> kTransformOps = {"lookat", "translate", "rotate", "scale", "matrix"};

/// Which object tags may be nested (or referenced) inside which.
const std::set<std::string>& allowed_children(const std::string& parent) {
    static const std::map<std::string, std::set<std::string>> table = {
        // film, sampler and rfilter only as declarations with an id, used by <ref> (Mitsuba 3)
        {"scene", {"integrator", "sensor", "bsdf", "shape", "emitter", "film", "sampler", "rfilter", "texture"}},
        {"integrator", {"integrator"}},  // Mitsuba's moment and aov wrappers
        {"sensor", {"film", "sampler"}},
        {"film", {"rfilter"}},
        {"bsdf", {"bsdf", "texture"}},
        {"texture", {"texture", "volume"}},       // checkerboard's color0/color1; a volume texture's grid
        {"emitter", {"texture"}},                 // textured radiance, spot texture, projector image
        {"shape", {"bsdf", "emitter", "shape"}},  // shapes only in a shapegroup, refs only in an instance
    };
    static const std::set<std::string> none;
    auto it = table.find(parent);
    return it == table.end() ? none : it->second;
}

std::string join(const std::set<std::string>& s) {
    std::string out;
    for (const auto& x : s) out += (out.empty() ? "" : ", ") + x;
    return out;
}

/// "toWorld" -> "to_world", "intIOR" -> "int_ior": the Mitsuba 2/3 spelling of a Mitsuba 0.6
/// name (an underscore before an upper-case letter that follows a lower-case one or a digit).
std::string snake_case(const std::string& s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        const unsigned char prev = i > 0 ? static_cast<unsigned char>(s[i - 1]) : 0;
        if (std::isupper(c) && (std::islower(prev) || std::isdigit(prev))) out += '_';
        out += char(std::tolower(c));
    }
    return out;
}

std::string read_file(const std::string& path, bool* ok) {
    // Checked before opening: opening a FIFO blocks (issue 12), a folder "opens" empty.
    std::error_code ec;
    *ok = fs::is_regular_file(path, ec);
    if (!*ok) return {};
    std::ifstream in(path, std::ios::binary);
    *ok = bool(in);
    if (!*ok) return {};
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// One XML document being read: its label, folder and byte-offset -> line table.
struct FileCtx {
    std::string name;
    std::string dir;
    std::vector<size_t> line_starts;

    FileCtx(std::string name_, std::string dir_, const std::string& text)
        : name(std::move(name_)), dir(std::move(dir_)) {
        line_starts.push_back(0);
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') line_starts.push_back(i + 1);
    }
    /// pugixml reports positions as byte offsets into the buffer; map them to 1-based lines.
    SourceLoc at(ptrdiff_t offset) const {
        if (offset < 0) return {name, 0};
        auto it = std::upper_bound(line_starts.begin(), line_starts.end(), size_t(offset));
        return {name, int(it - line_starts.begin())};
    }
    SourceLoc at(const pugi::xml_node& n) const { return at(n.offset_debug()); }
};

class Parser {
public:
    explicit Parser(const std::map<std::string, std::string>& defines, std::vector<std::string> extra_paths = {})
        : m_defines(defines), m_params(defines), m_extra_paths(std::move(extra_paths)) {}

    std::shared_ptr<XmlObject> parse_root(const std::string& text, const FileCtx& f, const std::string& canonical) {
        auto scene = std::make_shared<XmlObject>();
        scene->tag = "scene";
        scene->base_dir = f.dir;
        m_main_dir = f.dir;
        if (!canonical.empty()) m_include_stack.push_back(canonical);
        parse_document(text, f, *scene, /*is_root=*/true);
        try {
            resolve_refs();
            check_cycles(*scene);
        } catch (...) {
            break_ref_links();
            throw;
        }
        for (const auto& [name, value] : m_defines)
            // -D frame=N also numbers the output (-o frame_%04d.exr, issue 27): a scene that
            // is not animated need not declare it.
            if (!m_declared.count(name) && !m_used.count(name) && name != "frame")
                throw SceneError("-D " + name + "=" + value + ": the scene has no parameter '" + name +
                                 "' (no <default name=\"" + name + "\"> and no $" + name + ")");
        return scene;
    }

private:
    using Attrs = std::map<std::string, std::string>;

    struct PendingRef {
        XmlObject* parent;
        size_t index;
        std::string id;
        SourceLoc loc;
    };

    std::map<std::string, std::string> m_defines;  // -D overrides, as given
    std::map<std::string, std::string> m_params;   // defines + <default>s: the $name values
    std::map<std::string, SourceLoc> m_default_locs;
    std::set<std::string> m_declared, m_used;
    std::vector<std::string> m_include_stack;  // canonical paths of the files being read
    std::string m_main_dir;                    // folder of the main scene file
    std::vector<std::string> m_search_paths;   // <path> folders, the latest first (Mitsuba's prepend)
    std::vector<std::string> m_extra_paths;    // the command line's (-a), after the main folder
    std::map<std::string, std::shared_ptr<XmlObject>> m_ids;
    std::vector<PendingRef> m_refs;

    // --- documents and includes --------------------------------------------------------------

    /// Scene elements nest a few levels; every pass over them (this parser, the 0.6 upgrade, the
    /// loader) recurses, so a deeper document is refused before any of them runs, by an iterative
    /// walk (issue 12: 100,000 nested elements overflowed the stack).
    /// One budget for the whole scene: an included document starts at the depth of the <include>
    /// that reads it (issue 30: 200 levels per file, 600 files deep, overflowed the stack while
    /// each file alone was within the limit).
    static constexpr int kMaxDepth = 256;
    int m_include_depth = 0;  // depth of the <include> elements the current document is read through
    void check_depth(const pugi::xml_document& doc, const FileCtx& f) const {
        std::vector<std::pair<pugi::xml_node, int>> stack;
        for (pugi::xml_node c : doc.children()) stack.emplace_back(c, m_include_depth + 1);
        while (!stack.empty()) {
            const auto [n, depth] = stack.back();
            stack.pop_back();
            if (depth > kMaxDepth)
                throw SceneError(f.at(n), n.name(),
                                 "elements nested deeper than " + std::to_string(kMaxDepth) + " levels" +
                                     (m_include_depth > 0 ? " (counting the <include> elements that lead here)" : ""));
            for (pugi::xml_node c : n.children())
                if (c.type() == pugi::node_element) stack.emplace_back(c, depth + 1);
        }
    }

    void parse_document(const std::string& text, const FileCtx& f, XmlObject& parent, bool is_root) {
        pugi::xml_document doc;
        const pugi::xml_parse_result res = doc.load_buffer(text.data(), text.size(), pugi::parse_default);
        if (!res) throw SceneError(f.at(res.offset), "xml", std::string("malformed XML: ") + res.description());
        check_depth(doc, f);
        pugi::xml_node root;
        for (pugi::xml_node n : doc.children()) {
            if (n.type() != pugi::node_element) continue;
            if (root) throw SceneError(f.at(n), n.name(), "a scene file has exactly one root element <scene>");
            root = n;
        }
        if (!root) throw SceneError(SourceLoc{f.name, 1}, "scene", "the file contains no <scene> element");
        if (std::string(root.name()) != "scene")
            throw SceneError(f.at(root), root.name(), "the root element must be <scene version=\"3.0.0\">");
        const Attrs a = attrs(root, f, {"version"});
        if (check_version(a, f.at(root)) < 2) upgrade_from_mitsuba_0_6(root);
        if (is_root) parent.loc = f.at(root);
        parse_children(root, parent, f);
    }

    // Mitsuba 0.6 scenes, upgraded in memory as Mitsuba's loader does: parameter names from
    // camelCase to snake_case (toWorld -> to_world, intIOR -> int_ior, sampleCount ->
    // sample_count), <lookAt> -> <lookat>, <srgb> -> <rgb>.
    static void upgrade_from_mitsuba_0_6(pugi::xml_node node) {
        for (pugi::xml_node n : node.children()) {
            if (n.type() != pugi::node_element) continue;
            const std::string tag = n.name();
            if (tag == "lookAt") n.set_name("lookat");
            if (tag == "srgb") n.set_name("rgb");
            if (pugi::xml_attribute name = n.attribute("name")) name.set_value(snake_case(name.value()).c_str());
            upgrade_from_mitsuba_0_6(n);
        }
    }
    int check_version(const Attrs& a, const SourceLoc& loc) {
        auto it = a.find("version");
        if (it == a.end())
            throw SceneError(loc, "scene", "missing attribute 'version' (write version=\"3.0.0\" or \"2.0.0\")");
        const std::string& v = it->second;
        const int major = std::atoi(v.c_str());
        if (v.empty() || !std::isdigit(static_cast<unsigned char>(v[0])))
            throw SceneError(loc, "scene", "cannot read version '" + v + "'");
        if (major == 0 && v.rfind("0.", 0) != 0) throw SceneError(loc, "scene", "cannot read version '" + v + "'");
        if (major > 3) throw SceneError(loc, "scene", "version " + v + " is not supported (0.x, 2.x and 3.x are)");
        if (major == 1) throw SceneError(loc, "scene", "version " + v + " is not supported (0.x, 2.x and 3.x are)");
        return major;
    }

    void parse_include(const pugi::xml_node& n, XmlObject& parent, const FileCtx& f) {
        const SourceLoc loc = f.at(n);
        const Attrs a = attrs(n, f, {"filename"});
        const std::string file = require(a, "filename", loc, "include");
        // Not found anywhere: the error names the path beside the including file.
        const fs::path p = resolve_file(file, f.dir).value_or(fs::path(f.dir) / file);
        bool ok = false;
        const std::string text = read_file(p.string(), &ok);
        if (!ok) throw SceneError(loc, "include", "cannot open included file '" + p.string() + "'");
        const std::string canonical = fs::weakly_canonical(p).string();
        if (std::find(m_include_stack.begin(), m_include_stack.end(), canonical) != m_include_stack.end()) {
            std::string chain;
            for (const auto& s : m_include_stack) chain += s + " -> ";
            throw SceneError(loc, "include", "include cycle: " + chain + canonical);
        }
        m_include_stack.push_back(canonical);
        int depth = 0;  // of the <include> element, in its document
        for (pugi::xml_node a = n; a && a.type() == pugi::node_element; a = a.parent()) ++depth;
        m_include_depth += depth;
        // Included elements are spliced in place: they land in the including element.
        parse_document(text, FileCtx(p.string(), p.parent_path().string(), text), parent, false);
        m_include_depth -= depth;
        m_include_stack.pop_back();
    }

    // --- elements ----------------------------------------------------------------------------

    void parse_children(const pugi::xml_node& node, XmlObject& obj, const FileCtx& f) {
        for (pugi::xml_node c : node.children()) {
            if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
                const std::string t = c.value();
                if (t.find_first_not_of(" \t\r\n") != std::string::npos)
                    throw SceneError(f.at(c), node.name(),
                                     "unexpected text '" + t + "' (values go in a value=\"...\" attribute)");
                continue;
            }
            if (c.type() != pugi::node_element) continue;
            const std::string tag = c.name();
            const SourceLoc loc = f.at(c);
            if (tag == "default") {
                if (obj.tag != "scene") throw SceneError(loc, tag, "<default> is only allowed directly inside <scene>");
                parse_default(c, f);
            } else if (tag == "include") {
                parse_include(c, obj, f);
            } else if (tag == "path") {
                if (obj.tag != "scene") throw SceneError(loc, tag, "<path> is only allowed directly inside <scene>");
                parse_path(c, f);
            } else if (tag == "ref") {
                if (obj.tag == "scene") throw SceneError(loc, tag, "<ref> is only allowed inside an object");
                const Attrs a = attrs(c, f, {"id", "name"});
                const std::string id = require(a, "id", loc, tag);
                const std::string name = a.count("name") ? a.at("name") : "";
                check_name(name, loc, tag);
                obj.children.push_back({name, nullptr, loc});
                m_refs.push_back({&obj, obj.children.size() - 1, id, loc});
            } else if ((tag == "spectrum" || tag == "rgb") && c.attribute("type")) {
                // Mitsuba 2's texture-valued parameter, <spectrum type="bitmap" name="...">: a
                // <texture> by another name.
                if (!allowed_children(obj.tag).count("texture"))
                    throw SceneError(loc, tag, "a texture cannot be nested inside <" + obj.tag + ">");
                std::string name;
                auto child = parse_object(c, f, &name);
                child->tag = "texture";
                obj.children.push_back({name, child, loc});
            } else if (kValueTags.count(tag)) {
                if (obj.tag == "scene")
                    throw SceneError(loc, tag, "parameters must be nested in an object, not directly in <scene>");
                XmlParam p = parse_value(c, f);
                for (const auto& q : obj.params)
                    if (q.name == p.name)
                        throw SceneError(loc, tag,
                                         "duplicate parameter '" + p.name + "' (first given at " + q.loc.str() + ")");
                obj.params.push_back(std::move(p));
            } else if (kObjectTags.count(tag)) {
                if (!allowed_children(obj.tag).count(tag))
                    throw SceneError(loc, tag,
                                     "<" + tag + "> cannot be nested inside <" + obj.tag + ">" +
                                         (allowed_children(obj.tag).empty()
                                              ? std::string(" (it takes no nested objects)")
                                              : " (allowed: " + join(allowed_children(obj.tag)) + ")"));
                std::string name;
                auto child = parse_object(c, f, &name);
                obj.children.push_back({name, child, loc});
            } else if (tag == "medium") {
                throw SceneError(loc, tag,
                                 "participating media are not supported; for absorbing glass give the "
                                 "dielectric BSDF a 'sigma_a' (see docs/scene-format.md)");
            } else if (kTransformOps.count(tag)) {
                throw SceneError(loc, tag, "<" + tag + "> must be inside <transform>");
            } else if (tag == "scene") {
                throw SceneError(loc, tag, "nested <scene> (use <include filename=\"...\"/>)");
            } else {
                throw SceneError(loc, tag, "unknown tag inside <" + obj.tag + ">");
            }
        }
    }

    void parse_default(const pugi::xml_node& n, const FileCtx& f) {
        const SourceLoc loc = f.at(n);
        const Attrs a = attrs(n, f, {"name", "value"});
        const std::string name = require(a, "name", loc, "default");
        const std::string value = require(a, "value", loc, "default");
        // Mitsuba keeps the first <default> of a name (a later one, e.g. in an include, is ignored).
        if (m_default_locs.count(name)) return;
        m_default_locs[name] = loc;
        m_declared.insert(name);
        m_params.emplace(name, value);  // a -D define of the same name wins
    }

    // Mitsuba's <path value="..."/>: a folder that relative file names (meshes, images, includes)
    // are also looked up in; relative to the file it is written in. The latest is searched first.
    void parse_path(const pugi::xml_node& n, const FileCtx& f) {
        const SourceLoc loc = f.at(n);
        const Attrs a = attrs(n, f, {"value"});
        // As Mitsuba 3 does: relative to the folder of the file that says it, else through the
        // file resolver (the earlier <path> folders, the main scene's folder).
        const std::string value = require(a, "value", loc, "path");
        const std::optional<fs::path> p = resolve_file(value, f.dir);
        std::error_code ec;
        if (!p || !fs::is_directory(*p, ec))
            throw SceneError(loc, "path",
                             "no such folder '" + value + "' (relative to '" + f.dir +
                                 "', the <path> folders and the main scene's folder)");
        // A folder given again moves to the front rather than being searched twice (issue 30:
        // 20,000 <path value="."/> took 80 s to read).
        const std::string dir = fs::weakly_canonical(*p, ec).string();
        const std::string key = ec ? p->string() : dir;
        m_search_paths.erase(std::remove(m_search_paths.begin(), m_search_paths.end(), key), m_search_paths.end());
        m_search_paths.insert(m_search_paths.begin(), key);
    }

    // A relative file name as Mitsuba's file resolver finds it, with the folder of the file that
    // names it first: that folder, the <path> folders (latest first), the main scene's folder.
    // The first candidate that exists, or none (absolute names are taken as they are).
    std::optional<fs::path> resolve_file(const std::string& name, const std::string& own_dir) const {
        const fs::path file(name);
        if (file.is_absolute()) return file;
        // Tried in order, each built only when the ones before it are missing.
        const auto found = [&](const std::string& dir, std::optional<fs::path>* out) {
            std::error_code ec;
            fs::path c = fs::path(dir) / file;
            if (!fs::exists(c, ec)) return false;
            *out = std::move(c);
            return true;
        };
        std::optional<fs::path> out;
        if (found(own_dir, &out)) return out;
        for (const auto& dir : m_search_paths)
            if (found(dir, &out)) return out;
        if (found(m_main_dir, &out)) return out;
        for (const auto& dir : m_extra_paths)
            if (found(dir, &out)) return out;
        return std::nullopt;
    }

    std::shared_ptr<XmlObject> parse_object(const pugi::xml_node& n, const FileCtx& f, std::string* name) {
        auto obj = std::make_shared<XmlObject>();
        obj->tag = n.name();
        obj->loc = f.at(n);
        obj->base_dir = f.dir;
        const Attrs a = attrs(n, f, {"type", "id", "name"});
        obj->type_as_written = require(a, "type", obj->loc, obj->tag);
        // Plugin names are lower case; files exported on case-insensitive systems write
        // "Rectangle", which Mitsuba finds there. The loader says so (a notice).
        obj->type = obj->type_as_written;
        for (char& ch : obj->type) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        *name = a.count("name") ? a.at("name") : "";
        check_name(*name, obj->loc, obj->tag);
        if (a.count("id")) {
            obj->id = a.at("id");
            if (obj->id.empty()) throw SceneError(obj->loc, obj->tag, "empty id");
            auto [it, fresh] = m_ids.emplace(obj->id, obj);
            if (!fresh)
                throw SceneError(obj->loc, obj->tag,
                                 "duplicate id '" + obj->id + "' (first used at " + it->second->loc.str() + ")");
        }
        parse_children(n, *obj, f);
        // A file the object reads (a mesh, an image) is found as Mitsuba finds it.
        for (auto& q : obj->params)
            if (q.name == "filename")
                if (auto* file = std::get_if<std::string>(&q.value)) *file = resolved_name(*file, f.dir);
        return obj;
    }

    // resolve_file() as an absolute path where the file exists; else the name as given (the
    // loader reads it relative to the element's folder, and its error names that path).
    std::string resolved_name(const std::string& name, const std::string& own_dir) const {
        if (fs::path(name).is_absolute()) return name;
        const auto p = resolve_file(name, own_dir);
        if (!p) return name;
        std::error_code ec;
        const fs::path abs = fs::absolute(*p, ec);
        return ec ? p->string() : abs.lexically_normal().string();
    }

    // --- value tags --------------------------------------------------------------------------

    XmlParam parse_value(const pugi::xml_node& n, const FileCtx& f) {
        const std::string tag = n.name();
        const SourceLoc loc = f.at(n);
        XmlParam p;
        p.loc = loc;
        Attrs a;
        if (tag == "point" || tag == "vector")
            a = attrs(n, f, {"name", "value", "x", "y", "z"});
        else if (tag == "transform")
            a = attrs(n, f, {"name"});
        else
            a = attrs(n, f, {"name", "value"});
        p.name = require(a, "name", loc, tag);
        check_name(p.name, loc, tag);
        if (tag != "transform") no_content(n, f);

        if (tag == "float") {
            p.value = number(require(a, "value", loc, tag), loc, tag);
        } else if (tag == "integer") {
            const std::string s = require(a, "value", loc, tag);
            errno = 0;
            char* end = nullptr;
            const long long v = std::strtoll(s.c_str(), &end, 10);
            if (s.empty() || errno || !only_space(end)) throw SceneError(loc, tag, "'" + s + "' is not an integer");
            p.value = int64_t(v);
        } else if (tag == "boolean") {
            std::string s = require(a, "value", loc, tag);
            std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
            if (s != "true" && s != "false") throw SceneError(loc, tag, "'" + a.at("value") + "' is not true or false");
            p.value = (s == "true");
        } else if (tag == "string") {
            p.value = require(a, "value", loc, tag);
        } else if (tag == "point" || tag == "vector") {
            p.value = vec3(a, loc, tag, 0.0);
        } else if (tag == "rgb") {
            const auto v = numbers(require(a, "value", loc, tag), loc, tag);
            if (v.size() == 1)
                p.value = RGB(v[0]);
            else if (v.size() == 3)
                p.value = RGB(v[0], v[1], v[2]);
            else
                throw SceneError(loc, tag, "rgb needs 1 or 3 values, got " + std::to_string(v.size()));
        } else if (tag == "spectrum") {
            p.value = spectrum(require(a, "value", loc, tag), loc, tag);
        } else {  // transform
            p.value = transform(n, f);
        }
        return p;
    }

    SpectrumData spectrum(const std::string& s, const SourceLoc& loc, const std::string& tag) {
        SpectrumData d;
        if (s.find(':') == std::string::npos) {
            const auto v = numbers(s, loc, tag);
            if (v.size() != 1)
                throw SceneError(loc, tag, "spectrum needs one value or wavelength:value pairs (\"400:0.1, 700:0.5\")");
            d.values = v;
            return d;
        }
        for (const std::string& tok : split(s)) {
            const size_t c = tok.find(':');
            if (c == std::string::npos || tok.find(':', c + 1) != std::string::npos)
                throw SceneError(loc, tag, "'" + tok + "' is not a wavelength:value pair");
            d.lambda.push_back(number(tok.substr(0, c), loc, tag));
            d.values.push_back(number(tok.substr(c + 1), loc, tag));
        }
        for (size_t i = 1; i < d.lambda.size(); ++i)
            if (!(d.lambda[i] > d.lambda[i - 1])) throw SceneError(loc, tag, "spectrum wavelengths must increase");
        return d;
    }

    /// <transform>: operations composed in file order, each applied after the previous ones.
    Transform transform(const pugi::xml_node& n, const FileCtx& f) {
        Transform t;
        for (pugi::xml_node c : n.children()) {
            if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata)
                throw SceneError(f.at(c), "transform", "unexpected text inside <transform>");
            if (c.type() != pugi::node_element) continue;
            const std::string tag = c.name();
            const SourceLoc loc = f.at(c);
            if (!kTransformOps.count(tag))
                throw SceneError(loc, tag, "unknown tag inside <transform> (allowed: " + join(kTransformOps) + ")");
            no_content(c, f);
            try {
                t = transform_op(c, f, tag, loc) * t;
            } catch (const SceneError&) {
                throw;
            } catch (const std::exception& e) {  // singular matrix, degenerate lookat
                throw SceneError(loc, tag, e.what());
            }
        }
        return t;
    }

    Transform transform_op(const pugi::xml_node& c, const FileCtx& f, const std::string& tag, const SourceLoc& loc) {
        if (tag == "translate") {
            return Transform::translate(vec3(attrs(c, f, {"value", "x", "y", "z"}), loc, tag, 0.0));
        } else if (tag == "scale") {
            const Attrs a = attrs(c, f, {"value", "x", "y", "z"});
            Vec3 s;
            if (a.count("value") && numbers(a.at("value"), loc, tag).size() == 1) {
                if (a.size() > 1) throw SceneError(loc, tag, "give either 'value' or x/y/z, not both");
                s = Vec3(numbers(a.at("value"), loc, tag)[0]);
            } else {
                s = vec3(a, loc, tag, 1.0);
            }
            if (s.x == 0 || s.y == 0 || s.z == 0) throw SceneError(loc, tag, "scale by zero");
            return Transform::scale(s);
        } else if (tag == "rotate") {
            const Attrs a = attrs(c, f, {"value", "axis", "x", "y", "z", "angle"});
            Attrs axis_attrs = a;
            axis_attrs.erase("angle");
            if (axis_attrs.count("axis")) {
                if (axis_attrs.size() > 1) throw SceneError(loc, tag, "give the axis once (axis, value or x/y/z)");
                axis_attrs["value"] = axis_attrs.at("axis");
                axis_attrs.erase("axis");
            }
            const Vec3 axis = vec3(axis_attrs, loc, tag, 0.0);
            if (length(axis) == 0) throw SceneError(loc, tag, "rotation axis is zero");
            return Transform::rotate(axis, number(require(a, "angle", loc, tag), loc, tag));
        } else if (tag == "matrix") {
            const Attrs a = attrs(c, f, {"value"});
            const auto v = numbers(require(a, "value", loc, tag), loc, tag);
            Transform::Mat m{};
            m[3][3] = 1;
            if (v.size() == 16) {
                for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = v[i];
            } else if (v.size() == 9) {
                for (int i = 0; i < 9; ++i) m[i / 3][i % 3] = v[i];
            } else {
                throw SceneError(loc, tag,
                                 "matrix needs 16 (4x4) or 9 (3x3) values, row-major; got " + std::to_string(v.size()));
            }
            return Transform(m);
        } else {  // lookat
            const Attrs a = attrs(c, f, {"origin", "target", "up"});
            auto point3 = [&](const char* key) {
                const auto v = numbers(require(a, key, loc, tag), loc, tag);
                if (v.size() != 3) throw SceneError(loc, tag, std::string("'") + key + "' needs 3 values");
                return Vec3(v[0], v[1], v[2]);
            };
            const Vec3 o = point3("origin"), t = point3("target"), up = point3("up");
            if (length(t - o) == 0) throw SceneError(loc, tag, "origin and target coincide");
            if (length(up) == 0) throw SceneError(loc, tag, "'up' is zero");
            return Transform::look_at(o, t, up);
        }
    }

    /// A point from value="x, y, z" (one number: all three) or x/y/z attributes (default `def`).
    Vec3 vec3(const Attrs& a, const SourceLoc& loc, const std::string& tag, double def) {
        if (a.count("value")) {
            if (a.count("x") || a.count("y") || a.count("z"))
                throw SceneError(loc, tag, "give either 'value' or x/y/z, not both");
            const auto v = numbers(a.at("value"), loc, tag);
            if (v.size() == 1) return Vec3(v[0]);
            if (v.size() != 3) throw SceneError(loc, tag, "needs 3 values, got " + std::to_string(v.size()));
            return Vec3(v[0], v[1], v[2]);
        }
        Vec3 r(def);
        if (a.count("x")) r.x = number(a.at("x"), loc, tag);
        if (a.count("y")) r.y = number(a.at("y"), loc, tag);
        if (a.count("z")) r.z = number(a.at("z"), loc, tag);
        return r;
    }

    // --- attributes, substitution, numbers ---------------------------------------------------

    /// The element's attributes after $param substitution; anything not in `allowed` is an error.
    Attrs attrs(const pugi::xml_node& n, const FileCtx& f, std::initializer_list<const char*> allowed) {
        Attrs out;
        const SourceLoc loc = f.at(n);
        for (pugi::xml_attribute at : n.attributes()) {
            const std::string key = at.name();
            if (std::none_of(allowed.begin(), allowed.end(), [&](const char* k) { return key == k; })) {
                std::string list;
                for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
                throw SceneError(loc, n.name(), "unknown attribute '" + key + "' (allowed: " + list + ")");
            }
            if (out.count(key)) throw SceneError(loc, n.name(), "attribute '" + key + "' given twice");
            out[key] = substitute(at.value(), loc, n.name());
        }
        return out;
    }

    std::string substitute(const std::string& s, const SourceLoc& loc, const std::string& tag) {
        if (s.find('$') == std::string::npos) return s;
        std::string out;
        for (size_t i = 0; i < s.size();) {
            if (s[i] != '$') {
                out += s[i++];
                continue;
            }
            size_t j = i + 1;
            while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_')) ++j;
            const std::string name = s.substr(i + 1, j - i - 1);
            if (name.empty()) throw SceneError(loc, tag, "stray '$' in \"" + s + "\"");
            auto it = m_params.find(name);
            if (it == m_params.end())
                throw SceneError(loc, tag,
                                 "unknown parameter $" + name + " (declare <default name=\"" + name +
                                     "\" value=\"...\"/> before its use, or pass -D " + name + "=...)");
            m_used.insert(name);
            out += it->second;
            i = j;
        }
        return out;
    }

    static std::string require(const Attrs& a, const std::string& key, const SourceLoc& loc, const std::string& tag) {
        auto it = a.find(key);
        if (it == a.end()) throw SceneError(loc, tag, "missing attribute '" + key + "'");
        return it->second;
    }

    static void check_name(const std::string& name, const SourceLoc& loc, const std::string& tag) {
        if (std::any_of(name.begin(), name.end(), [](unsigned char c) { return std::isupper(c); }))
            throw SceneError(loc, tag,
                             "parameter name '" + name +
                                 "' is Mitsuba 0.6 camelCase, which is not supported; "
                                 "Mitsuba 2/3 spell it '" +
                                 snake_case(name) + "'");
    }

    /// Value tags and transform operations are empty elements: anything inside is an error.
    static void no_content(const pugi::xml_node& n, const FileCtx& f) {
        for (pugi::xml_node c : n.children()) {
            if (c.type() == pugi::node_element)
                throw SceneError(f.at(c), c.name(), std::string("unexpected element inside <") + n.name() + ">");
            if ((c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) &&
                std::string(c.value()).find_first_not_of(" \t\r\n") != std::string::npos)
                throw SceneError(f.at(n), n.name(), "unexpected text (values go in a value=\"...\" attribute)");
        }
    }

    static bool only_space(const char* p) {
        while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
        return *p == 0;
    }

    static double number(const std::string& s, const SourceLoc& loc, const std::string& tag) {
        errno = 0;
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        if (end == s.c_str() || errno == ERANGE || !only_space(end) || !std::isfinite(v))
            throw SceneError(loc, tag, "'" + s + "' is not a number");
        return v;
    }

    /// Tokens separated by commas and/or white space.
    static std::vector<std::string> split(const std::string& s) {
        std::vector<std::string> out;
        std::string cur;
        for (char c : s) {
            if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
                if (!cur.empty()) out.push_back(cur);
                cur.clear();
            } else {
                cur += c;
            }
        }
        if (!cur.empty()) out.push_back(cur);
        return out;
    }

    static std::vector<double> numbers(const std::string& s, const SourceLoc& loc, const std::string& tag) {
        std::vector<double> v;
        for (const auto& tok : split(s)) v.push_back(number(tok, loc, tag));
        if (v.empty()) throw SceneError(loc, tag, "empty value");
        return v;
    }

    // --- references --------------------------------------------------------------------------

    void resolve_refs() {
        for (const auto& r : m_refs) {
            auto it = m_ids.find(r.id);
            if (it == m_ids.end()) throw SceneError(r.loc, "ref", "unknown id '" + r.id + "'");
            const std::string& tag = it->second->tag;
            if (!allowed_children(r.parent->tag).count(tag))
                throw SceneError(
                    r.loc, "ref",
                    "id '" + r.id + "' is a <" + tag + ">, which cannot be used inside <" + r.parent->tag + ">");
            r.parent->children[r.index].obj = it->second;
            it->second->referenced = true;
        }
    }

    /// Resolved refs may form a cycle of shared_ptrs, which would never be freed: on an error
    /// the objects with an id drop their children (every cycle passes through one of them).
    void break_ref_links() {
        for (auto& [id, obj] : m_ids) obj->children.clear();
    }

    /// A <ref> to an enclosing object would make instantiation recurse forever.
    void check_cycles(const XmlObject& root) {
        std::set<const XmlObject*> active, done;
        std::function<void(const XmlObject&)> visit = [&](const XmlObject& o) {
            if (done.count(&o)) return;
            active.insert(&o);
            for (const auto& c : o.children) {
                if (active.count(c.obj.get()))
                    throw SceneError(c.loc, "ref", "reference cycle: '" + c.obj->id + "' contains itself");
                visit(*c.obj);
            }
            active.erase(&o);
            done.insert(&o);
        };
        visit(root);
    }
};

}  // namespace

std::shared_ptr<XmlObject> parse_scene_xml_file(const std::string& path,
                                                const std::map<std::string, std::string>& defines,
                                                const std::vector<std::string>& search_paths) {
    bool ok = false;
    const std::string text = read_file(path, &ok);
    if (!ok) throw SceneError("cannot open scene file '" + path + "'");
    std::string dir = fs::path(path).parent_path().string();
    if (dir.empty()) dir = ".";
    Parser parser(defines, search_paths);
    return parser.parse_root(text, FileCtx(path, dir, text), fs::weakly_canonical(path).string());
}

std::shared_ptr<XmlObject> parse_scene_xml_string(const std::string& xml, const std::string& name,
                                                  const std::string& base_dir,
                                                  const std::map<std::string, std::string>& defines) {
    Parser parser(defines);
    return parser.parse_root(xml, FileCtx(name, base_dir, xml), "");
}

}  // namespace snell
