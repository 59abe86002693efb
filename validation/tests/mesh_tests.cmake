# Tests of rayq::mesh (issue 5): tessellations, IO round trips, the ray–mesh caster, and the
# kernel-vs-mesh agreement and convergence rates. Included from validation/tests/CMakeLists.txt.
if(TARGET rayq::mesh)
  find_package(GTest REQUIRED)
  include(GoogleTest)
  add_executable(rayq_mesh_tests
    ${CMAKE_CURRENT_LIST_DIR}/mesh_tessellate_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/mesh_io_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/mesh_raycast_test.cpp
    ${CMAKE_CURRENT_LIST_DIR}/mesh_convergence_test.cpp
  )
  target_link_libraries(rayq_mesh_tests PRIVATE rayq::mesh GTest::gtest_main)
  target_compile_definitions(rayq_mesh_tests PRIVATE RAYQ_MESH_FIXTURES="${PROJECT_SOURCE_DIR}/fixtures/meshes")
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(rayq_mesh_tests PRIVATE -Wall -Wextra -Wpedantic -Werror)
  endif()
  gtest_discover_tests(rayq_mesh_tests TEST_PREFIX "mesh." DISCOVERY_TIMEOUT 60
                       PROPERTIES LABELS mesh)
endif()
