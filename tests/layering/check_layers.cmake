# Fails when a library includes a header of a library above it (docs/architecture.md), or when
# the top level holds a folder or file the project's design does not name.
# Run as: cmake -DROOT=<source dir> -P check_layers.cmake  (-DTOP_ONLY=ON: the top level alone)
#
# The top level is the one the design fixes: these folders and files, README and LICENSE files
# and dot-files beside them. A build folder inside the tree (it holds a CMakeCache.txt) is no part
# of the project and is passed over; anything else is a folder to move where its job belongs.
set(TOP_ALLOWED CMakeLists.txt asm vm include_files cli tests examples docs)
set(failures 0)
file(GLOB top_entries RELATIVE "${ROOT}" "${ROOT}/*")
foreach(entry IN LISTS top_entries)
  if(entry MATCHES "^\\." OR entry MATCHES "^(README|LICENSE)" OR EXISTS "${ROOT}/${entry}/CMakeCache.txt")
    continue()
  endif()
  list(FIND TOP_ALLOWED "${entry}" at)
  if(at EQUAL -1)
    message(SEND_ERROR "top level: '${entry}' is not one of ${TOP_ALLOWED} (README, LICENSE and dot-files aside); move it into the folder whose job it serves (docs/architecture.md)")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
if(TOP_ONLY)
  if(failures GREATER 0)
    message(FATAL_ERROR "${failures} entr(ies) at the top level the design does not name")
  endif()
  message(STATUS "top level: as the design fixes it")
  return()
endif()

# Each library is a folder; the table says which libraries each may reach (itself included).
# A header belongs to the library whose include/ folder holds it. A new library adds a row here.
set(LAYERS
  "base|vm/base|base"
  "isa|vm/isa|isa,base"
  "motion|vm/motion|motion,isa,base"
  "vm|vm|vm,motion,isa,base"
  "module|vm/module|module,vm,motion,isa,base"
  "asm|asm|asm,isa,base"
  "analysis|asm/analysis|analysis,asm,isa,base"
  "debug|cli/debug|debug,module,host,vm,asm,motion,isa,base"
  "testrun|cli/testrun|testrun,analysis,vm,asm,motion,isa,base"
  "lsp|cli/lsp|lsp,testrun,analysis,vm,motion,asm,isa,base"
  "report|cli/report|report,vm,motion,isa,base"
  "host|cli/host|host,asm,isa,base"
)

# The top-level folders are layers too, in this order (vm/ lowest): a row may let its library reach
# libraries of its own top-level folder and of those below it, never of one above
# (docs/architecture.md). So `asm/` never uses the machine of `vm/` above `vm/isa` through a row,
# and nothing in `vm/` uses the assembler.
set(TOP_LEVELS vm asm cli)
foreach(row IN LISTS LAYERS)
  string(REPLACE "|" ";" parts "${row}")
  list(GET parts 0 lib)
  list(GET parts 1 dir)
  string(REGEX REPLACE "/.*" "" top "${dir}")
  list(FIND TOP_LEVELS "${top}" rank)
  if(rank EQUAL -1)
    message(SEND_ERROR "layer '${lib}': ${dir} is in no top-level folder of TOP_LEVELS (${TOP_LEVELS})")
    math(EXPR failures "${failures} + 1")
  endif()
  set(top_of_${lib} "${top}")
  set(rank_of_${lib} ${rank})
endforeach()
foreach(row IN LISTS LAYERS)
  string(REPLACE "|" ";" parts "${row}")
  list(GET parts 0 lib)
  list(GET parts 2 allowed)
  string(REPLACE "," ";" allowed "${allowed}")
  foreach(other IN LISTS allowed)
    if(NOT DEFINED rank_of_${other})
      message(SEND_ERROR "layer '${lib}': may use '${other}', which the table does not have")
      math(EXPR failures "${failures} + 1")
    elseif(rank_of_${other} GREATER rank_of_${lib})
      message(SEND_ERROR "layer '${lib}' (${top_of_${lib}}/) may use '${other}' of ${top_of_${other}}/, a top-level folder above its own")
      math(EXPR failures "${failures} + 1")
    endif()
  endforeach()
endforeach()

# Which library owns each public header.
set(owners "")
foreach(row IN LISTS LAYERS)
  string(REPLACE "|" ";" parts "${row}")
  list(GET parts 0 lib)
  list(GET parts 1 dir)
  file(GLOB_RECURSE headers RELATIVE "${ROOT}/${dir}/include" "${ROOT}/${dir}/include/tmcl/*")
  foreach(h IN LISTS headers)
    set(owner_${h} ${lib})
  endforeach()
endforeach()

# ... and the generated ones (made in the build folder from a template in the library's folder).
set(owner_tmcl/version.hpp base)  # vm/base/version.hpp.in

# Which library a source file belongs to: the longest folder of the table that holds it.
foreach(row IN LISTS LAYERS)
  string(REPLACE "|" ";" parts "${row}")
  list(GET parts 0 lib)
  list(GET parts 1 dir)
  list(GET parts 2 allowed)
  list(GET parts 2 allowed)
  string(REPLACE "," ";" allowed "${allowed}")
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.cpp" "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.def")
  if(NOT files)
    message(SEND_ERROR "layer '${lib}': no sources under ${dir}")
    math(EXPR failures "${failures} + 1")
  endif()
  foreach(f IN LISTS files)
    # A file in a deeper library folder is that library's, not this one's.
    set(mine TRUE)
    foreach(other IN LISTS LAYERS)
      string(REPLACE "|" ";" o "${other}")
      list(GET o 1 odir)
      string(LENGTH "${dir}" dlen)
      string(LENGTH "${odir}" olen)
      if(olen GREATER dlen AND f MATCHES "^${ROOT}/${odir}/")
        set(mine FALSE)
      endif()
    endforeach()
    if(NOT mine)
      continue()
    endif()
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<]tmcl/")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[\"<](tmcl/[^\">]+)[\">].*$" "\\1" h "${line}")
      if(NOT DEFINED owner_${h})
        message(SEND_ERROR "${f}: includes ${h}, which no library of the table owns")
        math(EXPR failures "${failures} + 1")
      else()
        list(FIND allowed "${owner_${h}}" at)
        if(at EQUAL -1)
          message(SEND_ERROR "${f}: layer '${lib}' includes ${h} of layer '${owner_${h}}', which is above it")
          math(EXPR failures "${failures} + 1")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} layering violation(s)")
endif()
message(STATUS "layering: every include runs downwards")
