// The DSL's tokens (grammar/efc.ebnf, "lexical"). The lexer never fails: a
// bad character, string or number becomes an Error token carrying its
// message, so the parser reports it where it stands and goes on.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace efc::dsl {

enum class Tok {
  Ident,      // names, keywords, enum words, units: letter { letter | digit }
  Extension,  // x-... keys
  Number,     // JSON number syntax; text kept, value parsed by the parser
  String,     // "..." with JSON escapes; `text` holds the decoded value
  LBrace, RBrace, LParen, RParen, LBracket, RBracket,
  Comma, Semicolon, Colon, Arrow, DotDot, Slash,
  Error,      // `text` holds the message
  End,
};

struct Token {
  Tok kind = Tok::End;
  std::string text;
  int line = 1, col = 1;        // 1-based; columns count code points
  size_t offset = 0, end = 0;   // byte range in the source
  bool first_on_line = false;   // nothing but blanks and comments before it on its line
};

// A `#` comment, kept so `efc fmt` can put it back.
struct Comment {
  int line = 1;
  std::string text;       // after the '#', trailing blanks removed
  bool own_line = false;  // nothing but blanks before it on its line
};

// Splits the text into tokens, the last one End. A UTF-8 byte order mark is
// skipped. The text must be valid UTF-8 (the caller checks). Comments go to
// *comments when it is given.
std::vector<Token> tokenize(std::string_view text, std::vector<Comment>* comments = nullptr);

// A readable name for a token in messages: "'{'", "number 3", "end of file".
std::string describe(const Token& t);

}  // namespace efc::dsl
