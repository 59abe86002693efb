# The exact oracle's tests (issue 4), included by validation/tests/CMakeLists.txt:
#   oracle_exact_test         hand cases with known exact answers (t, tangency, rims, apex, clip box, transformed)
#   oracle_second_route_test  CGAL's spherical and exact kernels agree with the oracle exactly
#   oracle_fixtures_test      the fixture format: round trip, the checked-in files, "file:line: expected …" errors
#   oracle_measurement_test   the kernel under every policy against the oracle on every checked-in
#                             fixture: prints the table; asserts only what must already hold
# The tests include only the oracle's non-template API (no CGAL, no kernel instantiations: those
# live in rayq::oracle_harness), so they compile quickly.
if(TARGET rayq::oracle)
  find_package(GTest REQUIRED)
  include(GoogleTest)

  add_executable(rayq_oracle_tests
    ${CMAKE_CURRENT_LIST_DIR}/oracle_exact_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/oracle_second_route_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/oracle_fixtures_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/oracle_measurement_test.cpp)
  target_link_libraries(rayq_oracle_tests PRIVATE rayq::oracle rayq::oracle_harness GTest::gtest_main)
  target_compile_definitions(rayq_oracle_tests PRIVATE RAYQ_ORACLE_FIXTURES="${PROJECT_SOURCE_DIR}/fixtures/oracle"
                                                       RAYQ_FIXTURES_README="${PROJECT_SOURCE_DIR}/fixtures/README.md"
                                                       RAYQ_ORACLE_REPRODUCERS="${PROJECT_SOURCE_DIR}/fixtures/oracle-reproducers")
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(rayq_oracle_tests PRIVATE -Wall -Wextra -Wpedantic)
  endif()
  gtest_discover_tests(rayq_oracle_tests TEST_PREFIX "oracle." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 120)
endif()
