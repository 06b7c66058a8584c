# Virtual-machine benchmarks (tests/bench/vm_bench.cpp): dispatch speed and waiting speed.
tmcl_add_bench(vm_bench ${CMAKE_CURRENT_SOURCE_DIR}/vm_bench.cpp)
