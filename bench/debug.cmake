# Debugger benchmarks (bench/debug_bench.cpp): the cost of breakpoints and a watchpoint that are
# set but not hit, and the answer time of reverse-step after 10^9 instructions.
tmcl_add_bench(debug_bench ${CMAKE_CURRENT_SOURCE_DIR}/debug_bench.cpp)
target_link_libraries(debug_bench PRIVATE tmcl_debug)
