# fuzz_loader: the scene loader's libFuzzer target (tests/fuzz/, built with -DSNELL_BUILD_FUZZ=ON in
# the sanitizer build). ctest's fuzz.loader_corpus runs a bounded, seeded number of cases from the
# checked-in corpus; `make fuzz` runs long.
if(SNELL_BUILD_FUZZ)
  add_executable(fuzz_loader tests/fuzz/fuzz_loader.cpp tests/fuzz/bundle.cpp tests/fuzz/xml_mutator.cpp
                             tests/fuzz/asset_mutator.cpp)
  target_include_directories(fuzz_loader PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_link_libraries(fuzz_loader PRIVATE snell_loader snell_integrators pugixml::pugixml ZLIB::ZLIB)
  target_compile_options(fuzz_loader PRIVATE ${SNELL_WARNINGS} -fsanitize=fuzzer)
  target_link_options(fuzz_loader PRIVATE -fsanitize=fuzzer)
  add_dependencies(snell_test_suite fuzz_loader)

  set(SNELL_FUZZ_TEST_RUNS 2000 CACHE STRING "Cases fuzz.loader_corpus runs (make test)")
  if(SNELL_BUILD_TESTS)
    # A fresh scratch corpus each time, so that the run depends only on the seed and the corpus.
    add_test(NAME fuzz.loader_corpus
             COMMAND bash -c "rm -rf \"$1\" && exec bash \"$0\" \"$2\" ${SNELL_FUZZ_TEST_RUNS} \"$1\" \"$3\" -seed=1"
                     ${PROJECT_SOURCE_DIR}/tests/fuzz/run_fuzz.sh ${PROJECT_BINARY_DIR}/fuzz/test_scratch
                     $<TARGET_FILE:fuzz_loader> ${PROJECT_BINARY_DIR}/fuzz/test_findings)
    set_tests_properties(fuzz.loader_corpus PROPERTIES TIMEOUT 900)
  endif()
endif()
