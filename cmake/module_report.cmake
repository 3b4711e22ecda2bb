# Comparison reports for `snell compare` (owner: report): image error metrics, HTML, SVG plots,
# false-colour error images.
snell_library(snell_report
  src/report/compare_report.cpp
  src/report/false_colour.cpp
  src/report/html_report.cpp
  src/report/image_metrics.cpp
  src/report/image_ops.cpp
  src/report/svg_plot.cpp
)
target_link_libraries(snell_report PUBLIC snell_io nlohmann_json::nlohmann_json PRIVATE ${STB_LIBRARY})

snell_test(test_report
  SOURCES tests/unit/test_report.cpp
  LIBS snell_report)
