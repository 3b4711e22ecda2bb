# BSDFs: one file per model, microfacet distributions, Fresnel (owner: bsdf).
snell_library(snell_bsdf
  src/bsdf/bsdf.cpp
  src/bsdf/fresnel.cpp
  src/bsdf/microfacet.cpp
  src/bsdf/conductor_data.cpp
  src/bsdf/conductor_table.cpp
  src/bsdf/diffuse.cpp
  src/bsdf/dielectric.cpp
  src/bsdf/thindielectric.cpp
  src/bsdf/roughdielectric.cpp
  src/bsdf/conductor.cpp
  src/bsdf/roughconductor.cpp
  src/bsdf/plastic.cpp
  src/bsdf/roughplastic.cpp
  src/bsdf/principled.cpp
  src/bsdf/principledthin.cpp
  src/bsdf/blend.cpp
  src/bsdf/twosided.cpp
  src/bsdf/perturbed_frame.cpp
  src/bsdf/bumpmap.cpp
  src/bsdf/factory.cpp
)
target_link_libraries(snell_bsdf PUBLIC snell_core snell_texture)

snell_test(test_bsdf_chi2
  SOURCES tests/stat/test_bsdf_chi2.cpp
  LIBS snell_bsdf)

snell_test(test_bsdf_furnace
  SOURCES tests/stat/test_bsdf_furnace.cpp
  LIBS snell_bsdf)

snell_test(test_bsdf_unit
  SOURCES tests/unit/test_bsdf_unit.cpp
  LIBS snell_bsdf)
