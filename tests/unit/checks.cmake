# The harness of the test scripts run with `cmake -P` (tests/install, tests/cli, tests/unit), as
# check.hpp is of the C++ tests: problems are collected, so that a script reports all of them
# before it fails, and the tool list a test passes is read in one place. A script does
# include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake), calls problem("...") (or expect,
# expect_match) for each one found and tmcl_check_done("what was checked") at the end.
set(failures 0)
# problem(TEXT): one problem found, TEXT shown as it is. Functions, not macros: a macro's
# arguments are read a second time, so a `${NAME}` in TEXT (a line of a CMake file) would be
# replaced, and a backslash lost. Each passes the count up to its caller.
function(problem text)
  message(SEND_ERROR "${text}")
  math(EXPR failures "${failures} + 1")
  set(failures ${failures} PARENT_SCOPE)
endfunction()

# expect(WHAT WANT GOT): a problem when GOT is not WANT.
function(expect what want got)
  if(NOT "${got}" STREQUAL "${want}")
    problem("${what}: expected '${want}', got '${got}'")
    set(failures ${failures} PARENT_SCOPE)
  endif()
endfunction()

# expect_match(WHAT REGEX TEXT): a problem when TEXT does not match REGEX.
function(expect_match what regex text)
  if(NOT "${text}" MATCHES "${regex}")
    problem("${what}: expected a match of '${regex}' in:\n${text}")
    set(failures ${failures} PARENT_SCOPE)
  endif()
endfunction()

# Ends the script: a fatal error naming how many problems there were, if any.
macro(tmcl_check_done what)
  if(failures GREATER 0)
    message(FATAL_ERROR "${what}: ${failures} problem(s)")
  endif()
endmacro()

# tmcl_read_tools(ENTRIES NAMES_VAR): ENTRIES is the list "tool=path;..." a test passes as TOOLS;
# sets NAMES_VAR to the tool names and path_<tool> to each tool's path, in the caller's scope.
macro(tmcl_read_tools entries names_var)
  set(${names_var} "")
  foreach(entry IN LISTS ${entries})
    string(REGEX MATCH "^[^=]+" tool "${entry}")
    string(REGEX REPLACE "^[^=]+=" "" path_${tool} "${entry}")
    list(APPEND ${names_var} ${tool})
  endforeach()
endmacro()
