# Math, transforms, spectra and colour, the parameter dictionary, counters, progress, plain
# triangle-mesh arrays (owner: core). The lowest layer: it includes nothing else from src/.
snell_library(snell_core
  src/core/transform.cpp
  src/core/stats.cpp
  src/core/spectrum.cpp
  src/core/rgb_to_spectrum_table.cpp
  src/core/progress.cpp
  src/core/props.cpp
  src/core/mesh_data.cpp
)
target_link_libraries(snell_core PUBLIC TBB::tbb)

# For test_stats: a static library whose statistics sit in a translation unit no test names.
if(SNELL_BUILD_TESTS)
  add_library(snell_test_stats_lib STATIC tests/unit/stats_lib/stats_lib_counters.cpp
                                          tests/unit/stats_lib/stats_lib_work.cpp)
  target_compile_options(snell_test_stats_lib PRIVATE ${SNELL_WARNINGS})
  target_link_libraries(snell_test_stats_lib PUBLIC snell_core)
endif()

snell_test(test_core
  SOURCES tests/unit/test_transform.cpp tests/unit/test_stats.cpp tests/unit/test_exact_sum.cpp
  LIBS snell_core snell_test_stats_lib)

snell_test(test_spectrum
  SOURCES tests/unit/test_spectrum.cpp
  LIBS snell_core)

snell_test(test_props
  SOURCES tests/unit/test_props.cpp
  LIBS snell_core)
