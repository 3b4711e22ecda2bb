#include "fuzz/xml_mutator.h"

#include <cstdlib>
#include <pugixml.hpp>
#include <random>
#include <sstream>
#include <string_view>
#include <vector>

namespace snell::fuzz {

namespace {

// Values at the edges the loader has to range-check: zero, signs, float overflow and
// underflow, NaN and infinities, 32- and 64-bit integer limits, empty and long strings, lists.
const std::vector<std::string> kInterestingValues = {"0",
                                                     "-0",
                                                     "1",
                                                     "-1",
                                                     "0.5",
                                                     "3",
                                                     "65536",
                                                     "1e300",
                                                     "-1e300",
                                                     "1e-320",
                                                     "nan",
                                                     "-nan",
                                                     "inf",
                                                     "-inf",
                                                     "2147483647",
                                                     "2147483648",
                                                     "-2147483649",
                                                     "4294967296",
                                                     "4294967297",
                                                     "1e19",
                                                     "-1e19",
                                                     "9223372036854775808",
                                                     "",
                                                     " ",
                                                     "true",
                                                     "false",
                                                     "x",
                                                     "$spp",
                                                     std::string(300, '9'),
                                                     std::string(300, 'a'),
                                                     "1, 2",
                                                     "0, 0, 0",
                                                     "1, 1, 1",
                                                     "1e300, 1e300, 1e300",
                                                     "nan, 0, 1",
                                                     "0, 0, 0, 0",
                                                     "400:1, 700:0",
                                                     "400:nan",
                                                     "#ff00ff",
                                                     "0 1 0"};

// Plugin types the factories know, so that a changed `type` often names a real plugin that
// now meets another plugin's parameters.
const std::vector<std::string> kTypes = {"diffuse",
                                         "dielectric",
                                         "thindielectric",
                                         "roughdielectric",
                                         "conductor",
                                         "roughconductor",
                                         "plastic",
                                         "roughplastic",
                                         "principled",
                                         "principledthin",
                                         "blendbsdf",
                                         "twosided",
                                         "bumpmap",
                                         "normalmap",
                                         "mask",
                                         "null",
                                         "area",
                                         "point",
                                         "spot",
                                         "projector",
                                         "directional",
                                         "constant",
                                         "envmap",
                                         "obj",
                                         "ply",
                                         "serialized",
                                         "sphere",
                                         "cylinder",
                                         "rectangle",
                                         "cube",
                                         "disk",
                                         "instance",
                                         "shapegroup",
                                         "bitmap",
                                         "checkerboard",
                                         "mesh_attribute",
                                         "gridvolume",
                                         "path",
                                         "pt",
                                         "nee",
                                         "direct",
                                         "mnee",
                                         "bdpt",
                                         "pssmlt",
                                         "erpt",
                                         "independent",
                                         "stratified",
                                         "multijitter",
                                         "orthogonal",
                                         "ldsampler",
                                         "sobol",
                                         "box",
                                         "tent",
                                         "gaussian",
                                         "perspective",
                                         "thinlens",
                                         "orthographic",
                                         "hdrfilm",
                                         "moment",
                                         "aov",
                                         "beckmann",
                                         "ggx"};

const std::vector<std::string> kTags = {
    "integer", "float",     "boolean", "string",  "rgb",     "spectrum", "point", "vector",    "ref",     "transform",
    "lookat",  "translate", "scale",   "rotate",  "matrix",  "shape",    "bsdf",  "emitter",   "texture", "sensor",
    "film",    "sampler",   "rfilter", "include", "default", "path",     "alias", "integrator"};

const std::vector<std::string> kParamTags = {"integer", "float",    "boolean", "string",
                                             "rgb",     "spectrum", "point",   "vector"};

struct Mutator {
    pugi::xml_document& doc;
    std::mt19937_64 rng;
    std::vector<pugi::xml_node> elements;  // document order, the root included

    size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }
    template <class T>
    T pick_from(const std::vector<T>& v) {
        return v[pick(v.size())];
    }

    void collect() {
        elements.clear();
        // Iterative, so that deeply nested documents cannot overflow the stack here.
        std::vector<pugi::xml_node> stack = {doc.document_element()};
        while (!stack.empty() && elements.size() < 100000) {
            pugi::xml_node n = stack.back();
            stack.pop_back();
            if (!n) continue;
            elements.push_back(n);
            for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling())
                if (c.type() == pugi::node_element) stack.push_back(c);
        }
    }

    // For a list ("0, 1, 0"), one of its entries changed, so that it keeps its length.
    std::string new_value(const std::string& old) {
        std::vector<std::string> parts;
        size_t start = 0;
        while (true) {
            const size_t comma = old.find(',', start);
            parts.push_back(old.substr(start, comma - start));
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        if (parts.size() < 2 || pick(4) == 0) return new_scalar(old);
        std::string& part = parts[pick(parts.size())];
        part = " " + new_scalar(part);
        std::string out = parts[0];
        for (size_t i = 1; i < parts.size(); ++i) out += "," + parts[i];
        return out;
    }

    // A number scaled, negated or nudged, or an interesting value.
    std::string new_scalar(const std::string& old) {
        char* end = nullptr;
        const double v = std::strtod(old.c_str(), &end);
        if (end != old.c_str() && pick(3) != 0) {
            const double factors[] = {-1, 2, 0.5, 1000, 1e-3, 1e10, 0};
            std::ostringstream s;
            s.precision(17);
            s << v * factors[pick(std::size(factors))] + double(pick(3)) - 1;
            return s.str();
        }
        return pick_from(kInterestingValues);
    }

    // The root's attributes (the version) are left alone: the parser's tests cover them, and a
    // scene without a version goes no further.
    void set_attribute() {
        std::vector<pugi::xml_attribute> attrs;
        for (size_t i = 1; i < elements.size(); ++i)
            for (pugi::xml_attribute a : elements[i].attributes()) attrs.push_back(a);
        if (attrs.empty()) return add_parameter();
        pugi::xml_attribute a = pick_from(attrs);
        const std::string_view name = a.name();
        if (name == "type" && pick(4) != 0)
            a.set_value(pick_from(kTypes).c_str());
        else if (name == "name" && pick(2) == 0)
            a.set_value(pick_from(attrs).value());  // another attribute's value, often a parameter name
        else
            a.set_value(new_value(a.value()).c_str());
    }

    void delete_element() {
        if (elements.size() < 2) return;
        pugi::xml_node n = elements[1 + pick(elements.size() - 1)];
        n.parent().remove_child(n);
    }

    void duplicate_element() {
        if (elements.size() < 2) return;
        pugi::xml_node n = elements[1 + pick(elements.size() - 1)];
        n.parent().insert_copy_after(n, n);
    }

    // A copy of one element inside another (anywhere but its own subtree, which pugixml refuses).
    void nest_element() {
        if (elements.size() < 2) return;
        pugi::xml_node n = elements[1 + pick(elements.size() - 1)];
        pugi::xml_node target = pick_from(elements);
        for (pugi::xml_node p = target; p; p = p.parent())
            if (p == n) return;
        target.append_copy(n);
    }

    void rename_element() {
        if (elements.size() < 2) return;
        elements[1 + pick(elements.size() - 1)].set_name(pick_from(kTags).c_str());
    }

    void remove_attribute() {
        if (elements.size() < 2) return;
        pugi::xml_node n = elements[1 + pick(elements.size() - 1)];
        std::vector<pugi::xml_attribute> attrs(n.attributes_begin(), n.attributes_end());
        if (!attrs.empty()) n.remove_attribute(pick_from(attrs));
    }

    // <tag name="..." value="..."/> in a random element, its name taken from the document.
    void add_parameter() {
        std::vector<std::string> names = {"radius",   "width", "height",  "sample_count", "max_depth", "filename",
                                          "to_world", "alpha", "int_ior", "reflectance",  "radiance",  "fov"};
        for (pugi::xml_node n : elements)
            if (pugi::xml_attribute a = n.attribute("name")) names.push_back(a.value());
        pugi::xml_node p = pick_from(elements).append_child(pick_from(kParamTags).c_str());
        p.append_attribute("name") = pick_from(names).c_str();
        p.append_attribute("value") = pick_from(kInterestingValues).c_str();
    }

    void mutate_once() {
        collect();
        if (elements.empty()) return;
        // Mostly values: most structural changes make the loader refuse the scene, and inputs
        // that load are the ones that reach the plugins and the renderer.
        switch (pick(16)) {
            case 0:
                delete_element();
                break;
            case 1:
                duplicate_element();
                break;
            case 2:
                nest_element();
                break;
            case 3:
                rename_element();
                break;
            case 4:
                remove_attribute();
                break;
            case 5:
                add_parameter();
                break;
            case 6:
                add_parameter();
                break;
            default:
                set_attribute();
                break;
        }
    }
};

}  // namespace

bool mutate_scene_xml(std::string& xml, uint64_t seed) {
    pugi::xml_document doc;
    if (!doc.load_buffer(xml.data(), xml.size(), pugi::parse_default) || !doc.document_element()) return false;
    Mutator m{doc, std::mt19937_64(seed), {}};
    const size_t n = m.pick(2) == 0 ? 1 : 1 + m.pick(3);
    for (size_t i = 0; i < n; ++i) m.mutate_once();
    std::ostringstream out;
    doc.save(out, "  ", pugi::format_indent | pugi::format_no_declaration);
    xml = out.str();
    return true;
}

}  // namespace snell::fuzz
