# Fails when a unit test makes a temporary file with std::tmpfile() instead of
# tmcl_test::scratch_file() (tests/unit/os_test.hpp): the Windows build runs the unit tests under
# Wine two at a time, and Wine's tmpfile() then fails now and then (a null FILE*, or a DAP
# session without input: CI's Windows step). check.hpp's --jobs is POSIX alone (fork) and may.
# Run as: cmake -DROOT=<source dir>/tests -P scratch_files.cmake
include(${CMAKE_CURRENT_LIST_DIR}/checks.cmake)
file(GLOB_RECURSE sources RELATIVE "${ROOT}" "${ROOT}/*.cpp" "${ROOT}/*.hpp")
foreach(f IN LISTS sources)
  if(f STREQUAL "unit/os_test.hpp" OR f STREQUAL "unit/check.hpp")
    continue()
  endif()
  file(STRINGS "${ROOT}/${f}" lines REGEX "tmpfile\\(")
  foreach(l IN LISTS lines)
    problem("tests/${f}: '${l}': use tmcl_test::scratch_file() (tests/unit/os_test.hpp), which works under Wine")
  endforeach()
endforeach()
tmcl_check_done("no unit test makes its temporary files with tmpfile()")
