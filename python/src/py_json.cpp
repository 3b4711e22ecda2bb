// JSON (the stats report, diff metrics, compare's report.json) as Python objects.
#include "bindings.h"

namespace snell::py {

pyb::object to_python(const nlohmann::json& j) {
    switch (j.type()) {
        case nlohmann::json::value_t::object: {
            pyb::dict d;
            for (const auto& [k, v] : j.items()) d[pyb::str(k)] = to_python(v);
            return d;
        }
        case nlohmann::json::value_t::array: {
            pyb::list l;
            for (const auto& v : j) l.append(to_python(v));
            return l;
        }
        case nlohmann::json::value_t::string:
            return pyb::str(j.get<std::string>());
        case nlohmann::json::value_t::boolean:
            return pyb::bool_(j.get<bool>());
        case nlohmann::json::value_t::number_integer:
            return pyb::int_(j.get<int64_t>());
        case nlohmann::json::value_t::number_unsigned:
            return pyb::int_(j.get<uint64_t>());
        case nlohmann::json::value_t::number_float:
            return pyb::float_(j.get<double>());
        default:
            return pyb::none();
    }
}

}  // namespace snell::py
