# The shared tile render loop and the pixel-sample pipeline (below the integrators, which
# own their render loops and use this one by default).
snell_library(snell_render
  src/render/renderer.cpp
  src/render/camera_sample.cpp
)
target_link_libraries(snell_render PUBLIC snell_scene snell_sampler snell_camera snell_core TBB::tbb)
