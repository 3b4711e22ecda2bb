# Emitters (one file per Mitsuba emitter type), the environment-map sampling distribution, the
# RGB emission upsampling lattice and the emitter factory (owner: light).
snell_library(snell_light
  src/light/area.cpp
  src/light/point.cpp
  src/light/spot.cpp
  src/light/projector.cpp
  src/light/directional.cpp
  src/light/constant.cpp
  src/light/envmap.cpp
  src/light/rgb_illuminant_table.cpp
  src/light/texture_emission.cpp
  src/light/factory.cpp
)
# Environment maps are read with io/image.h; area lights use the Shape interface; textured
# emission reads texture/; the projector's field of view is the camera's (camera/field_of_view.h).
target_link_libraries(snell_light PUBLIC snell_texture snell_camera snell_geometry snell_io snell_core TBB::tbb)

snell_test(test_light
  SOURCES tests/unit/test_light.cpp
  LIBS snell_light)

snell_test(test_light_stat
  SOURCES tests/stat/test_light_stat.cpp
  LIBS snell_light)
