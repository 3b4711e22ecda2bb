# The Scene (owner: scene): shapes in Embree's BVH, lights and their sampler, the camera. It holds
# no integrator (LoadedScene does, in loader/), so it sits below manifold/, render/ and the
# integrators that use it.
snell_library(snell_scene
  src/scene/scene.cpp
  src/scene/light_choice.cpp
  src/scene/caster_sampling.cpp
)
target_link_libraries(snell_scene PUBLIC snell_geometry snell_bsdf snell_light snell_camera snell_core embree)

# The shape tests trace rays through a Scene, so they are registered here rather than beside
# snell_geometry.
snell_test(test_geometry
  SOURCES tests/unit/test_geometry_sphere.cpp tests/unit/test_geometry_cylinder.cpp tests/unit/test_geometry_mesh.cpp
          tests/unit/test_geometry_scene.cpp tests/unit/test_geometry_instance.cpp
  LIBS snell_scene)
