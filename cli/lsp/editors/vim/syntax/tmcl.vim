" Vim syntax for TMCL sources (docs/language.md): mnemonics and keywords of opcodes.def and
" keywords.def, labels, constants, directives, numbers in every base, three comment styles.
if exists('b:current_syntax')
  finish
endif
syntax case ignore
syntax keyword tmclMnemonic ROR ROL MST MVP SAP GAP STAP RSAP SGP GGP STGP RSGP RFS SIO GIO SAPX GAPX AAPX CALC COMP JC JA CSUB RSUB EI DI WAIT STOP SCO GCO CCO CALCX AAP AGP CLE VECT RETI ACO CALCVV CALCVA CALCAV CALCVX CALCXV CALCV MVPA MVPXA RST DJNZ ROLA RORA ROLXA RORXA MSTX SIV GIV AIV PUSHA PUSHX PUSHV POPA POPX POPV CALL UF0 UF1 UF2 UF3 UF4 UF5 UF6 UF7
syntax match tmclMnemonic /\.raw\>/
syntax keyword tmclKeyword ABS REL COORD ADD SUB MUL DIV MOD AND OR XOR NOT LOAD SWAP ZE NZ EQ NE GT GE LT LE ETO EAL EDV EPO ESD ALL TICKS POS REFSW LIMSW START STATUS
syntax match tmclDirective /#\(include\|export\|import\|no_append_stop\)\>/
syntax match tmclLabel /^\s*\h\w*\s*:/
syntax match tmclConstant /^\s*\h\w*\ze\s*=/
syntax match tmclNumber /\<\d\+\>/
syntax match tmclNumber /\<0x\x\+\>\|\$\x\+\>/
syntax match tmclNumber /\<0b[01]\+\>/
syntax case match
syntax match tmclComment /\/\/.*$/
syntax match tmclComment /;.*$/
syntax region tmclComment start=/\/\*/ end=/\*\//
highlight default link tmclMnemonic Statement
highlight default link tmclKeyword Constant
highlight default link tmclDirective PreProc
highlight default link tmclLabel Label
highlight default link tmclConstant Identifier
highlight default link tmclNumber Number
highlight default link tmclComment Comment
let b:current_syntax = 'tmcl'
