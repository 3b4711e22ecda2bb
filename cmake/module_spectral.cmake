# Spectra and colour, film, images (EXR/PNG).
snell_library(snell_spectral
  src/core/spectrum.cpp
)
target_link_libraries(snell_spectral PUBLIC snell_base)

snell_test(test_spectrum
  SOURCES tests/unit/test_spectrum.cpp
  LIBS snell_spectral)
