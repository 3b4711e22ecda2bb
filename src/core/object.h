#pragma once
#include <string>

namespace snell {

/// Base of everything a scene file can instantiate (shapes, BSDFs, emitters, sensors,
/// integrators), so that the parameter dictionary can hold nested and referenced objects.
class Object {
public:
    virtual ~Object() = default;
    /// The scene-file id (`id="..."`), empty when none was given.
    const std::string& id() const { return m_id; }
    void set_id(std::string id) { m_id = std::move(id); }

private:
    std::string m_id;
};

}  // namespace snell
