# Language server benchmark (tests/bench/lsp_bench.cpp): diagnostics after a one-character edit in a
# 10,000-line file, and hover and completion answers, through tmcl::lsp::Server as a client sees it.
tmcl_add_bench(lsp_bench ${CMAKE_CURRENT_SOURCE_DIR}/lsp_bench.cpp)
target_link_libraries(lsp_bench PRIVATE tmcl_lsp)
