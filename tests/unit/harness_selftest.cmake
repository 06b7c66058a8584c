# The harness's --jobs (tests/unit/check.hpp): cases run in processes of their own, their outputs
# printed in the cases' order however they finish, a failed check and a process that dies each a
# failed case, the closing count and the exit status as in a serial run.
# Run as: cmake -DEXE=<harness_selftest> -P harness_selftest.cmake
include(${CMAKE_CURRENT_LIST_DIR}/checks.cmake)

execute_process(COMMAND "${EXE}" --jobs 3 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1)
  problem("--jobs 3: exit status ${rc}, expected 1")
endif()
if(NOT out STREQUAL "1 passed, 2 failed\n")
  problem("--jobs 3: standard output '${out}', expected '1 passed, 2 failed'")
endif()
set(want "^output of slow_pass\noutput of fails_a_check\n[^\n]*harness_selftest.cpp:[0-9]+: check failed: 1 \\+ 1 == 3\n    left:  2\n    right: 3\nFAILED: fails_a_check\noutput of dies\ncase process [0-9]+ killed by signal 9\nFAILED: dies\n$")
if(NOT err MATCHES "${want}")
  problem("--jobs 3: standard error, in the cases' order, expected to match\n${want}\ngot:\n${err}")
endif()

execute_process(COMMAND "${EXE}" --jobs 2 slow_pass RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL "1 passed, 0 failed\n" OR NOT err STREQUAL "output of slow_pass\n")
  problem("--jobs 2 slow_pass: exit ${rc}, '${out}', '${err}'")
endif()
foreach(bad 0 3x 257)
  execute_process(COMMAND "${EXE}" --jobs ${bad} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "--jobs needs a number from 1 to 256, not '${bad}'")
    problem("--jobs ${bad}: exit ${rc}, '${err}'")
  endif()
endforeach()
tmcl_check_done("the harness's --jobs")
