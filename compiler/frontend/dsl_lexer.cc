#include "compiler/frontend/dsl_lexer.h"

#include "compiler/frontend/dsl_syntax.h"

#include <cstdint>

namespace efc::dsl {
namespace {


class Lexer {
 public:
  Lexer(std::string_view text, std::vector<Comment>* comments) : s_(text), comments_(comments) {
    if (s_.substr(0, 3) == "\xEF\xBB\xBF") off_ = 3;
  }

  std::vector<Token> run() {
    std::vector<Token> out;
    bool line_start = true;
    for (;;) {
      // Blanks and comments; a newline makes the next token first on its line.
      while (off_ < s_.size()) {
        char c = s_[off_];
        if (c == '\n') {
          line_start = true;
          step();
        } else if (c == ' ' || c == '\t' || c == '\r') {
          step();
        } else if (c == '#') {
          Comment comment;
          comment.line = line_;
          comment.own_line = line_start;
          step();
          while (off_ < s_.size() && s_[off_] != '\n') {
            comment.text += s_[off_];
            step();
          }
          while (!comment.text.empty() &&
                 (comment.text.back() == ' ' || comment.text.back() == '\t' ||
                  comment.text.back() == '\r'))
            comment.text.pop_back();
          if (comments_) comments_->push_back(std::move(comment));
        } else {
          break;
        }
      }
      Token t;
      t.line = line_;
      t.col = col_;
      t.offset = off_;
      t.first_on_line = line_start;
      line_start = false;
      if (off_ >= s_.size()) {
        t.kind = Tok::End;
        t.end = off_;
        out.push_back(std::move(t));
        return out;
      }
      lex_one(t);
      t.end = off_;
      out.push_back(std::move(t));
    }
  }

 private:
  char peek(size_t ahead = 0) const {
    return off_ + ahead < s_.size() ? s_[off_ + ahead] : '\0';
  }
  void step() {
    unsigned char c = static_cast<unsigned char>(s_[off_++]);
    if (c == '\n') {
      ++line_;
      col_ = 1;
    } else if ((c & 0xC0) != 0x80) {
      ++col_;
    }
  }

  void lex_one(Token& t) {
    const char c = peek();
    auto single = [&](Tok k) {
      t.kind = k;
      t.text = std::string(1, c);
      step();
    };
    switch (c) {
      case '{': return single(Tok::LBrace);
      case '}': return single(Tok::RBrace);
      case '(': return single(Tok::LParen);
      case ')': return single(Tok::RParen);
      case '[': return single(Tok::LBracket);
      case ']': return single(Tok::RBracket);
      case ',': return single(Tok::Comma);
      case ';': return single(Tok::Semicolon);
      case ':': return single(Tok::Colon);
      case '/': return single(Tok::Slash);
      case '"': return lex_string(t);
      default: break;
    }
    if (c == '-' && peek(1) == '>') {
      t.kind = Tok::Arrow;
      t.text = "->";
      step();
      step();
      return;
    }
    if (c == '.' && peek(1) == '.') {
      t.kind = Tok::DotDot;
      t.text = "..";
      step();
      step();
      return;
    }
    if (is_digit(c) || (c == '-' && is_digit(peek(1)))) return lex_number(t);
    // x-... (an extension key) but not `x->` (a part named x, then an arrow).
    if (c == 'x' && peek(1) == '-' && (is_letter(peek(2)) || is_digit(peek(2)))) {
      t.kind = Tok::Extension;
      while (is_letter(peek()) || is_digit(peek()) || peek() == '-' || peek() == '.') {
        if (peek() == '-' && peek(1) == '>') break;
        t.text += peek();
        step();
      }
      return;
    }
    if (is_letter(c)) {
      t.kind = Tok::Ident;
      while (is_letter(peek()) || is_digit(peek())) {
        t.text += peek();
        step();
      }
      return;
    }
    // Anything else: one code point, reported as an unexpected character.
    t.kind = Tok::Error;
    size_t start = off_;
    step();
    while (off_ < s_.size() && (static_cast<unsigned char>(s_[off_]) & 0xC0) == 0x80) step();
    std::string shown(s_.substr(start, off_ - start));
    if (c == '\'')
      t.text = "unexpected character \"'\": strings use double quotes";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      t.text = "unexpected control character";
    else
      t.text = "unexpected character '" + shown + "'";
  }

  // JSON number syntax: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  void lex_number(Token& t) {
    t.kind = Tok::Number;
    size_t start = off_;
    if (peek() == '-') step();
    if (peek() == '0') {
      step();
      if (is_digit(peek())) {
        while (is_digit(peek())) step();
        t.kind = Tok::Error;
        t.text = "numbers may not have leading zeros";
        return;
      }
    } else {
      while (is_digit(peek())) step();
    }
    // "0..4": the dot starts a range, not a fraction.
    if (peek() == '.' && is_digit(peek(1))) {
      step();
      while (is_digit(peek())) step();
    } else if (peek() == '.' && peek(1) != '.') {
      step();
      t.kind = Tok::Error;
      t.text = "a number needs a digit after its decimal point";
      return;
    }
    if (peek() == 'e' || peek() == 'E') {
      step();
      if (peek() == '+' || peek() == '-') step();
      if (!is_digit(peek())) {
        t.kind = Tok::Error;
        t.text = "a number's exponent needs digits";
        return;
      }
      while (is_digit(peek())) step();
    }
    t.text = std::string(s_.substr(start, off_ - start));
  }

  static void append_utf8(std::string& out, uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  bool read_hex4(uint32_t* v) {
    *v = 0;
    for (int i = 0; i < 4; ++i) {
      char h = peek();
      int d = (h >= '0' && h <= '9')   ? h - '0'
              : (h >= 'a' && h <= 'f') ? h - 'a' + 10
              : (h >= 'A' && h <= 'F') ? h - 'A' + 10
                                       : -1;
      if (d < 0) return false;
      *v = *v * 16 + static_cast<uint32_t>(d);
      step();
    }
    return true;
  }

  // JSON strings: no raw control characters (so no raw newline: an unclosed
  // string ends at its line, and the parser goes on with the next).
  void lex_string(Token& t) {
    t.kind = Tok::String;
    step();  // opening quote
    std::string value;
    std::string error;
    for (;;) {
      if (off_ >= s_.size() || peek() == '\n') {
        t.kind = Tok::Error;
        t.text = "unterminated string (a string ends with '\"' on the line it starts)";
        return;
      }
      char c = peek();
      if (c == '"') {
        step();
        break;
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        if (error.empty()) error = "control character in a string (write it as an escape: \\t, \\u0001)";
        step();
        continue;
      }
      if (c != '\\') {
        value += c;
        step();
        continue;
      }
      step();
      char e = peek();
      if (off_ >= s_.size() || e == '\n') continue;  // reported as unterminated
      step();
      switch (e) {
        case '"': value += '"'; break;
        case '\\': value += '\\'; break;
        case '/': value += '/'; break;
        case 'b': value += '\b'; break;
        case 'f': value += '\f'; break;
        case 'n': value += '\n'; break;
        case 'r': value += '\r'; break;
        case 't': value += '\t'; break;
        case 'u': {
          uint32_t cp = 0;
          if (!read_hex4(&cp)) {
            if (error.empty()) error = "\\u needs four hex digits";
            break;
          }
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            uint32_t lo = 0;
            if (peek() == '\\' && peek(1) == 'u') {
              step();
              step();
              if (read_hex4(&lo) && lo >= 0xDC00 && lo <= 0xDFFF) {
                append_utf8(value, 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00));
                break;
              }
            }
            if (error.empty()) error = "unpaired UTF-16 surrogate in a \\u escape";
            break;
          }
          if (cp >= 0xDC00 && cp <= 0xDFFF) {
            if (error.empty()) error = "unpaired UTF-16 surrogate in a \\u escape";
            break;
          }
          append_utf8(value, cp);
          break;
        }
        default:
          if (error.empty()) error = std::string("unknown escape '\\") + e + "' in a string";
      }
    }
    if (!error.empty()) {
      t.kind = Tok::Error;
      t.text = error;
      return;
    }
    t.text = std::move(value);
  }

  std::string_view s_;
  std::vector<Comment>* comments_;
  size_t off_ = 0;
  int line_ = 1, col_ = 1;
};

}  // namespace

std::vector<Token> tokenize(std::string_view text, std::vector<Comment>* comments) {
  return Lexer(text, comments).run();
}

std::string describe(const Token& t) {
  switch (t.kind) {
    case Tok::Ident: return "'" + t.text + "'";
    case Tok::Extension: return "'" + t.text + "'";
    case Tok::Number: return "number " + t.text;
    case Tok::String: return "a string";
    case Tok::End: return "end of file";
    case Tok::Error: return "an invalid token";
    default: return "'" + t.text + "'";
  }
}

}  // namespace efc::dsl
