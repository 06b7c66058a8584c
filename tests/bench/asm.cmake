# Assembler throughput and process-start benchmarks (tests/bench/asm_bench.cpp).
tmcl_add_bench(asm_bench ${CMAKE_CURRENT_SOURCE_DIR}/asm_bench.cpp)
target_compile_definitions(asm_bench PRIVATE TMCL_TMCLASM_PATH="$<TARGET_FILE:tmclasm>")
add_dependencies(asm_bench tmclasm)
