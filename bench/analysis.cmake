# The control-flow analysis against the assembly alone (bench/analysis_bench.cpp, issue 13).
tmcl_add_bench(analysis_bench ${CMAKE_CURRENT_SOURCE_DIR}/analysis_bench.cpp)
target_link_libraries(analysis_bench PRIVATE tmcl_analysis)
