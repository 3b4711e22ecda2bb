# Parameter dictionary handed to every factory (owner: loader).
snell_library(snell_props
  src/core/props.cpp
)
target_link_libraries(snell_props PUBLIC snell_spectral)

snell_test(test_props
  SOURCES tests/unit/test_props.cpp
  LIBS snell_props)
