// The source formatter (tmclasm --format, the language server's formatting request) and the
// token view of a source that editor tools share. Both run on the assembler's own lexer, so a
// token here is exactly what the assembler reads; comments are kept as tokens too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/asm/diag.hpp"

namespace tmcl {

struct SourceToken {
  enum class Kind : std::uint8_t { Name, Number, Punct, Directive, IncludeName, Comment, Newline, Bad };
  Kind kind;
  std::string_view text;  // points into the text given to tokenize()
  std::size_t offset;     // byte offset of text in it
  int line;               // 1-based
  int col;                // 1-based byte column
  std::int64_t number = 0;  // a Number's value as the lexer read it (any base); 0 otherwise
};

// Every token of `text` in source order, comments included, each line ended by a Newline token.
// Lexical errors (bad characters and numbers, unterminated comments) go to `diags` when given.
std::vector<SourceToken> tokenize(std::string_view text, Diagnostics* diags = nullptr);

// How far the canonical layout indents an instruction (and anything an editor inserts as one).
inline constexpr int kFormatIndent = 2;

struct FormatResult {
  bool ok = false;
  std::string text;   // the formatted source (ok)
  std::string error;  // why not ("3:5: unexpected character '@'"), when not ok
};

// The canonical layout: labels alone at column 0, instructions indented two spaces with
// "MNEMONIC A, B, C" (mnemonics upper case, names as spelt), constants "Name = expr" and
// directives at column 0, binary operators spaced, trailing comments of a blank-line group
// aligned one column apart, full-line comments kept (indented when they were), runs of blank lines
// as one, LF line ends and one final newline. Every token and comment is kept, so the assembled
// bytes never change; formatting formatted text gives it back unchanged. A source the lexer
// rejects is not formatted.
FormatResult format_source(std::string_view text);

}  // namespace tmcl
