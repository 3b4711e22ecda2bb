# Shapes (analytic sphere and cylinder, triangle meshes and Mitsuba's built-in meshes) with their Embree
# geometry and closest-point projection (owner: geometry). The Scene is in scene/, the shape
# factory in loader/ (it attaches BSDFs), the OBJ/PLY readers in io/.
snell_library(snell_geometry
  src/geometry/shape.cpp
  src/geometry/analytic_shape.cpp
  src/geometry/sphere.cpp
  src/geometry/cylinder.cpp
  src/geometry/mesh.cpp
  src/geometry/builders.cpp
  src/geometry/instance.cpp
)
target_link_libraries(snell_geometry PUBLIC snell_core embree TBB::tbb)

# Its tests trace rays through a Scene: test_geometry is in module_scene.cmake.
