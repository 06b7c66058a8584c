# tmclctl transfer benchmark (tests/bench/host_bench.cpp): download+verify over a pty vs bare round trips.
tmcl_add_bench(host_bench ${CMAKE_CURRENT_SOURCE_DIR}/host_bench.cpp)
target_link_libraries(host_bench PRIVATE tmcl_host)
target_compile_definitions(host_bench PRIVATE TMCL_TMCLRUN="$<TARGET_FILE:tmclrun>")
add_dependencies(host_bench tmclrun)
