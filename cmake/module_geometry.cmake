# Shapes (analytic sphere, triangle meshes and Mitsuba's built-in meshes), the Embree scene,
# closest-point projection, OBJ/PLY readers (owner: geometry).
snell_library(snell_geometry
  src/geometry/shape.cpp
  src/core/mesh_data.cpp
  src/geometry/sphere.cpp
  src/geometry/mesh.cpp
  src/geometry/builders.cpp
  src/scene/scene.cpp
  src/loader/shape_factory.cpp
  src/io/mesh_obj.cpp
  src/io/mesh_ply.cpp
)
target_link_libraries(snell_geometry PUBLIC snell_spectral embree TBB::tbb tinyobjloader::tinyobjloader)

snell_test(test_geometry
  SOURCES tests/unit/test_geometry_sphere.cpp tests/unit/test_geometry_mesh.cpp
          tests/unit/test_geometry_scene.cpp tests/unit/test_mesh_io.cpp
  LIBS snell_geometry)
