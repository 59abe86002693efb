# Issue 9, included by validation/tests/CMakeLists.txt (and by tools/sanitize without the validation
# suite): the deterministic edge-case generator and the replay of fixtures/fuzz/
# (edge_case_test.cpp), with the exact oracle sampled when rayq::oracle_harness is built. The
# libFuzzer harnesses and the sanitizer build are a project of their own: tools/sanitize/.
find_package(GTest REQUIRED)
include(GoogleTest)
add_executable(rayq_edge_case_tests ${CMAKE_CURRENT_LIST_DIR}/edge_case_test.cpp)
target_link_libraries(rayq_edge_case_tests PRIVATE rayq::fuzz_checks GTest::gtest_main)
target_compile_definitions(rayq_edge_case_tests PRIVATE RAYQ_FUZZ_FIXTURES="${CMAKE_CURRENT_LIST_DIR}/../../fixtures/fuzz")
if(TARGET rayq::oracle_harness)
  target_link_libraries(rayq_edge_case_tests PRIVATE rayq::oracle rayq::oracle_harness)
  target_compile_definitions(rayq_edge_case_tests PRIVATE RAYQ_EDGE_CASE_ORACLE)
endif()
target_compile_options(rayq_edge_case_tests PRIVATE -Wall -Wextra -Wpedantic)
set(RAYQ_EDGE_CASES "" CACHE STRING "Byte strings per family for the edge-case test (empty: its default)")
set(rayq_edge_case_env)
if(RAYQ_EDGE_CASES)
  set(rayq_edge_case_env ENVIRONMENT RAYQ_EDGE_CASES=${RAYQ_EDGE_CASES})
endif()
gtest_discover_tests(rayq_edge_case_tests TEST_PREFIX "edge_case." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600 ${rayq_edge_case_env})
