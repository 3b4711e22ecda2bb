# Pixel samplers (Mitsuba's independent, stratified, multijitter, orthogonal, ldsampler; scrambled Sobol) and
# their factory. Every sampler is a pure function of (seed, pixel, sample index).
snell_library(snell_sampler
  src/sampler/stratified.cpp
  src/sampler/multijitter.cpp
  src/sampler/orthogonal.cpp
  src/sampler/ldsampler.cpp
  src/sampler/sobol.cpp
  src/sampler/factory.cpp
)
target_link_libraries(snell_sampler PUBLIC snell_core)

snell_test(test_samplers
  SOURCES tests/unit/test_samplers.cpp tests/unit/test_sampler.cpp
  LIBS snell_sampler)
