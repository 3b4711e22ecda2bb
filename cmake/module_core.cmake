# Math, transforms, spectra and colour, the parameter dictionary, counters, progress, plain
# triangle-mesh arrays (owner: core). The lowest layer: it includes nothing else from src/.
snell_library(snell_core
  src/core/transform.cpp
  src/core/stats.cpp
  src/core/spectrum.cpp
  src/core/progress.cpp
  src/core/props.cpp
  src/core/mesh_data.cpp
)
target_link_libraries(snell_core PUBLIC TBB::tbb)

snell_test(test_core
  SOURCES tests/unit/test_transform.cpp
  LIBS snell_core)

snell_test(test_spectrum
  SOURCES tests/unit/test_spectrum.cpp
  LIBS snell_core)

snell_test(test_props
  SOURCES tests/unit/test_props.cpp
  LIBS snell_core)
