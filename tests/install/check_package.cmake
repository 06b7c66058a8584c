# `cpack -G TGZ` and `cpack -G DEB` make packages from the build, the .deb installs with dpkg into
# a throwaway root (its own dpkg database, so the system is untouched), and the tools run from
# there with no source or build tree. Skipped (exit code 77 = CTest SKIP_RETURN_CODE) without dpkg.
# Run as: cmake -DBUILD=<build dir> -DWORK=<scratch dir> -DVERSION=<x.y.z> "-DTOOLS=<tool;...>"
#               -P check_package.cmake
cmake_minimum_required(VERSION 3.25)
find_program(DPKG dpkg)
find_program(DPKG_DEB dpkg-deb)
if(NOT DPKG OR NOT DPKG_DEB)
  message(STATUS "package: dpkg not found, skipped")
  cmake_language(EXIT 77)
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
get_filename_component(cmake_dir "${CMAKE_COMMAND}" DIRECTORY)
find_program(CPACK cpack HINTS "${cmake_dir}" REQUIRED)

# CPack's first step for each format is to build the project's `preinstall` target. The test runs
# after the build, so that step finds nothing to do, but with the Makefiles it still walks every
# target: 7 of the test's 12 s. CPACK_CMAKE_GENERATOR names the generator whose build CPack would
# run; Ninja's has no such target, so CPack goes straight to the build's own install rules (the
# packages are the same, file for file).
execute_process(COMMAND "${CPACK}" -G "TGZ;DEB" -D CPACK_CMAKE_GENERATOR=Ninja --config "${BUILD}/CPackConfig.cmake" -B "${WORK}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cpack failed (${rc}):\n${out}\n${err}")
endif()
# cpack reads the configuration the project wrote (CPackConfig.cmake); a warning there, such as a
# badly escaped regular expression, is a defect users would see on every run.
if("${out}${err}" MATCHES "CMake (Warning|Deprecation)")
  message(FATAL_ERROR "cpack warned:\n${out}\n${err}")
endif()
file(GLOB deb "${WORK}/tmcl_${VERSION}_*.deb")
file(GLOB tgz "${WORK}/tmcl-${VERSION}-*.tar.gz")
if(NOT deb OR NOT tgz)
  message(FATAL_ERROR "cpack made no tmcl_${VERSION}_*.deb or tmcl-${VERSION}-*.tar.gz in ${WORK}")
endif()

execute_process(COMMAND "${DPKG_DEB}" -f "${deb}" Package Version Depends OUTPUT_VARIABLE control)
# Depends comes from dpkg-shlibdeps: libc6 always, and libasan8 etc. first in a sanitizer build.
if(NOT control MATCHES "Package: tmcl\nVersion: ${VERSION}\nDepends: [^\n]*libc6")
  message(FATAL_ERROR "unexpected control data of ${deb}:\n${control}")
endif()

# ... and is exactly what dpkg-shlibdeps says of the package's programs (worked out at cpack time by
# cli/package_depends.cmake.in, not by CPack's look at every file).
find_program(SHLIBDEPS dpkg-shlibdeps)
if(SHLIBDEPS)
  file(GLOB programs "${WORK}/_CPack_Packages/Linux/DEB/*/usr/bin/*")
  file(MAKE_DIRECTORY "${WORK}/shlibdeps/debian")
  file(WRITE "${WORK}/shlibdeps/debian/control" "")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env LC_ALL=C "${SHLIBDEPS}" -O ${programs} WORKING_DIRECTORY "${WORK}/shlibdeps"
    OUTPUT_VARIABLE shlibs ERROR_QUIET)
  string(REGEX MATCH "shlibs:Depends=([^\n]+)" shlibs "${shlibs}")
  set(want "${CMAKE_MATCH_1}")
  string(REGEX MATCH "Depends: ([^\n]+)" got "${control}")
  if(NOT programs OR NOT want OR NOT CMAKE_MATCH_1 STREQUAL want)
    message(FATAL_ERROR "Depends of ${deb} is '${CMAKE_MATCH_1}', not dpkg-shlibdeps's '${want}' for ${programs}")
  endif()
endif()

set(root "${WORK}/root")
file(MAKE_DIRECTORY "${root}/var/lib/dpkg/info" "${root}/var/lib/dpkg/updates")
file(TOUCH "${root}/var/lib/dpkg/status" "${root}/var/lib/dpkg/available")
# --force-depends: the throwaway root has no libc6 package registered (the host's libc runs it).
execute_process(COMMAND "${DPKG}" --root=${root} --log=${WORK}/dpkg.log --force-depends
  --force-script-chrootless -i "${deb}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "dpkg -i ${deb} into ${root} failed (${rc}):\n${out}\n${err}")
endif()
foreach(tool IN LISTS TOOLS)
  foreach(f usr/bin/${tool} usr/share/man/man1/${tool}.1 usr/share/bash-completion/completions/${tool})
    if(NOT EXISTS "${root}/${f}")
      message(FATAL_ERROR "the .deb does not install /${f}")
    endif()
  endforeach()
  execute_process(COMMAND "${root}/usr/bin/${tool}" --version WORKING_DIRECTORY "${root}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "${tool} (tmcl) ${VERSION}\n")
    message(FATAL_ERROR "${tool} from the .deb: exit ${rc}, '${out}'")
  endif()
endforeach()
# tmclrun is one program: it serves and debugs itself, and nothing else is installed to run.
execute_process(COMMAND "${root}/usr/bin/tmclrun" --serve bogus RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 64 OR NOT err MATCHES "^tmclrun: --serve takes tcp:HOST:PORT, pty, stdio or a serial port \\(COM3, /dev/ttyUSB0\\), not 'bogus'")
  message(FATAL_ERROR "tmclrun --serve bogus from the .deb: exit ${rc}, '${err}'")
endif()
if(EXISTS "${root}/usr/libexec")
  message(FATAL_ERROR "the .deb installs /usr/libexec: tmclrun is one program")
endif()
foreach(f usr/lib/cmake/tmcl/tmclConfig.cmake usr/include/tmcl/vm.hpp usr/share/tmcl/include/TMCLParam.tmc)
  if(NOT EXISTS "${root}/${f}")
    message(FATAL_ERROR "the .deb does not install /${f}")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
message(STATUS "package: .tar.gz and .deb made; the .deb installs and its tools run")
