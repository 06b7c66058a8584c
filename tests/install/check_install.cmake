# Installs the build into a fresh prefix, checks that everything a user needs landed where
# GNUInstallDirs puts it, then configures, builds and runs examples/consumer against it through
# find_package(tmcl 0.1) (assemble a program with tmcl::asm, run it on tmcl::vm).
# Run as: cmake -DBUILD=<build dir> -DROOT=<source dir> -DWORK=<scratch dir> -DLIBDIR=<libdir>
#               [-DGENERATOR=<generator>] -DTOOLS=<tool;...> -P check_install.cmake
cmake_minimum_required(VERSION 3.25)
foreach(v BUILD ROOT WORK LIBDIR TOOLS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_install.cmake needs -D${v}=...")
  endif()
endforeach()
set(prefix "${WORK}/prefix")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)

execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${prefix} failed (${rc}):\n${out}\n${err}")
endif()

# Every library of the tree (each folder's `tmcl_library(NAME ...)`, examples aside).
include(${CMAKE_CURRENT_LIST_DIR}/tree_libraries.cmake)
tmcl_tree_libraries(libs "${ROOT}")
if(NOT libs)
  problem("found no library in the tree (tmcl_library(NAME ...))")
endif()

set(expect
  include/tmcl/vm.hpp include/tmcl/version.hpp include/tmcl/asm/assembler.hpp
  share/tmcl/include/TMCLParam.tmc share/tmcl/include/Interrupts.inc
  share/doc/tmcl/README.md share/doc/tmcl/LICENSE share/doc/tmcl/tmclasm.md
  ${LIBDIR}/cmake/tmcl/tmclConfig.cmake ${LIBDIR}/cmake/tmcl/tmclConfigVersion.cmake
  ${LIBDIR}/cmake/tmcl/tmclTargets.cmake)
foreach(lib IN LISTS libs)
  list(APPEND expect ${LIBDIR}/libtmcl_${lib}.a)
endforeach()
foreach(tool IN LISTS TOOLS)
  list(APPEND expect bin/${tool} share/man/man1/${tool}.1 share/bash-completion/completions/${tool})
endforeach()
foreach(f IN LISTS expect)
  if(NOT EXISTS "${prefix}/${f}")
    problem("not installed: ${f} (every library needs its tmcl_install_library line in CMakeLists.txt)")
  endif()
endforeach()

# tmclrun is one program: it serves and debugs itself, and nothing else is installed to run.
execute_process(COMMAND "${prefix}/bin/tmclrun" --serve bogus RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 64 OR NOT err MATCHES "^tmclrun: --serve takes tcp:HOST:PORT, pty, stdio or a serial port \\(COM3, /dev/ttyUSB0\\), not 'bogus'")
  problem("installed tmclrun --serve bogus: exit ${rc}, '${err}'")
endif()
if(EXISTS "${prefix}/libexec")
  problem("installed into libexec/: tmclrun is one program")
endif()

# The installed tools run on their own, and say the one version.
foreach(tool IN LISTS TOOLS)
  execute_process(COMMAND "${prefix}/bin/${tool}" --version RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "^${tool} \\(tmcl\\) [0-9]+\\.[0-9]+\\.[0-9]+\n$")
    problem("installed ${tool} --version: exit ${rc}, '${out}'")
  endif()
endforeach()

# The consumer project, against the installation only.
set(gen_args "")
if(GENERATOR)
  set(gen_args -G "${GENERATOR}")
endif()
# Libraries from a sanitizer build call the sanitizer runtime: their consumer links it too.
set(flag_args "")
if(SANITIZE)
  set(flag_args "-DCMAKE_CXX_FLAGS=${SANITIZE}" "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${ROOT}/examples/consumer" -B "${WORK}/consumer" ${gen_args}
  "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release ${flag_args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring examples/consumer against ${prefix} failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK}/consumer" --parallel 2
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building examples/consumer failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${WORK}/consumer/tmcl_consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "consumer: ${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "STOP|Stop|stop")
  problem("examples/consumer ran with exit ${rc}: ${out}${err}")
endif()

if(failures GREATER 0)
  message(FATAL_ERROR "install: ${failures} problem(s); the installation is in ${prefix}")
endif()
file(REMOVE_RECURSE "${WORK}")
message(STATUS "install: every library, header, tool, page and completion in place; the consumer ran")
