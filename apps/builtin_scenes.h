#pragma once
#include <string>
#include <vector>

namespace snell {

/// Scenes compiled into the binary, addressed as "builtin:<name>" (e.g. builtin:droplet).
/// Their text is the file under scenes/ of the same name, embedded at build time.
const std::string* builtin_scene(const std::string& name);
std::vector<std::string> builtin_scene_names();

}  // namespace snell
