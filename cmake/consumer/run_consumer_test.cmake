# CTest package_consumer_test: installs BUILD into WORK/install, configures and builds the
# consumer project (CONSUMER) against it with find_package(garbing), and runs it. Any failing
# step fails the test with its output.
#   cmake -DBUILD=... -DCONSUMER=... -DWORK=... -DGENERATOR=... -P run_consumer_test.cmake
file(REMOVE_RECURSE ${WORK})
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()
step("install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/install)
foreach(f lib/cmake/garbing/garbingConfig.cmake lib/cmake/garbing/garbingTargets.cmake
          include/garbing/garb.h bin/garb)
  if(NOT EXISTS ${WORK}/install/${f})
    message(FATAL_ERROR "install: ${f} missing")
  endif()
endforeach()
step("configure" ${CMAKE_COMMAND} -S ${CONSUMER} -B ${WORK}/build -G ${GENERATOR}
     -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/install)
step("build" ${CMAKE_COMMAND} --build ${WORK}/build)
step("run" ${WORK}/build/consumer)
message(STATUS "${step_output}")
