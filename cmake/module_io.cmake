# File formats only (owner: io): EXR/PNG images, images read by OpenImageIO, OBJ/PLY/serialized meshes, render statistics JSON. Nothing
# here knows the film, shapes or scenes; callers convert to and from plain buffers and MeshData.
snell_library(snell_io
  src/io/image.cpp
  src/io/stats_json.cpp
  src/io/mesh_obj.cpp
  src/io/mesh_ply.cpp
  src/io/mesh_serialized.cpp
  src/io/texture_image.cpp
  src/io/volume_grid.cpp
  src/io/atomic_file.cpp
)
target_link_libraries(snell_io PUBLIC snell_core nlohmann_json::nlohmann_json
                      PRIVATE OpenEXR::OpenEXR PkgConfig::OIIO tinyobjloader::tinyobjloader ZLIB::ZLIB ${STB_LIBRARY})
target_include_directories(snell_io PRIVATE ${STB_INCLUDE_DIR})

snell_test(test_image
  SOURCES tests/unit/test_image.cpp tests/unit/test_image_stats.cpp
          tests/unit/test_image_progress.cpp
  LIBS snell_io OpenEXR::OpenEXR PkgConfig::OIIO ${STB_LIBRARY})
if(TARGET test_image)
  target_include_directories(test_image PRIVATE ${STB_INCLUDE_DIR})
endif()

snell_test(test_mesh_io
  SOURCES tests/unit/test_mesh_io.cpp
  LIBS snell_io ZLIB::ZLIB)
