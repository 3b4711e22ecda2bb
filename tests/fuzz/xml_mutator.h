#pragma once
// Structure-aware mutation of Mitsuba scene XML for the loader's fuzz target: changes that keep
// the document well formed, so that the fuzzer's inputs get past the XML parser and reach the
// plugins' parameter checks, the mesh and image readers and the renderer.
#include <cstdint>
#include <string>

namespace snell::fuzz {

/// Applies one to three tree mutations (an attribute set to an interesting value or another
/// plugin type, an element deleted, duplicated, nested elsewhere or renamed, a parameter added)
/// to the document `xml`. Returns false, leaving `xml` as it was, when it does not parse or has
/// no elements; the caller then mutates its bytes instead.
bool mutate_scene_xml(std::string& xml, uint64_t seed);

}  // namespace snell::fuzz
