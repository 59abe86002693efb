# rayq::stats: mergeable histograms (the basis of shard/merge identity), included by
# validation/tests/CMakeLists.txt.
if(TARGET rayq::stats)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(rayq_stats_tests ${CMAKE_CURRENT_LIST_DIR}/stats_histogram_test.cpp)
  target_link_libraries(rayq_stats_tests PRIVATE rayq::stats GTest::gtest_main)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(rayq_stats_tests PRIVATE -Wall -Wextra -Wpedantic)
  endif()
  gtest_discover_tests(rayq_stats_tests TEST_PREFIX "stats." DISCOVERY_TIMEOUT 60)
endif()
