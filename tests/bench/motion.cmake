# Motion-core benchmark: 100,000 moves through the tmc4361, tmc429 and tmc5160 cores' API, and two homing
# programs (switch, stall) on the tmc429 core for one simulated hour (docs/performance.md).
tmcl_add_bench(motion_bench ${CMAKE_CURRENT_SOURCE_DIR}/motion_bench.cpp)
