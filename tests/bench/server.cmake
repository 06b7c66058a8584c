# Virtual-module benchmark (tests/bench/server_bench.cpp): request/reply round trips over loopback TCP.
find_package(Threads REQUIRED)
tmcl_add_bench(server_bench ${CMAKE_CURRENT_SOURCE_DIR}/server_bench.cpp)
target_link_libraries(server_bench PRIVATE tmcl_vm Threads::Threads)
