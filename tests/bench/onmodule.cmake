# Debugging on a module (tests/bench/onmodule_bench.cpp, issue 39): round trips per step, breakpoint hit
# and print, steps per second and hit-to-report time against tmclrun --serve tcp.
tmcl_add_bench(onmodule_bench ${CMAKE_CURRENT_SOURCE_DIR}/onmodule_bench.cpp)
target_link_libraries(onmodule_bench PRIVATE tmcl_host)
target_compile_definitions(onmodule_bench PRIVATE TMCL_TMCLRUN="$<TARGET_FILE:tmclrun>")
add_dependencies(onmodule_bench tmclrun)
