# Math, transforms, counters, camera (owner: core).
snell_library(snell_base
  src/core/transform.cpp
  src/core/stats.cpp
  src/camera/camera.cpp
  src/camera/filter.cpp
)
target_link_libraries(snell_base PUBLIC TBB::tbb)

snell_test(test_base
  SOURCES tests/unit/test_transform.cpp tests/unit/test_sampler.cpp
  LIBS snell_base)
