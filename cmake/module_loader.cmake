# Mitsuba 2/3 XML scene loading (owner: loader). Stage 1 (xml_scene.cpp) parses the document into
# an intermediate tree and needs no plugin; stage 2 (scene_loader.cpp, with the shape factory)
# instantiates it through every factory and picks the integrator, so the folder sits above the
# integrators. Both stages are one library, as every folder is one library: test_scene_parser
# links it, yet from a static library the linker takes only the parser's objects, so that test
# still exercises stage 1 alone (it merely waits for the plugin libraries to build).
snell_library(snell_loader
  src/loader/xml_scene.cpp
  src/loader/scene_loader.cpp
  src/loader/shape_factory.cpp
  src/loader/mitsuba_integrators.cpp
  src/loader/unsupported.cpp
)
target_link_libraries(snell_loader PUBLIC snell_integrators snell_scene snell_sampler snell_camera snell_geometry
                      snell_bsdf snell_light snell_io snell_core PRIVATE pugixml::pugixml)

snell_test(test_scene_parser
  SOURCES tests/unit/test_scene_parser.cpp
  LIBS snell_loader)

# Full instantiation through every factory (needs all plugin libraries).
snell_test(test_scene_loader_full
  SOURCES tests/unit/test_scene_loader_full.cpp
  LIBS snell_loader snell_integrators)

# Scenes with textures: the loader's forms and errors, and renders by every integrator against
# the albedo a plane under a constant environment shows.
snell_test(test_texture_scenes
  SOURCES tests/texture/test_texture_scenes.cpp
  LIBS snell_loader snell_integrators PkgConfig::OIIO)

# Emitters that read textures (area, spot, projector) and mesh_attribute, against closed-form
# values; Mitsuba's file layout (<path> through the main folder, capitalised types).
snell_test(test_emitter_textures
  SOURCES tests/texture/test_emitter_textures.cpp
  LIBS snell_loader snell_integrators PkgConfig::OIIO)

# Reconstruction filters: chi-square of filter importance sampling, normalisation, splat
# support, and <rfilter> loading.
snell_test(test_filters
  SOURCES tests/stat/test_filters.cpp
  LIBS snell_loader snell_integrators)
