# Mitsuba 2/3 XML scene loading (owner: loader). Stage 1 (snell_xml) parses the document into an
# intermediate tree and needs no plugin; stage 2 (snell_loader) instantiates it via the factories.
snell_library(snell_xml
  src/loader/xml_scene.cpp
)
target_link_libraries(snell_xml PUBLIC snell_props PRIVATE pugixml::pugixml)

snell_library(snell_loader
  src/loader/scene_loader.cpp
  src/camera/factory.cpp
)
target_link_libraries(snell_loader PUBLIC snell_xml snell_sampler)
foreach(dep snell_bsdf snell_geometry snell_light snell_integrators)
  if(TARGET ${dep})
    target_link_libraries(snell_loader PUBLIC ${dep})
  endif()
endforeach()

snell_test(test_scene_parser
  SOURCES tests/unit/test_scene_parser.cpp
  LIBS snell_xml)

# Full instantiation through every factory (needs all plugin libraries).
snell_test(test_scene_loader_full
  SOURCES tests/unit/test_scene_loader_full.cpp
  LIBS snell_loader snell_integrators)

# Reconstruction filters: chi-square of filter importance sampling, normalisation, splat
# support, and <rfilter> loading.
snell_test(test_filters
  SOURCES tests/stat/test_filters.cpp
  LIBS snell_loader snell_integrators)
