# Tests of issue 6, included by validation/tests/CMakeLists.txt:
#   rayq_fit_tests    the Ceres fits on synthetic data with known parameters (noise, outliers,
#                     flat data, zeros, degenerate input); no kernel, no oracle — milliseconds
#   rayq_sweep_tests  the precision sweeps of the kernel against the exact oracle: accurate flat and
#                     never misclassifying where it is exact, fast on the sphere growing as δ^-1/2
if(TARGET rayq::fit)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(rayq_fit_tests ${CMAKE_CURRENT_LIST_DIR}/fit_error_model_test.cpp)
  target_link_libraries(rayq_fit_tests PRIVATE rayq::fit GTest::gtest_main)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(rayq_fit_tests PRIVATE -Wall -Wextra -Wpedantic)
  endif()
  gtest_discover_tests(rayq_fit_tests TEST_PREFIX "fit." DISCOVERY_TIMEOUT 60 PROPERTIES LABELS fit)
endif()

if(TARGET rayq::sweep)
  add_executable(rayq_sweep_tests ${CMAKE_CURRENT_LIST_DIR}/fit_sweep_test.cpp)
  target_link_libraries(rayq_sweep_tests PRIVATE rayq::sweep GTest::gtest_main)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(rayq_sweep_tests PRIVATE -Wall -Wextra -Wpedantic)
  endif()
  gtest_discover_tests(rayq_sweep_tests TEST_PREFIX "sweep." DISCOVERY_TIMEOUT 60 PROPERTIES LABELS fit TIMEOUT 120)
endif()
