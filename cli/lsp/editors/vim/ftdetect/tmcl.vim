" TMCL sources: .tmc programs and .inc include files; and test files, .tmctest (filetype
" tmcltest; docs/testing.md) (tmcl cli/lsp/editors/vim, docs/editors.md).
autocmd BufRead,BufNewFile *.tmc setfiletype tmcl
autocmd BufRead,BufNewFile *.inc if getline(1) =~? '^\s*\(//\|;\|#include\|[A-Za-z_][A-Za-z0-9_]*\s*=\)' | setfiletype tmcl | endif
autocmd BufRead,BufNewFile *.tmctest setfiletype tmcltest
