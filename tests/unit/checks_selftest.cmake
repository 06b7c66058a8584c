# The test scripts' harness (checks.cmake) on a script made to fail: every problem is counted,
# inside a loop and through expect and expect_match, and a text is shown as it is (a `${NAME}`
# from a scanned file stays, a backslash too), which macros got wrong.
# Run as: cmake -DWORK=<scratch dir> -P checks_selftest.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/failing.cmake" [=[
include("${HARNESS}")
expect("a" 1 2)
expect_match("b" "^x" "y")
# Lines as a scanned file has them: a macro replaced the first's ${...}, and choked on the second.
set(line [[x ${SOME_NAME}/y]])
problem("line: ${line}")
set(line [[x C:\backslash]])
problem("line: ${line}")
foreach(i 1 2)
  expect("loop" 1 "${i}")
endforeach()
tmcl_check_done("the failing script")
]=])
execute_process(COMMAND ${CMAKE_COMMAND} -DHARNESS=${CMAKE_CURRENT_LIST_DIR}/checks.cmake -P "${WORK}/failing.cmake"
  RESULT_VARIABLE rc ERROR_VARIABLE err)
set(wrong "")
if(rc EQUAL 0)
  string(APPEND wrong "\n  it exited 0")
endif()
if(err MATCHES "Syntax error|Invalid escape")
  string(APPEND wrong "\n  a text was read as CMake code")
endif()
foreach(want "a: expected '1', got '2'" "b: expected a match of '^x' in:" "loop: expected '1', got '2'"
             "the failing script: 5 problem(s)" "line: x \${SOME_NAME}/y\n" "line: x C:\\backslash\n")
  string(FIND "${err}" "${want}" at)
  if(at EQUAL -1)
    string(APPEND wrong "\n  no '${want}'")
  endif()
endforeach()
if(wrong)
  message(FATAL_ERROR "checks.cmake on a failing script:${wrong}\nits output:\n${err}")
endif()
file(REMOVE_RECURSE "${WORK}")
message(STATUS "checks.cmake counts every problem and shows its text as it is")
