# The control-flow analysis against the assembly alone, in process and as whole tmclasm
# processes (tests/bench/analysis_bench.cpp, issue 13).
tmcl_add_bench(analysis_bench ${CMAKE_CURRENT_SOURCE_DIR}/analysis_bench.cpp)
target_link_libraries(analysis_bench PRIVATE tmcl_analysis)
target_compile_definitions(analysis_bench PRIVATE TMCL_TMCLASM_PATH="$<TARGET_FILE:tmclasm>")
add_dependencies(analysis_bench tmclasm)
