# Motion-core benchmark: 100,000 S-shaped moves through the tmc4361 core's API (docs/performance.md).
# Registered like tmcl_add_bench does, but linked against the VM library only (no assembler needed).
add_executable(motion_bench EXCLUDE_FROM_ALL motion_bench.cpp)
target_link_libraries(motion_bench PRIVATE tmcl_vm tmcl_flags)
set(TMCL_BENCHES ${TMCL_BENCHES} motion_bench CACHE INTERNAL "")
