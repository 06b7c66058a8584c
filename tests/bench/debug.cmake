# Debugger benchmarks (tests/bench/debug_bench.cpp): the cost of breakpoints and a watchpoint that are
# set but not hit, and the answer time of reverse-step after 10^9 instructions.
tmcl_add_bench(debug_bench ${CMAKE_CURRENT_SOURCE_DIR}/debug_bench.cpp)
target_link_libraries(debug_bench PRIVATE tmcl_debug)
# (4) compares whole tmclrun processes: a plain run and the same run under --debug.
target_compile_definitions(debug_bench PRIVATE TMCL_TMCLRUN_PATH="$<TARGET_FILE:tmclrun>")
add_dependencies(debug_bench tmclrun)
