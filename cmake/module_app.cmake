# The `snell` command. Built-in scenes are embedded from scenes/ at configure time.
file(READ ${PROJECT_SOURCE_DIR}/scenes/droplet/droplet.xml DROPLET_XML)
configure_file(${PROJECT_SOURCE_DIR}/apps/builtin_scenes.cpp.in ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp @ONLY)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenes/droplet/droplet.xml)

# The sub-commands and their helpers are one library, so that the two front ends, the command
# line (apps/snell.cpp) and the Python module (python/), run the same code.
add_library(snell_commands STATIC
  apps/app_common.cpp
  apps/output_files.cpp
  apps/cmd_render.cpp
  apps/cmd_diff.cpp
  apps/cmd_compare.cpp
  apps/cmd_merge.cpp
  ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp)
target_include_directories(snell_commands PUBLIC ${PROJECT_SOURCE_DIR}/apps)
target_link_libraries(snell_commands PUBLIC snell_loader snell_integrators snell_report CLI11::CLI11)
target_compile_options(snell_commands PRIVATE ${SNELL_WARNINGS})

add_executable(snell apps/snell.cpp)
target_link_libraries(snell PRIVATE snell_commands)
target_compile_options(snell PRIVATE ${SNELL_WARNINGS})

# `make bench` (Google Benchmark); built only with -DSNELL_BUILD_BENCH=ON.
if(SNELL_BUILD_BENCH)
  find_package(benchmark REQUIRED)
  add_executable(snell_bench bench/bench_main.cpp bench/bench_textures.cpp
                             ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp)
  target_include_directories(snell_bench PRIVATE ${PROJECT_SOURCE_DIR}/apps)
  target_link_libraries(snell_bench PRIVATE snell_loader snell_integrators benchmark::benchmark PkgConfig::OIIO)
endif()

if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  add_test(NAME cli.end_to_end COMMAND bash ${PROJECT_SOURCE_DIR}/tests/cli/test_cli.sh $<TARGET_FILE:snell>)
  set_tests_properties(cli.end_to_end PROPERTIES TIMEOUT 300)
endif()

# Issue 27 end to end: MPI ranks and farm tasks give the one-process frame bit for bit.
if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  find_program(SNELL_MPIRUN mpirun)
  if(SNELL_MPIRUN AND TARGET MPI::MPI_CXX)
    set(SNELL_DISTRIBUTED_MODE mpi)
  else()
    set(SNELL_DISTRIBUTED_MODE local)
  endif()
  add_test(NAME cli.distributed COMMAND bash ${PROJECT_SOURCE_DIR}/tests/cli/test_distributed.sh $<TARGET_FILE:snell>
                                        ${SNELL_DISTRIBUTED_MODE})
  set_tests_properties(cli.distributed PROPERTIES TIMEOUT 600)
endif()

# `snell compare` end to end: cli.compare writes a report (and checks report.json and the error
# messages); cli.compare_html opens that report in headless Chromium.
if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  add_executable(test_compare_cli tests/cli/test_compare.cpp)
  target_link_libraries(test_compare_cli PRIVATE snell_report GTest::gtest GTest::gtest_main)
  target_compile_options(test_compare_cli PRIVATE ${SNELL_WARNINGS})
  set(SNELL_COMPARE_ENV "SNELL_BIN=$<TARGET_FILE:snell>;SNELL_COMPARE_DIR=${PROJECT_BINARY_DIR}/test_compare_report")
  add_test(NAME cli.compare COMMAND test_compare_cli --gtest_filter=CompareCli.*)
  set_tests_properties(cli.compare PROPERTIES TIMEOUT 300 ENVIRONMENT "${SNELL_COMPARE_ENV}"
                       FIXTURES_SETUP compare_report)
  add_test(NAME cli.compare_html COMMAND test_compare_cli --gtest_filter=CompareHtml.*)
  set_tests_properties(cli.compare_html PROPERTIES TIMEOUT 300 ENVIRONMENT "${SNELL_COMPARE_ENV}"
                       FIXTURES_REQUIRED compare_report)
  add_dependencies(test_compare_cli snell)
endif()

# The layout of every tracked C++ source against .clang-format (STYLE.md habit 9).
if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  add_test(NAME style.clang_format COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/check-format.sh)
endif()

# Includes in src/ and library links run from higher layers to lower ones only, and each folder
# is one library (scripts/check-layers.sh; the layer order is listed there).
if(SNELL_BUILD_TESTS AND NOT SNELL_SANITIZE)
  add_test(NAME style.layers COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/check-layers.sh)
endif()

# `cmake --install`: the command (the Python package installs beside it, cmake/module_python.cmake).
install(TARGETS snell RUNTIME DESTINATION bin COMPONENT cli)
