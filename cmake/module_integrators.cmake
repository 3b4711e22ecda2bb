# Integrators (path, nee; later mnee and the baselines) and the tile renderer.
snell_library(snell_integrators
  src/integrators/registry.cpp
  src/integrators/integrator.cpp
  src/integrators/light_connection.cpp
  src/integrators/path/path_tracer.cpp
  src/integrators/path/camera_walk.cpp
  src/integrators/path/path_settings.cpp
  src/integrators/path/technique_stats.cpp
  src/integrators/direct/direct.cpp
  src/integrators/mnee/mnee_integrator.cpp
  src/integrators/mnee/mnee_path.cpp
  src/integrators/mnee/connection_allocation.cpp
  src/integrators/bdpt/bdpt.cpp
  src/integrators/bdpt/vertex.cpp
  src/integrators/bdpt/subpath.cpp
  src/integrators/bdpt/mis_weight.cpp
  src/integrators/bdpt/connect.cpp
  src/integrators/pssmlt/primary_sample_sampler.cpp
  src/integrators/pssmlt/pssmlt.cpp
  src/integrators/pssmlt/path_sample.cpp
  src/integrators/pssmlt/metropolis_loop.cpp
  src/integrators/hslt/hslt_path.cpp
  src/integrators/hslt/hslt_mutation.cpp
  src/integrators/hslt/hslt.cpp
  src/integrators/erpt/erpt.cpp
  src/integrators/erpt/energy_redistribution.cpp
  src/integrators/erpt/shape_watch.cpp
)
target_link_libraries(snell_integrators PUBLIC snell_render snell_manifold snell_scene snell_sampler snell_camera
                      snell_geometry snell_bsdf snell_light snell_core TBB::tbb)

set(SNELL_ALL_LIBS snell_loader snell_integrators)
snell_test(test_integrators
  SOURCES tests/stat/test_integrator_agreement.cpp tests/stat/test_furnace.cpp tests/unit/test_render_determinism.cpp
  LIBS ${SNELL_ALL_LIBS})
snell_test(test_scatter SOURCES tests/unit/test_scatter.cpp LIBS snell_integrators)
snell_test(test_mnee
  SOURCES tests/stat/test_mnee_agreement.cpp tests/stat/test_mnee_estimator.cpp tests/stat/test_mnee_solutions.cpp
    tests/stat/test_exterior_reflection.cpp
  LIBS ${SNELL_ALL_LIBS})
snell_test(test_path_features SOURCES tests/stat/test_path_features.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_cameras SOURCES tests/stat/test_cameras.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_instancing SOURCES tests/stat/test_instancing.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_mitsuba_references SOURCES tests/stat/test_mitsuba_references.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_hero_wavelengths SOURCES tests/stat/test_hero_wavelengths.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_dispersion SOURCES tests/stat/test_dispersion.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_connection_allocation SOURCES tests/stat/test_connection_allocation.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_caster_sampling SOURCES tests/stat/test_caster_sampling.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_sampler_images SOURCES tests/stat/test_sampler_images.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_pssmlt SOURCES tests/stat/test_pssmlt.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_hslt SOURCES tests/stat/test_hslt.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_scale_invariance SOURCES tests/stat/test_scale_invariance.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_bdpt SOURCES tests/stat/test_bdpt_agreement.cpp tests/stat/test_bdpt_light_tracing.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_erpt SOURCES tests/stat/test_erpt.cpp LIBS ${SNELL_ALL_LIBS})
snell_test(test_bdpt_vertices SOURCES tests/unit/test_bdpt_vertices.cpp LIBS ${SNELL_ALL_LIBS})
