# Issue 9, included by validation/tests/CMakeLists.txt: the deterministic edge-case generator and
# the replay of fixtures/fuzz/ (edge_case_test.cpp), with the exact oracle sampled. The libFuzzer
# harnesses and the sanitizer build are a project of their own: tools/sanitize/CMakeLists.txt.
if(TARGET rayq::oracle_harness)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(rayq_edge_case_tests ${CMAKE_CURRENT_LIST_DIR}/edge_case_test.cpp)
  target_link_libraries(rayq_edge_case_tests PRIVATE rayq::fuzz_checks rayq::oracle rayq::oracle_harness GTest::gtest_main)
  target_compile_definitions(rayq_edge_case_tests PRIVATE RAYQ_EDGE_CASE_ORACLE RAYQ_FUZZ_FIXTURES="${PROJECT_SOURCE_DIR}/fixtures/fuzz")
  target_compile_options(rayq_edge_case_tests PRIVATE -Wall -Wextra -Wpedantic)
  gtest_discover_tests(rayq_edge_case_tests TEST_PREFIX "edge_case." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
endif()
