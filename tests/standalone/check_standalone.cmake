# The tree stands alone: nothing in its build, tests, benchmarks or CI reads outside it.
# Run as: cmake -DROOT=<source dir> [-DWORK=<scratch dir>] [-DGENERATOR=<generator>] [-DGREP_ONLY=ON]
#            -P check_standalone.cmake
#
# 1. Greps the CMake files, scripts and sources for paths that leave the tree: the parent's `shared` folder,
#    `${PROJECT_SOURCE_DIR}/..`, `${CMAKE_SOURCE_DIR}/..` and the absolute `/work/shared`.
# 2. Copies the tree (without build*/ and .git) into a fresh folder under WORK that has nothing
#    beside it, configures it, checks that the generated build names no file of the original
#    tree, and builds one small target (tmcl_base) from the copy.
#    Configuring plus one library keeps this a few seconds (docs/performance.md, "Build time");
#    the whole suite from a copy is what .ci/run does.
cmake_minimum_required(VERSION 3.25)
if(NOT DEFINED ROOT)
  message(FATAL_ERROR "check_standalone.cmake needs -DROOT=<source dir>")
endif()
# The scratch folder is the system's temporary folder, far from the tree and whatever is beside it.
if(NOT WORK)
  set(WORK "$ENV{TMPDIR}")
  if(NOT WORK)
    set(WORK /tmp)
  endif()
endif()
get_filename_component(ROOT "${ROOT}" REALPATH)
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)

# ---- 1. grep ---------------------------------------------------------------------------------
# Top-level entries of the tree, without build folders and .git (never walked: they are big).
file(GLOB top LIST_DIRECTORIES true RELATIVE "${ROOT}" "${ROOT}/*" "${ROOT}/.ci")
list(FILTER top EXCLUDE REGEX "^(build.*|\\.git)$")
set(candidates "")
foreach(entry IN LISTS top)
  if(IS_DIRECTORY "${ROOT}/${entry}")
    file(GLOB_RECURSE found LIST_DIRECTORIES false RELATIVE "${ROOT}"
      "${ROOT}/${entry}/*CMakeLists.txt" "${ROOT}/${entry}/*.cmake" "${ROOT}/${entry}/*.in"
      "${ROOT}/${entry}/*.sh" "${ROOT}/${entry}/*.py" "${ROOT}/${entry}/*.cpp" "${ROOT}/${entry}/*.hpp"
      "${ROOT}/${entry}/*.h" "${ROOT}/${entry}/*.def" "${ROOT}/${entry}/*.run")
    list(APPEND candidates ${found})
  elseif(entry STREQUAL "CMakeLists.txt")
    list(APPEND candidates ${entry})
  endif()
endforeach()
list(APPEND candidates .ci/run)
list(REMOVE_DUPLICATES candidates)
# The patterns, spelled so that this file does not match itself.
set(dotdot "..")
# (`/work/shared` is where this project's reading material lives; other absolute paths, such as a
# test's made-up file:// URI, are not reads of the disk.)
set(patterns "${dotdot}/shared" "PROJECT_SOURCE_DIR}/${dotdot}" "CMAKE_SOURCE_DIR}/${dotdot}" "/work/shared")
# The same as one regular expression: file(STRINGS ... REGEX) looks through a file far faster than
# a loop over its lines, which only a file with a match needs (for the line numbers).
set(any_pattern "")
foreach(p IN LISTS patterns)
  string(REPLACE "." "\\." quoted "${p}")  # the only special character they hold
  list(APPEND any_pattern "${quoted}")
endforeach()
list(JOIN any_pattern "|" any_pattern)
string(ASCII 1 "stand_in_;")
string(ASCII 2 "stand_in_[")
string(ASCII 3 "stand_in_]")
foreach(rel IN LISTS candidates)
  if(rel STREQUAL "tests/standalone/check_standalone.cmake" OR NOT EXISTS "${ROOT}/${rel}")
    continue()
  endif()
  file(STRINGS "${ROOT}/${rel}" hits REGEX "${any_pattern}")
  if(NOT hits)
    continue()
  endif()
  # The file as a list of its lines, to number them. `;`, `[` and `]` are list syntax (a `;` splits
  # a line, a bracket joins lines), so they stand in as bytes no source holds while it is a list.
  file(READ "${ROOT}/${rel}" text)
  foreach(ch IN ITEMS ";" "[" "]")
    string(REPLACE "${ch}" "${stand_in_${ch}}" text "${text}")
  endforeach()
  string(REPLACE "\n" ";" lines "${text}")
  set(n 0)
  foreach(line IN LISTS lines)
    math(EXPR n "${n} + 1")
    foreach(p IN LISTS patterns)
      string(FIND "${line}" "${p}" at)
      if(at GREATER -1)
        foreach(ch IN ITEMS ";" "[" "]")
          string(REPLACE "${stand_in_${ch}}" "${ch}" line "${line}")
        endforeach()
        problem("${rel}:${n}: reaches outside the tree (`${p}`): ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()
list(LENGTH candidates scanned)
message(STATUS "grep: ${scanned} files scanned, ${failures} paths leaving the tree")
if(GREP_ONLY)  # standalone_grep: the grep alone, on a tree made to fail
  tmcl_check_done("grep")
  return()
endif()

# ---- 2. a copy with nothing beside it ------------------------------------------------------
string(RANDOM LENGTH 8 tag)
set(box "${WORK}/standalone-${tag}")
set(copy "${box}/tmcl")
file(REMOVE_RECURSE "${box}")
file(MAKE_DIRECTORY "${copy}")
foreach(entry IN LISTS top)
  file(COPY "${ROOT}/${entry}" DESTINATION "${copy}")
endforeach()

string(TIMESTAMP t0 "%s")
set(gen_args "")
if(GENERATOR)
  set(gen_args -G "${GENERATOR}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${copy}" -B "${copy}/build" ${gen_args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  problem("configuring a copy of the tree in ${copy} failed (${rc}):\n${out}\n${err}")
else()
  # The generated build must name no file of the original tree (a path that escaped the copy).
  file(GLOB_RECURSE generated "${copy}/build/*.ninja" "${copy}/build/*Makefile*" "${copy}/build/*.make"
       "${copy}/build/*CTestTestfile.cmake")
  foreach(g IN LISTS generated)
    file(STRINGS "${g}" lines)
    foreach(line IN LISTS lines)
      string(FIND "${line}" "${ROOT}/" original)
      string(FIND "${line}" "${dotdot}/shared" shared)
      if(original GREATER -1 OR shared GREATER -1)
        problem("${g}: the copy's build names a file outside it: ${line}")
        break()
      endif()
    endforeach()
  endforeach()
  string(TIMESTAMP t1 "%s")
  math(EXPR secs "${t1} - ${t0}")
  message(STATUS "copy and configure: ${secs} s")
  execute_process(COMMAND ${CMAKE_COMMAND} --build "${copy}/build" --parallel 2 --target tmcl_base
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    problem("building tmcl_base in the copy ${copy} failed (${rc}):\n${out}\n${err}")
  endif()
  string(TIMESTAMP t2 "%s")
  math(EXPR secs "${t2} - ${t1}")
  message(STATUS "build tmcl_base: ${secs} s")
endif()

if(failures EQUAL 0)
  file(REMOVE_RECURSE "${box}")
endif()
tmcl_check_done("standalone (the copy is kept in ${copy})")
message(STATUS "standalone: the tree configures and builds from ${copy} with nothing beside it")
