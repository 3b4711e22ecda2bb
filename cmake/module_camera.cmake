# Cameras (perspective, thinlens, orthographic), film, pixel filters and the filter factory (owner: camera).
snell_library(snell_camera
  src/camera/camera.cpp
  src/camera/field_of_view.cpp
  src/camera/thinlens.cpp
  src/camera/orthographic.cpp
  src/camera/filter.cpp
  src/camera/film.cpp
  src/camera/outlier_clamp.cpp
  src/camera/factory.cpp
)
target_link_libraries(snell_camera PUBLIC snell_core)

snell_test(test_film
  SOURCES tests/unit/test_film.cpp tests/unit/test_camera.cpp
  LIBS snell_camera)
