" Vim syntax for TMCL test files, *.tmctest (docs/testing.md): the kinds of lines, the words of
" expectations and scenario lines, instants and numbers, '#' comments.
scriptencoding utf-8
if exists('b:current_syntax')
  finish
endif
syntax match tmcltestDirective /^\s*\(program\|target\|motion\|instr-time\|max-time\|define\|skip\|at\|switch\|hardstop\|load\|expect\)\>/
syntax keyword tmcltestWord at end never fault no warnings notes halted stop max-time blocked stall
syntax keyword tmcltestWord input analog left right home slip load from to
syntax keyword tmcltestValue acc a x pc sp flags errors time steps v ap gp in ain out position velocity
syntax match tmcltestNumber /\<\d\+\(\.\d\+\)\=\(us\|ms\|s\|min\|h\)\=\>/
syntax match tmcltestNumber /\<0x\x\+\>\|\<0b[01]\+\>/
" $acc, $pc ...: registers as the debugger writes them ($FF is no number here: 0xFF is).
syntax match tmcltestValue /\$\(acc\|a\|x\|pc\|sp\|flags\|errors\|time\|steps\)\>/
syntax match tmcltestOperator /[=!<>]=\=\|±\|+\/-/
syntax match tmcltestComment /#.*$/
highlight default link tmcltestDirective Statement
highlight default link tmcltestWord Keyword
highlight default link tmcltestValue Identifier
highlight default link tmcltestNumber Number
highlight default link tmcltestOperator Operator
highlight default link tmcltestComment Comment
let b:current_syntax = 'tmcltest'
