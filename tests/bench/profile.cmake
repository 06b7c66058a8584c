# Module profile benchmarks (tests/bench/profile_bench.cpp): tmclasm with a bundled TMCM profile against
# generic, and loading a user's profile file.
tmcl_add_bench(profile_bench ${CMAKE_CURRENT_SOURCE_DIR}/profile_bench.cpp)
target_compile_definitions(profile_bench PRIVATE TMCL_TMCLASM_PATH="$<TARGET_FILE:tmclasm>")
add_dependencies(profile_bench tmclasm)
