# Spectra and colour, film, images (EXR/PNG), render statistics JSON, progress bar.
snell_library(snell_spectral
  src/core/spectrum.cpp
  src/core/progress.cpp
  src/camera/film.cpp
  src/io/image.cpp
  src/io/stats_json.cpp
  src/report/image_metrics.cpp
)
target_link_libraries(snell_spectral PUBLIC snell_base nlohmann_json::nlohmann_json
                      PRIVATE OpenEXR::OpenEXR ${STB_LIBRARY})
target_include_directories(snell_spectral PRIVATE ${STB_INCLUDE_DIR})

snell_test(test_spectrum
  SOURCES tests/unit/test_spectrum.cpp
  LIBS snell_spectral)

snell_test(test_image
  SOURCES tests/unit/test_image.cpp tests/unit/test_image_stats.cpp
          tests/unit/test_image_progress.cpp
  LIBS snell_spectral OpenEXR::OpenEXR ${STB_LIBRARY})
if(TARGET test_image)
  target_include_directories(test_image PRIVATE ${STB_INCLUDE_DIR})
endif()

snell_test(test_film
  SOURCES tests/unit/test_film.cpp
  LIBS snell_spectral)
