# doc_paths: every file of the repository that README.md or docs/*.md names by its path from the
# top (`vm/motion/ramp.hpp`, asm/fast_path.cpp, tests/golden/run/summary.tmc) exists, so a file
# that moves cannot leave the documentation pointing at nothing (issue 28: docs/profiles.md and
# docs/motion.md did). Names with a placeholder (cli/NAME.cpp, docs/man/TOOL.1) and paths
# without an extension (golden case names, build targets, folders) are not checked.
# Run as: cmake -DROOT=<source dir> -P check_doc_paths.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)
file(GLOB docs "${ROOT}/docs/*.md")
list(APPEND docs "${ROOT}/README.md")
set(top "(asm|vm|cli|tests|include_files|examples|docs|\\.ci)")
set(checked 0)
foreach(doc IN LISTS docs)
  file(READ "${doc}" text)
  # `[`, `]` and `;` are list syntax to CMake: a match holding one would split or join wrongly.
  string(REGEX REPLACE "[][;]" " " text "${text}")
  # A path starts the text or follows a character that cannot be part of one.
  string(REGEX MATCHALL "(^|[^A-Za-z0-9_./~-])${top}/[A-Za-z0-9_./-]*[A-Za-z0-9_]" found "${text}")
  file(RELATIVE_PATH name "${ROOT}" "${doc}")
  foreach(match IN LISTS found)
    string(REGEX REPLACE "^[^A-Za-z0-9_.]" "" path "${match}")
    if(NOT path MATCHES "\\.(hpp|cpp|h|def|cmake|sh|md|profile|tmc|inc|lua|json|txt|py|golden|run|1)$" OR
       path MATCHES "(^|/)[^/]*(NAME|TOOL)")
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    if(NOT EXISTS "${ROOT}/${path}")
      problem("${name} names ${path}, which is not in the repository")
    endif()
  endforeach()
endforeach()
if(checked LESS 100)
  problem("only ${checked} paths found in the documentation: the pattern no longer matches how it names files")
endif()
message(STATUS "${checked} paths named by README.md and docs/*.md")
tmcl_check_done("paths in the documentation")
