#include "core/props.h"

#include <algorithm>

namespace snell {

namespace {

/// The scene-file word for each alternative of Props::Value (same order as the variant).
const char* value_type_name(const Props::Value& v) {
    static const char* names[] = {"boolean",      "integer", "float",     "string",
                                  "point/vector", "rgb",     "transform", "spectrum"};
    static_assert(std::variant_size_v<Props::Value> == 8, "keep names in sync with Props::Value");
    return names[v.index()];
}

}  // namespace

void Props::set(const std::string& name, Value v, const SourceLoc& loc) {
    auto it = m_entries.find(name);
    if (it != m_entries.end())
        throw SceneError(loc, m_tag,
                         "duplicate parameter '" + name + "' (first given at " + it->second.loc.str() + ")");
    m_entries.emplace(name, Entry{std::move(v), loc, false});
}

void Props::add_child(const std::string& name, std::shared_ptr<Object> obj, const SourceLoc& loc) {
    if (!name.empty())
        for (const auto& c : m_children)
            if (c.name == name)
                throw SceneError(loc, m_tag,
                                 "duplicate nested object '" + name + "' (first given at " + c.loc.str() + ")");
    m_children.push_back(Child{name, std::move(obj), loc, false});
}

bool Props::has(const std::string& name) const { return find(name) != nullptr; }

const Props::Entry* Props::find(const std::string& name) const {
    if (std::find(m_queried.begin(), m_queried.end(), name) == m_queried.end()) m_queried.push_back(name);
    auto it = m_entries.find(name);
    return it == m_entries.end() ? nullptr : &it->second;
}

template <typename T>
const T* Props::get_as(const std::string& name, const char* type_name) const {
    const Entry* e = find(name);
    if (!e) return nullptr;
    e->used = true;
    if (const T* p = std::get_if<T>(&e->value)) return p;
    throw SceneError(
        e->loc, m_tag,
        "parameter '" + name + "' has the wrong type: expected " + type_name + ", got " + value_type_name(e->value));
}

void Props::raise_param(const std::string& name, const std::string& what) const {
    auto it = m_entries.find(name);
    throw SceneError(it == m_entries.end() ? m_loc : it->second.loc, m_tag, what);
}

// --- typed getters --------------------------------------------------------------------------

bool Props::get_bool(const std::string& name) const {
    if (const bool* v = get_as<bool>(name, "boolean")) return *v;
    raise("missing required boolean parameter '" + name + "'");
}
bool Props::get_bool(const std::string& name, bool def) const {
    const bool* v = get_as<bool>(name, "boolean");
    return v ? *v : def;
}

int64_t Props::get_int(const std::string& name) const {
    if (const int64_t* v = get_as<int64_t>(name, "integer")) return *v;
    raise("missing required integer parameter '" + name + "'");
}
int64_t Props::get_int(const std::string& name, int64_t def) const {
    const int64_t* v = get_as<int64_t>(name, "integer");
    return v ? *v : def;
}

double Props::get_float(const std::string& name) const {
    const Entry* e = find(name);
    if (!e) raise("missing required float parameter '" + name + "'");
    return get_float(name, 0.0);
}
double Props::get_float(const std::string& name, double def) const {
    const Entry* e = find(name);
    if (!e) return def;
    // An <integer> is a valid float (Mitsuba writes e.g. <integer name="radius" value="2"/>).
    if (const int64_t* i = std::get_if<int64_t>(&e->value)) {
        e->used = true;
        return double(*i);
    }
    // So is a one-value <spectrum> (Mitsuba reads <spectrum name="weight" value="0.5"/> as 0.5).
    if (const SpectrumData* sd = std::get_if<SpectrumData>(&e->value);
        sd && sd->lambda.empty() && sd->values.size() == 1) {
        e->used = true;
        return sd->values[0];
    }
    return *get_as<double>(name, "float");
}

std::string Props::get_string(const std::string& name) const {
    if (const std::string* v = get_as<std::string>(name, "string")) return *v;
    raise("missing required string parameter '" + name + "'");
}
std::string Props::get_string(const std::string& name, const std::string& def) const {
    const std::string* v = get_as<std::string>(name, "string");
    return v ? *v : def;
}

Vec3 Props::get_vec3(const std::string& name) const {
    if (const Vec3* v = get_as<Vec3>(name, "point/vector")) return *v;
    raise("missing required point/vector parameter '" + name + "'");
}
Vec3 Props::get_vec3(const std::string& name, const Vec3& def) const {
    const Vec3* v = get_as<Vec3>(name, "point/vector");
    return v ? *v : def;
}

Transform Props::get_transform(const std::string& name, const Transform& def) const {
    const Transform* v = get_as<Transform>(name, "transform");
    return v ? *v : def;
}

Spectrum Props::get_spectrum(const std::string& name, SpectrumUse use) const {
    if (!find(name)) raise("missing required spectrum parameter '" + name + "'");
    return get_spectrum(name, use, Spectrum());
}

Spectrum Props::get_spectrum(const std::string& name, SpectrumUse use, const Spectrum& def) const {
    const Entry* e = find(name);
    if (!e) return def;
    e->used = true;
    const Value& v = e->value;
    // A single number is grey: for emitters that is the white illuminant scaled (as Mitsuba
    // scales D65), so <float name="radiance" value="5"/> is white light, not equal energy.
    const auto grey = [&](double x) {
        return use == SpectrumUse::Illuminant ? Spectrum::from_rgb_illuminant(RGB(x)) : Spectrum::constant(x);
    };
    if (const double* d = std::get_if<double>(&v)) return grey(*d);
    if (const int64_t* i = std::get_if<int64_t>(&v)) return grey(double(*i));
    if (const RGB* c = std::get_if<RGB>(&v)) {
        switch (use) {
            case SpectrumUse::Reflectance:
                return Spectrum::from_rgb_reflectance(*c);
            case SpectrumUse::Unbounded:
                return Spectrum::from_rgb_unbounded(*c);
            case SpectrumUse::Illuminant:
                return Spectrum::from_rgb_illuminant(*c);
        }
    }
    if (const SpectrumData* s = std::get_if<SpectrumData>(&v)) {
        if (s->lambda.empty() && s->values.size() == 1) return grey(s->values[0]);
        if (s->lambda.empty() || s->lambda.size() != s->values.size())
            throw SceneError(e->loc, m_tag, "spectrum '" + name + "': need wavelength:value pairs or one value");
        for (size_t k = 1; k < s->lambda.size(); ++k)
            if (!(s->lambda[k] > s->lambda[k - 1]))
                throw SceneError(e->loc, m_tag, "spectrum '" + name + "': wavelengths must increase");
        return Spectrum::tabulated(s->lambda, s->values);
    }
    throw SceneError(
        e->loc, m_tag,
        "parameter '" + name + "' has the wrong type: expected float, rgb or spectrum, got " + value_type_name(v));
}

RGB Props::get_rgb(const std::string& name, const RGB& def) const {
    const Entry* e = find(name);
    if (!e) return def;
    if (const double* d = std::get_if<double>(&e->value)) {
        e->used = true;
        return RGB(*d);
    }
    if (const int64_t* i = std::get_if<int64_t>(&e->value)) {
        e->used = true;
        return RGB(double(*i));
    }
    if (const SpectrumData* s = std::get_if<SpectrumData>(&e->value); s && s->lambda.empty() && s->values.size() == 1) {
        e->used = true;
        return RGB(s->values[0]);
    }
    return *get_as<RGB>(name, "rgb or float");
}

bool Props::is_string(const std::string& name) const {
    const Entry* e = find(name);
    return e && std::holds_alternative<std::string>(e->value);
}

bool Props::is_rgb(const std::string& name) const {
    const Entry* e = find(name);
    return e && std::holds_alternative<RGB>(e->value);
}

bool Props::mark_used(const std::string& name) const {
    const Entry* e = find(name);
    if (e) e->used = true;
    return e != nullptr;
}

// --- unused reporting -----------------------------------------------------------------------

void Props::check_unused() const {
    // Report the unused item that comes first in the file, so fixes proceed top to bottom.
    const Entry* first = nullptr;
    std::string first_name;
    for (const auto& [name, e] : m_entries)
        if (!e.used && (!first || e.loc.line < first->loc.line)) {
            first = &e;
            first_name = name;
        }
    const Child* first_child = nullptr;
    for (const auto& c : m_children)
        if (!c.used && (!first_child || c.loc.line < first_child->loc.line)) first_child = &c;

    std::string known;
    for (const auto& q : m_queried)  // "__" names are internal (e.g. the loader's __base_dir)
        if (q.rfind("__", 0) != 0) known += (known.empty() ? "" : ", ") + q;
    const std::string suffix =
        known.empty() ? std::string(" (it takes no parameters)") : " (known parameters: " + known + ")";
    if (first && (!first_child || first->loc.line <= first_child->loc.line))
        throw SceneError(first->loc, m_tag, "unused parameter '" + first_name + "' for type '" + m_type + "'" + suffix);
    if (first_child) {
        const std::string what =
            first_child->name.empty() ? "a nested object" : "nested object '" + first_child->name + "'";
        throw SceneError(first_child->loc, m_tag, "unused " + what + " for type '" + m_type + "' (not accepted here)");
    }
}

}  // namespace snell
