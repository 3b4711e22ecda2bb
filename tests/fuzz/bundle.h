#pragma once
// A fuzz input is a bundle of files: the scene first, then what it reads (included XML, PLY, OBJ,
// EXR, PNG, ...). The layout is plain text so that corpus files stay readable and byte-level
// mutation keeps most of it intact:
//
//   @@file scene.xml
//   <scene version="3.0.0"> ... </scene>
//   @@file meshes/tri.ply
//   ply ...
//
// Every file starts with a line "@@file NAME"; its contents run to the newline before the next
// such line (or to the end). Input that does not start with "@@file " is a lone scene.xml.
#include <string>
#include <string_view>
#include <vector>

namespace snell::fuzz {

struct BundleFile {
    std::string name;  ///< relative path inside the bundle's folder
    std::string data;
};

inline constexpr size_t kMaxBundleFiles = 8;

/// The files of `input`, the scene first. Unsafe names (absolute, "..", odd characters) are
/// dropped, as are duplicates and files beyond kMaxBundleFiles; a first file with an unsafe name
/// is called scene.xml. Never empty.
std::vector<BundleFile> parse_bundle(std::string_view input);

/// The inverse of parse_bundle for files with safe names.
std::string write_bundle(const std::vector<BundleFile>& files);

/// A relative path of at most three components of [A-Za-z0-9._-], none of them "." or "..".
bool safe_bundle_name(std::string_view name);

}  // namespace snell::fuzz
