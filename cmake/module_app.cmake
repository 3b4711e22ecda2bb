# The `snell` command. Built-in scenes are embedded from scenes/ at configure time.
file(READ ${PROJECT_SOURCE_DIR}/scenes/droplet/droplet.xml DROPLET_XML)
configure_file(${PROJECT_SOURCE_DIR}/apps/builtin_scenes.cpp.in ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp @ONLY)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/scenes/droplet/droplet.xml)

add_executable(snell apps/snell.cpp ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp)
target_include_directories(snell PRIVATE ${PROJECT_SOURCE_DIR}/apps)
target_link_libraries(snell PRIVATE snell_loader snell_integrators CLI11::CLI11)
target_compile_options(snell PRIVATE ${SNELL_WARNINGS})

# `make bench` (Google Benchmark); built only with -DSNELL_BUILD_BENCH=ON.
if(SNELL_BUILD_BENCH)
  find_package(benchmark REQUIRED)
  add_executable(snell_bench bench/bench_main.cpp ${PROJECT_BINARY_DIR}/generated/builtin_scenes.cpp)
  target_include_directories(snell_bench PRIVATE ${PROJECT_SOURCE_DIR}/apps)
  target_link_libraries(snell_bench PRIVATE snell_loader snell_integrators benchmark::benchmark)
endif()

if(SNELL_BUILD_TESTS)
  add_test(NAME cli.end_to_end COMMAND bash ${PROJECT_SOURCE_DIR}/tests/cli/test_cli.sh $<TARGET_FILE:snell>)
  set_tests_properties(cli.end_to_end PROPERTIES TIMEOUT 300)
endif()
