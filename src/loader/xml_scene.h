#pragma once
// Intermediate representation of a Mitsuba 2/3 XML scene (stage 1 of loading, after Mitsuba 3's
// parser): the document with <default>/$param substitution, <include> splicing and <ref>
// resolution done, and every value tag converted to a typed parameter. Nothing here knows the
// plugin factories, so the syntax can be tested on its own; scene_loader.cpp instantiates it.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/props.h"

namespace snell {

/// A value tag (<float>, <rgb>, <transform>, ...) after parsing.
struct XmlParam {
    std::string name;
    Props::Value value;
    SourceLoc loc;
};

/// One object element (<scene>, <integrator>, <sensor>, <film>, <sampler>, <rfilter>, <bsdf>,
/// <shape>, <emitter>). A <ref> makes the same XmlObject appear under several parents, so
/// instantiating by pointer gives one shared instance.
struct XmlObject {
    struct Child {
        std::string name;  ///< the `name` attribute of the nested element or <ref> (may be empty)
        std::shared_ptr<XmlObject> obj;
        SourceLoc loc;  ///< where it was nested or referenced
    };
    std::string tag;               ///< element name, e.g. "bsdf"
    std::string type;              ///< `type` attribute in lower case (empty for <scene>)
    std::string type_as_written;   ///< `type` as the file spells it
    std::string id;                ///< `id` attribute, empty if none
    SourceLoc loc;                 ///< the element itself
    std::string base_dir;          ///< folder of the file the element was written in
    std::vector<XmlParam> params;  ///< value tags in file order (names unique)
    std::vector<Child> children;   ///< nested objects and resolved refs in file order
    bool referenced = false;       ///< some <ref> names it (top-level declarations used elsewhere)

    /// The parameter called `name`, or nullptr.
    const XmlParam* param(const std::string& name) const;
};

/// Parses a scene file. `defines` (-D name=value) override the scene's <default> values; a
/// define that the scene never declares or uses is an error (it is most likely a typo).
/// Throws SceneError "file:line: <element>: what" for any syntax the loader does not know.
/// `search_paths` (Mitsuba's -a) are tried for relative file names after the main scene's folder.
std::shared_ptr<XmlObject> parse_scene_xml_file(const std::string& path,
                                                const std::map<std::string, std::string>& defines = {},
                                                const std::vector<std::string>& search_paths = {});
/// Same from a string; `name` labels errors and `base_dir` resolves relative includes.
std::shared_ptr<XmlObject> parse_scene_xml_string(const std::string& xml, const std::string& name,
                                                  const std::string& base_dir,
                                                  const std::map<std::string, std::string>& defines = {});

}  // namespace snell
