# Integrators (path, nee; later mnee and the baselines) and the tile renderer.
snell_library(snell_integrators
  src/integrators/registry.cpp
  src/integrators/path/path_tracer.cpp
  src/render/renderer.cpp
)
target_link_libraries(snell_integrators PUBLIC snell_geometry snell_bsdf snell_light snell_props TBB::tbb)

set(SNELL_ALL_LIBS snell_loader snell_integrators)
snell_test(test_integrators
  SOURCES tests/stat/test_integrator_agreement.cpp tests/stat/test_furnace.cpp tests/unit/test_render_determinism.cpp
  LIBS ${SNELL_ALL_LIBS})
