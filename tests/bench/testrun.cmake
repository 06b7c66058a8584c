# Test runner benchmarks (tests/bench/testrun_bench.cpp): 1,000 test files with -j 1 and -j 2 against
# 1,000 plain tmclrun runs, and the cost of --coverage.
tmcl_add_bench(testrun_bench ${CMAKE_CURRENT_SOURCE_DIR}/testrun_bench.cpp)
target_compile_definitions(testrun_bench PRIVATE TMCL_TMCLRUN_PATH="$<TARGET_FILE:tmclrun>")
add_dependencies(testrun_bench tmclrun)
