#pragma once
// Parameter dictionary handed to every factory (pbrt-v4's ParameterDictionary, Mitsuba's
// Properties). Every lookup marks the parameter used; `check_unused()` then reports what a
// plugin did not understand with its file:line, so no attribute is ever silently ignored.
#include <initializer_list>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/object.h"
#include "core/spectrum.h"
#include "core/transform.h"
#include "core/vector.h"

namespace snell {

/// Position in a scene file.
struct SourceLoc {
    std::string file;
    int line = 0;
    std::string str() const { return file + ":" + std::to_string(line); }
};

/// Error in a scene description: the message reads "file:line: <element>: what".
class SceneError : public std::runtime_error {
public:
    SceneError(const SourceLoc& loc, const std::string& element, const std::string& what)
        : std::runtime_error(loc.str() + ": <" + element + ">: " + what) {}
    explicit SceneError(const std::string& what) : std::runtime_error(what) {}
};

/// Raw spectrum as written in the file: wavelength:value pairs (nm), or one value.
struct SpectrumData {
    std::vector<double> lambda, values;
};

/// How an RGB parameter is upsampled to a spectrum.
enum class SpectrumUse { Reflectance, Unbounded, Illuminant };

class Props {
public:
    using Value = std::variant<bool, int64_t, double, std::string, Vec3, RGB, Transform, SpectrumData>;

    Props() = default;
    Props(std::string tag, std::string type, SourceLoc loc)
        : m_tag(std::move(tag)), m_type(std::move(type)), m_loc(std::move(loc)) {}

    const std::string& tag() const { return m_tag; }    ///< "bsdf", "shape", ...
    const std::string& type() const { return m_type; }  ///< plugin type, e.g. "dielectric"
    const std::string& id() const { return m_id; }
    void set_id(std::string id) { m_id = std::move(id); }
    const SourceLoc& loc() const { return m_loc; }

    /// Stores a parameter; a duplicate name is an error naming both places.
    void set(const std::string& name, Value v, const SourceLoc& loc);
    /// Adds a nested or referenced object; `name` may be empty (Mitsuba allows unnamed children).
    void add_child(const std::string& name, std::shared_ptr<Object> obj, const SourceLoc& loc);

    bool has(const std::string& name) const;

    bool get_bool(const std::string& name) const;
    bool get_bool(const std::string& name, bool def) const;
    int64_t get_int(const std::string& name) const;
    int64_t get_int(const std::string& name, int64_t def) const;
    /// Integers are accepted where floats are expected.
    double get_float(const std::string& name) const;
    double get_float(const std::string& name, double def) const;
    std::string get_string(const std::string& name) const;
    std::string get_string(const std::string& name, const std::string& def) const;
    /// A string parameter naming one of `names` (mapped to its value), `def` if absent; any other
    /// string is a located error listing the names.
    template <typename E>
    E get_choice(const std::string& name, E def, std::initializer_list<std::pair<const char*, E>> names) const {
        if (!has(name)) return def;
        const std::string v = get_string(name);
        std::string list;
        for (const auto& [n, e] : names) {
            if (v == n) return e;
            list += (list.empty() ? "'" : ", '") + std::string(n) + "'";
        }
        raise_param(name, name + " must be one of " + list);
    }
    Vec3 get_vec3(const std::string& name) const;  ///< <point>/<vector>
    Vec3 get_vec3(const std::string& name, const Vec3& def) const;
    Transform get_transform(const std::string& name, const Transform& def = Transform()) const;
    /// <float>, <rgb> or <spectrum>; RGB is upsampled according to `use`.
    Spectrum get_spectrum(const std::string& name, SpectrumUse use) const;
    Spectrum get_spectrum(const std::string& name, SpectrumUse use, const Spectrum& def) const;
    /// The raw RGB of a parameter given as <rgb> or <float> (used e.g. for light power).
    RGB get_rgb(const std::string& name, const RGB& def) const;
    /// True when the parameter holds a string (e.g. a named IOR like "water").
    bool is_string(const std::string& name) const;
    /// True when the parameter was given as <rgb>.
    bool is_rgb(const std::string& name) const;

    /// Nested/referenced children of type T, in file order; marks them used.
    template <typename T>
    std::vector<std::shared_ptr<T>> children() const {
        std::vector<std::shared_ptr<T>> out;
        for (auto& c : m_children)
            if (auto p = std::dynamic_pointer_cast<T>(c.obj)) {
                c.used = true;
                out.push_back(p);
            }
        return out;
    }
    /// The single child of type T (nullptr if none); more than one is an error.
    template <typename T>
    std::shared_ptr<T> child(const char* what) const {
        auto v = children<T>();
        if (v.size() > 1) raise(std::string("expected at most one nested ") + what);
        return v.empty() ? nullptr : v[0];
    }

    /// The nested or referenced child named `name` if it is a T (nullptr otherwise); marks it used.
    template <typename T>
    std::shared_ptr<T> named_child(const std::string& name) const {
        m_queried.push_back(name);
        for (auto& c : m_children)
            if (c.name == name)
                if (auto p = std::dynamic_pointer_cast<T>(c.obj)) {
                    c.used = true;
                    return p;
                }
        return nullptr;
    }
    /// Where the child named `name` was given (the element's location if there is none).
    SourceLoc child_loc(const std::string& name) const {
        for (auto& c : m_children)
            if (c.name == name) return c.loc;
        return m_loc;
    }

    /// Marks the parameter used whatever its type (a value that is accepted and has no effect);
    /// false if absent.
    bool mark_used(const std::string& name) const;
    /// Throws SceneError naming the first parameter or child nobody asked for.
    void check_unused() const;
    /// Throws a SceneError located at this object's element.
    [[noreturn]] void raise(const std::string& what) const { throw SceneError(m_loc, m_tag, what); }
    /// Throws a SceneError located at the named parameter (or the element if absent).
    [[noreturn]] void raise_param(const std::string& name, const std::string& what) const;

private:
    struct Entry {
        Value value;
        SourceLoc loc;
        mutable bool used = false;
    };
    struct Child {
        std::string name;
        std::shared_ptr<Object> obj;
        SourceLoc loc;
        mutable bool used = false;
    };
    const Entry* find(const std::string& name) const;
    template <typename T>
    const T* get_as(const std::string& name, const char* type_name) const;

    std::string m_tag, m_type, m_id;
    SourceLoc m_loc;
    std::map<std::string, Entry> m_entries;
    std::vector<Child> m_children;
    // Every name a plugin asked for (present or not), so check_unused can list the known ones.
    mutable std::vector<std::string> m_queried;
};

}  // namespace snell
