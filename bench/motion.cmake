# Motion-core benchmark: 100,000 S-shaped moves through the tmc4361 core's API (docs/performance.md).
tmcl_add_bench(motion_bench ${CMAKE_CURRENT_SOURCE_DIR}/motion_bench.cpp)
