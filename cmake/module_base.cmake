# Math, transforms, counters, camera (owner: core).
snell_library(snell_base
  src/core/transform.cpp
  src/core/stats.cpp
  src/camera/camera.cpp
  src/camera/filter.cpp
)
target_link_libraries(snell_base PUBLIC TBB::tbb)

# For test_stats: a static library whose statistics sit in a translation unit no test names.
if(SNELL_BUILD_TESTS)
  snell_library(snell_test_stats_lib tests/unit/stats_lib/stats_lib_counters.cpp tests/unit/stats_lib/stats_lib_work.cpp)
  target_link_libraries(snell_test_stats_lib PUBLIC snell_base)
endif()

snell_test(test_base
  SOURCES tests/unit/test_transform.cpp tests/unit/test_sampler.cpp tests/unit/test_stats.cpp
  LIBS snell_base snell_test_stats_lib)
