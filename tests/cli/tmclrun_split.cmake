# tmclrun and tmclrun-full (cli/tmclrun_modes.hpp): tmclrun runs programs with no tmclrun-full beside
# it; it hands serving and debugging to tmclrun-full, looked for in the installed place
# (../libexec/tmcl/ from its folder) and beside it; and without tmclrun-full it says so by name,
# exit 71, as JSON too with --json. The install and package tests run it from an installed tree.
# Run as: cmake -DTMCLRUN=... -DTMCLRUN_FULL=... -DSRC=<source dir> -DWORK=<scratch dir> -P tmclrun_split.cmake
include(${CMAKE_CURRENT_LIST_DIR}/../unit/checks.cmake)

file(REMOVE_RECURSE "${WORK}")
set(alone "${WORK}/alone")
file(MAKE_DIRECTORY "${alone}")
file(COPY "${TMCLRUN}" DESTINATION "${alone}")
set(prog "${SRC}/examples/quickstart.tmc")

# Alone, tmclrun still runs a program.
execute_process(COMMAND "${alone}/tmclrun" -t usb-2-sd "${prog}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect("tmclrun alone runs a program: exit status" 0 "${rc}")
expect_match("tmclrun alone runs a program" "motor 0: position 1000" "${out}")

# Serving or debugging: the missing program is named, with where it was looked for.
foreach(args "--serve;pty" "--dap" "--debug=1;${prog}")
  execute_process(COMMAND "${alone}/tmclrun" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  list(GET args 0 first)
  string(REGEX REPLACE "=.*" "" first "${first}")
  expect("tmclrun ${args} without tmclrun-full: exit status" 71 "${rc}")
  expect("tmclrun ${args} without tmclrun-full: standard output" "" "${out}")
  expect_match("tmclrun ${args} without tmclrun-full"
    "^tmclrun: '${first}' is not an option of tmclrun itself, and tmclrun-full, which serves and debugs, is missing \\(tried ${alone}/../libexec/tmcl/tmclrun-full \\(No such file or directory\\), ${alone}/tmclrun-full \\(No such file or directory\\)\\)\n"
    "${err}")
endforeach()
execute_process(COMMAND "${alone}/tmclrun" --json --serve pty RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_QUIET)
expect("tmclrun --json --serve pty without tmclrun-full: exit status" 71 "${rc}")
expect_match("tmclrun --json --serve pty without tmclrun-full" "^{\"error\":\"usage\",\n \"exit\":71,\n \"message\":\"'--serve' is not an option of tmclrun itself" "${out}")

# Beside it (the build tree's layout), then in the installed layout: tmclrun-full parses the
# whole command line, so its own errors come back, and a truly unknown option is named as such.
file(COPY "${TMCLRUN_FULL}" DESTINATION "${alone}")
file(MAKE_DIRECTORY "${WORK}/prefix/bin" "${WORK}/prefix/libexec/tmcl")
file(COPY "${TMCLRUN}" DESTINATION "${WORK}/prefix/bin")
file(COPY "${TMCLRUN_FULL}" DESTINATION "${WORK}/prefix/libexec/tmcl")
foreach(dir "${alone}" "${WORK}/prefix/bin")
  execute_process(COMMAND "${dir}/tmclrun" --serve bogus RESULT_VARIABLE rc ERROR_VARIABLE err)
  expect("${dir}/tmclrun --serve bogus: exit status" 64 "${rc}")
  expect_match("${dir}/tmclrun --serve bogus" "^tmclrun: --serve takes tcp:HOST:PORT, pty or stdio, not 'bogus'\n" "${err}")
  execute_process(COMMAND "${dir}/tmclrun" --frobnicate "${prog}" RESULT_VARIABLE rc ERROR_VARIABLE err)
  expect("${dir}/tmclrun --frobnicate: exit status" 64 "${rc}")
  expect_match("${dir}/tmclrun --frobnicate" "^tmclrun: unknown option '--frobnicate'\n" "${err}")
  # A whole debugging session through tmclrun: the same transcript as tmclrun-full's own.
  execute_process(COMMAND "${dir}/tmclrun" -t usb-2-sd --debug "${prog}" INPUT_FILE "${SRC}/tests/cli/tmclrun_split.gdb"
    RESULT_VARIABLE rc OUTPUT_VARIABLE via ERROR_VARIABLE err)
  expect("${dir}/tmclrun --debug: exit status" 0 "${rc}")
  execute_process(COMMAND "${TMCLRUN_FULL}" -t usb-2-sd --debug "${prog}" INPUT_FILE "${SRC}/tests/cli/tmclrun_split.gdb"
    OUTPUT_VARIABLE direct ERROR_QUIET)
  expect("${dir}/tmclrun --debug, the transcript" "${direct}" "${via}")
  expect_match("${dir}/tmclrun --debug, the transcript" "Breakpoint 1" "${via}")
endforeach()

if(failures EQUAL 0)
  file(REMOVE_RECURSE "${WORK}")
endif()
tmcl_check_done("tmclrun_split (files kept in ${WORK})")
