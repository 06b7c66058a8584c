# Installs the build into a fresh prefix and builds tests/install/every_target against it: a
# consumer that links every exported tmcl:: target and compiles every installed header alone
# (docs/install.md). It fails when the package configuration does not find what its targets link,
# when a header needs an include it does not make, or when the package exports other libraries
# than the tree has.
# Run as: cmake -DBUILD=<build dir> -DROOT=<source dir> -DWORK=<scratch dir>
#               [-DGENERATOR=<generator>] [-DSANITIZE=<flags>] -P check_every_target.cmake
cmake_minimum_required(VERSION 3.25)
foreach(v BUILD ROOT WORK)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_every_target.cmake needs -D${v}=...")
  endif()
endforeach()
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/tree_libraries.cmake)
set(prefix "${WORK}/prefix")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${prefix} failed (${rc}):\n${out}\n${err}")
endif()

tmcl_tree_libraries(libs "${ROOT}")
set(gen_args "")
if(GENERATOR)
  set(gen_args -G "${GENERATOR}")
endif()
set(flag_args "")
if(SANITIZE)  # libraries of a sanitizer build call its runtime: the consumer links it too
  set(flag_args "-DCMAKE_CXX_FLAGS=${SANITIZE}" "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${CMAKE_CURRENT_LIST_DIR}/every_target" -B "${WORK}/consumer"
  ${gen_args} "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release "-DEXPECT=${libs}" ${flag_args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the every-target consumer against ${prefix} failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/consumer" --parallel 2
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the every-target consumer failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${WORK}/consumer/every_target" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  problem("the every-target consumer ran with exit ${rc}: ${out}${err}")
endif()
if(failures GREATER 0)
  message(FATAL_ERROR "every_target: ${failures} problem(s); the installation is in ${prefix}")
endif()
file(REMOVE_RECURSE "${WORK}")
message(STATUS "every_target: ${out}")
