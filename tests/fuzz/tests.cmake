# fuzz: the libFuzzer targets of tests/fuzz/CMakeLists.txt, a clang tree of its own that
# tests/fuzz/run-fuzz.sh builds under the main build directory (the gcc build is unaffected).
# fuzz.build builds them once (a fixture); each fuzz.TARGET replays its regression inputs and then
# fuzzes for STRATA_FUZZ_SECONDS (default 6) from the checked-in seed corpus.
find_program(STRATA_CLANGXX clang++)
if(STRATA_CLANGXX)
  set(STRATA_FUZZ_DIR ${CMAKE_BINARY_DIR}/fuzz)
  set(STRATA_FUZZ_SECONDS 6 CACHE STRING "seconds each fuzz target runs in ctest -L fuzz")
  add_test(NAME fuzz.build COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/run-fuzz.sh build ${STRATA_FUZZ_DIR})
  set_tests_properties(fuzz.build PROPERTIES LABELS fuzz TIMEOUT 900 FIXTURES_SETUP strata_fuzz_build)
  foreach(target gltf create_session frame_input camera_path exr texture environment)
    add_test(NAME fuzz.${target}
             COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/run-fuzz.sh run ${STRATA_FUZZ_DIR} ${target} ${STRATA_FUZZ_SECONDS})
    set_tests_properties(fuzz.${target} PROPERTIES LABELS fuzz TIMEOUT 120 FIXTURES_REQUIRED strata_fuzz_build)
  endforeach()
else()
  message(STATUS "clang++ not found: the fuzz tests (ctest -L fuzz) are left out")
endif()
