# standalone_grep: check_standalone.cmake's grep on a tree made to fail. Every path that leaves
# the tree is reported with its file and line, and the line as it is, even after lines that hold
# `;`, `[` or `]` (list syntax in CMake, which once split and joined lines and shifted the numbers).
# Run as: cmake -DWORK=<scratch dir> -P check_grep.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)
set(dotdot "..")  # spelled so that the real grep does not match this file
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/tests")
file(WRITE "${WORK}/tests/t.cpp" "int a; int b;\nint c[2];  // [\n]\nauto p = \"${dotdot}/shared/y\";\n")
file(WRITE "${WORK}/CMakeLists.txt" "set(x \${PROJECT_SOURCE_DIR}/${dotdot}/z)\n")
file(WRITE "${WORK}/tests/ok.sh" "echo fine\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DROOT=${WORK} -DGREP_ONLY=ON -P ${CMAKE_CURRENT_LIST_DIR}/check_standalone.cmake
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
string(REGEX REPLACE "\n +" " " err "${err}")  # CMake wraps long messages
if(rc EQUAL 0)
  problem("the grep passed a tree with paths that leave it")
endif()
foreach(want "tests/t.cpp:4: reaches outside the tree (`${dotdot}/shared`): auto p = \"${dotdot}/shared/y\";"
             "CMakeLists.txt:1: reaches outside the tree (`PROJECT_SOURCE_DIR}/${dotdot}`): set(x \${PROJECT_SOURCE_DIR}/${dotdot}/z)"
             "grep: 2 problem(s)")
  string(FIND "${err}" "${want}" at)
  if(at EQUAL -1)
    problem("no '${want}' in:\n${err}")
  endif()
endforeach()
if(err MATCHES "ok.sh")
  problem("a file with no such path was reported:\n${err}")
endif()
file(REMOVE_RECURSE "${WORK}")
tmcl_check_done("standalone's grep")
