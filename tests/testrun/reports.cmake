# The reports of `tmclrun --test` read by the tools CI uses (tests/testrun/CMakeLists.txt):
#   MODE=etree        the JUnit XML by Python's xml.etree (check_junit.py)
#   MODE=junitparser  the JUnit XML by junitparser (Debian's python3-junitparser)
#   MODE=genhtml      the lcov tracefile rendered by genhtml --branch-coverage, with no warning,
#                     and read by lcov --summary (Debian's lcov)
# A test whose tool is missing is skipped with a message (.ci/run installs them).
# Run as: cmake -DMODE=... -DTMCLRUN=... -DCASES=tests/golden/testrun -DWORK=dir
#               -DPYTHON=python3 -DGENHTML=genhtml -DLCOV=lcov -P reports.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

if(MODE STREQUAL "genhtml")
  if(NOT GENHTML OR NOT EXISTS "${GENHTML}")
    message(STATUS "SKIPPED: genhtml (Debian's lcov) is not installed; the tracefile is pinned by golden/testrun/coverage")
    return()
  endif()
  execute_process(COMMAND ${TMCLRUN} --test --coverage ${WORK}/coverage.info suite ../../../examples/tested/tests
                  WORKING_DIRECTORY ${CASES} OUTPUT_QUIET RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1)  # suite/fail.tmctest fails on purpose
    message(FATAL_ERROR "tmclrun --test --coverage: exit status ${rc}, expected 1")
  endif()
  execute_process(COMMAND ${GENHTML} --branch-coverage -o ${WORK}/html ${WORK}/coverage.info
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR "${out}${err}" MATCHES "WARNING|ERROR|[Ww]arning")
    message(FATAL_ERROR "genhtml complained (${rc}):\n${out}${err}")
  endif()
  if(NOT EXISTS ${WORK}/html/index.html)
    message(FATAL_ERROR "genhtml wrote no index.html:\n${out}${err}")
  endif()
  if(NOT out MATCHES "lines\\.+: 100\\.0% \\(49 of 49 lines\\)" OR NOT out MATCHES "branches\\.+: 100\\.0% \\(10 of 10 branches\\)")
    message(FATAL_ERROR "genhtml's totals are not the tracefile's (49 lines, 10 branches):\n${out}")
  endif()
  if(LCOV AND EXISTS "${LCOV}")
    execute_process(COMMAND ${LCOV} --summary ${WORK}/coverage.info --rc lcov_branch_coverage=1
                    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0 OR NOT "${out}${err}" MATCHES "functions\\.+: 100\\.0% \\(3 of 3 functions\\)")
      message(FATAL_ERROR "lcov --summary (${rc}):\n${out}${err}")
    endif()
  endif()
  message(STATUS "genhtml rendered the tracefile without a warning:\n${out}")
  return()
endif()

# The JUnit file: the golden suite (a pass, a failure, a skip) and a test whose program is bad.
execute_process(COMMAND ${TMCLRUN} --test --junit ${WORK}/junit.xml suite bad/program.tmctest
                WORKING_DIRECTORY ${CASES} OUTPUT_QUIET ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 65)
  message(FATAL_ERROR "tmclrun --test --junit: exit status ${rc}, expected 65 (a bad program)")
endif()
if(NOT PYTHON OR NOT EXISTS "${PYTHON}")
  message(STATUS "SKIPPED: python3 is not installed; the JUnit XML is pinned by golden/testrun/junit")
  return()
endif()
set(python ${PYTHON})
set(flag "")
if(MODE STREQUAL "junitparser")
  set(flag --junitparser)
  # Debian's package is for the system's Python, which a PATH's python3 (pyenv, venv) may not be.
  set(python "")
  foreach(candidate ${PYTHON} /usr/bin/python3)
    execute_process(COMMAND ${candidate} -c "import junitparser" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
    if(rc EQUAL 0)
      set(python ${candidate})
      break()
    endif()
  endforeach()
  if(NOT python)
    message(STATUS "SKIPPED: junitparser (Debian's python3-junitparser) is not installed")
    return()
  endif()
endif()
execute_process(COMMAND ${python} ${CMAKE_CURRENT_LIST_DIR}/check_junit.py ${WORK}/junit.xml ${flag}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the JUnit XML as ${MODE} reads it:\n${out}${err}")
endif()
message(STATUS "${MODE} read the JUnit XML: 4 tests, 1 failure, 1 error, 1 skipped")
