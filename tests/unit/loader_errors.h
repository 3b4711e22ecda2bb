#pragma once
// Loading scenes that must fail: the error text, and checks of where (file:line) and what.
#include <gtest/gtest.h>

#include <string>

#include "core/props.h"
#include "loader/scene_loader.h"

namespace snell::test {

/// The message of the SceneError that loading `xml` (relative paths against `base_dir`) throws,
/// or "" when it loads.
inline std::string load_error(const std::string& xml, const std::string& base_dir, const Defines& defines = {}) {
    try {
        load_scene_string(xml, "test.xml", base_dir, defines);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "";
}

/// Loading fails with a message that starts with `where` ("test.xml:3: <rfilter>") and says `what`.
inline void expect_load_error(const std::string& xml, const std::string& base_dir, const std::string& where,
                              const std::string& what) {
    const std::string msg = load_error(xml, base_dir);
    EXPECT_EQ(msg.rfind(where, 0), 0u) << "expected prefix '" << where << "' in: " << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
}

}  // namespace snell::test
