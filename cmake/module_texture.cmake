# Textures (owner: texture): the Texture interface, constant/checkerboard/bitmap plugins, the
# parameter lookup BSDF factories use. Images are read by io/ (OpenImageIO); colours are upsampled
# with core/'s RGBToSpectrumTable.
snell_library(snell_texture
  src/texture/checkerboard.cpp
  src/texture/bitmap.cpp
  src/texture/mesh_attribute.cpp
  src/texture/gridvolume.cpp
  src/texture/factory.cpp
)
target_link_libraries(snell_texture PUBLIC snell_core snell_io snell_geometry)

snell_test(test_texture
  SOURCES tests/texture/test_texture.cpp
  LIBS snell_texture PkgConfig::OIIO)

