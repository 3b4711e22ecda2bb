# The sanitizer build (`make test-sanitize`, folder build-sanitize/): ASan + UBSan with clang,
# and the scene-loader fuzz target (libFuzzer). -O1 keeps the suite quick while the reports keep
# their line numbers; -fno-sanitize-recover makes every UBSan report fail the test that hit it.
option(SNELL_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer (clang)" OFF)
option(SNELL_BUILD_FUZZ "Build fuzz_loader, the scene-loader fuzz target (libFuzzer; needs clang)" OFF)

# The tests the sanitizer build registers: unit, parser and manifold tests. The statistical tests
# (tests/stat) are too slow under ASan and find their bugs as numbers, not memory errors.
set(SNELL_SANITIZE_TESTS
    test_core test_spectrum test_props test_film test_samplers test_image test_mesh_io test_bsdf_unit
    test_light test_geometry test_scatter test_bdpt_vertices test_scene_parser test_scene_loader_full
    test_manifold test_report test_team_pass
    CACHE STRING "Test executables built and run by the sanitizer build")

if(SNELL_SANITIZE OR SNELL_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SNELL_SANITIZE / SNELL_BUILD_FUZZ need clang: cmake -DCMAKE_CXX_COMPILER=clang++")
  endif()
  set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O1 -g")
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

# Coverage feedback for the fuzzer in every library; executables without libFuzzer get the
# sanitizer runtime's empty coverage callbacks.
if(SNELL_BUILD_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# The executables the sanitizer build needs (`cmake --build --target snell_test_suite`); snell_test
# adds each test it registers.
add_custom_target(snell_test_suite)
