# Builds and runs kernel/tests/consumer twice: against an installed rayq (find_package) and with
# rayq's source tree added as a subdirectory; with EXPECT_EMBREE, the Embree adapter (rayq::embree,
# find_package(rayq COMPONENTS embree)) both ways too.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} --install ${RAYQ_BUILD} --prefix ${prefix})
if(NOT EXISTS ${prefix}/include/rayq/rayq.hpp)
  message(FATAL_ERROR "install did not place include/rayq/rayq.hpp")
endif()

foreach(mode find_package add_subdirectory)
  set(build ${WORK}/${mode})
  if(mode STREQUAL find_package)
    set(how -DCMAKE_PREFIX_PATH=${prefix})
  else()
    set(how -DRAYQ_SOURCE_DIR=${RAYQ_SOURCE})
  endif()
  run(${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/consumer -B ${build} -G ${GENERATOR}
      -DCMAKE_CXX_COMPILER=${CXX} -DRAYQ_EXPECT_EMBREE=${EXPECT_EMBREE} ${how})
  run(${CMAKE_COMMAND} --build ${build})
  run(${build}/consumer)
  if(EXPECT_EMBREE)
    run(${build}/embree_consumer)
  endif()
  message(STATUS "consumer via ${mode}: ok")
endforeach()
