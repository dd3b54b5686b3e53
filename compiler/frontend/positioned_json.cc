#include "compiler/frontend/positioned_json.h"

#include <algorithm>
#include <vector>

namespace efc::frontend {
namespace {

using nlohmann::json;

// Walks the text byte by byte, tracking 1-based line and column. Columns count
// code points (continuation bytes 10xxxxxx do not advance them), so a name
// with accents does not shift the column an editor shows.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {
    // nlohmann skips a UTF-8 byte order mark; the editor does not show it.
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") off_ = 3;
  }

  // Position of the next token (skipping whitespace, ',' and ':'), then moves
  // past it. Called once per SAX event: every event is exactly one token.
  std::pair<int, int> next_token() {
    skip_separators();
    auto at = pos();
    skip_token();
    return at;
  }
  std::pair<int, int> peek_token() {
    skip_separators();
    return pos();
  }
  std::pair<int, int> pos() const { return {line_, col_}; }
  size_t offset() const { return off_; }
  // Moves forward to `target` (never back).
  void advance_to(size_t target) {
    while (off_ < target && off_ < text_.size()) step();
  }

 private:
  void step() {
    unsigned char c = static_cast<unsigned char>(text_[off_++]);
    if (c == '\n') {
      ++line_;
      col_ = 1;
    } else if ((c & 0xC0) != 0x80) {
      ++col_;
    }
  }
  void skip_separators() {
    while (off_ < text_.size()) {
      char c = text_[off_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == ':')
        step();
      else
        break;
    }
  }
  // Only valid tokens reach here (the SAX parser accepted them).
  void skip_token() {
    if (off_ >= text_.size()) return;
    char c = text_[off_];
    if (c == '{' || c == '}' || c == '[' || c == ']') {
      step();
    } else if (c == '"') {
      step();
      while (off_ < text_.size()) {
        char d = text_[off_];
        step();
        if (d == '\\' && off_ < text_.size())
          step();
        else if (d == '"')
          break;
      }
    } else {  // number or literal
      while (off_ < text_.size()) {
        char d = text_[off_];
        bool part = (d >= '0' && d <= '9') || (d >= 'a' && d <= 'z') || (d >= 'A' && d <= 'Z') ||
                    d == '+' || d == '-' || d == '.';
        if (!part) break;
        step();
      }
    }
  }

  std::string_view text_;
  size_t off_ = 0;
  int line_ = 1, col_ = 1;
};


// nlohmann's message minus its "[json.exception...] parse error at line..: "
// prefix (we print our own position).
// Also drops its "; last read: '...'" part, which quotes lexer internals
// (often more than the bad token) rather than what the user wrote.
std::string clean_message(const std::string& what) {
  std::string m = what;
  auto at = m.find("syntax error");
  if (at == std::string::npos) at = m.find("] "), at = at == std::string::npos ? 0 : at + 2;
  m = m.substr(at);
  auto lr = m.find("; last read: ");
  if (lr != std::string::npos) {
    auto next = m.find("; expected", lr);
    m.erase(lr, next == std::string::npos ? std::string::npos : next - lr);
  }
  return m;
}

// Builds the DOM and the position map from SAX events. Returns false (which
// stops the parser) only on nesting deeper than max_depth.
class Handler {
 public:
  Handler(std::string_view text, const std::string& file, size_t max_depth, Diagnostics& d,
          PositionedJson& out)
      : text_(text), cur_(text), file_(file), max_depth_(max_depth), diags_(d), out_(out) {}

  bool null() { return value(json(nullptr)); }
  bool boolean(bool b) { return value(json(b)); }
  bool number_integer(json::number_integer_t v) { return value(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return value(json(v)); }
  bool number_float(json::number_float_t v, const std::string&) { return value(json(v)); }
  bool string(std::string& s) { return value(json(std::move(s))); }
  bool binary(json::binary_t&) { return value(json(nullptr)); }  // not produced by JSON text

  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    auto at = cur_.next_token();
    Frame& top = stack_.back();
    out_.positions.insert_or_assign(key_position(pointer_append(top.ptr, k)), at);
    if (top.node->contains(k)) {
      diags_.error("E0007", file_, at.first, at.second, pointer_append(top.ptr, k),
                   "duplicate key '" + k + "' in the same object",
                   "remove one of the two; JSON readers disagree on which one wins");
    }
    top.key = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
    failed_ = true;
    if (ex.id == 406) {  // a number too large for a double: point at its first digit
      auto at = cur_.peek_token();
      diags_.error("E0006", file_, at.first, at.second, current_pointer(),
                   "number is out of range (too large for a double)",
                   "use a number below 1.8e308; in SI units real values are far smaller");
      return false;
    }
    // `position` counts the characters read, the failing one included; at the
    // end of input point just after the last thing written instead.
    size_t off = position > 0 ? position - 1 : 0;
    if (off >= text_.size()) {
      off = text_.size();
      while (off > 0 && std::string_view(" \t\r\n").find(text_[off - 1]) != std::string_view::npos)
        --off;
    }
    std::string message = clean_message(ex.what());
    std::string hint;
    // A trailing comma: the closing bracket follows ',' (JSON forbids it).
    if (off < text_.size() && (text_[off] == ']' || text_[off] == '}')) {
      size_t k = off;
      while (k > 0 && std::string_view(" \t\r\n").find(text_[k - 1]) != std::string_view::npos) --k;
      if (k > 0 && text_[k - 1] == ',') hint = "remove the trailing comma before it";
    }
    std::pair<int, int> at;
    if (message.find("invalid literal") != std::string::npos || off < cur_.offset()) {
      at = cur_.peek_token();  // the start of the bad word, not where the lexer gave up
    } else {
      cur_.advance_to(off);
      at = cur_.pos();
    }
    diags_.error("E0003", file_, at.first, at.second, "", message, hint);
    return false;
  }

  bool failed() const { return failed_; }

 private:
  struct Frame {
    json* node;
    std::string ptr;
    std::string key;  // pending key (objects)
  };

  std::string current_pointer() const {
    if (stack_.empty()) return "";
    const Frame& top = stack_.back();
    if (top.node->is_array()) return top.ptr + "/" + std::to_string(top.node->size());
    return pointer_append(top.ptr, top.key);
  }

  // Stores v where the next value goes; returns it and its pointer.
  json* place(json&& v, std::string* ptr) {
    *ptr = current_pointer();
    if (stack_.empty()) {
      out_.value = std::move(v);
      return &out_.value;
    }
    Frame& top = stack_.back();
    if (top.node->is_array()) {
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    json& slot = (*top.node)[top.key];
    slot = std::move(v);
    return &slot;
  }

  bool value(json&& v) {
    auto at = cur_.next_token();
    std::string ptr;
    place(std::move(v), &ptr);
    out_.positions.insert_or_assign(std::move(ptr), at);
    return true;
  }

  bool open(json&& container) {
    auto at = cur_.next_token();
    if (stack_.size() >= max_depth_) {
      failed_ = true;
      // Name the top-level field that holds the deep data, not a 256-step pointer.
      diags_.error("E0005", file_, at.first, at.second,
                   stack_.size() > 1 ? stack_[1].ptr : current_pointer(),
                   "nesting is deeper than " + std::to_string(max_depth_) + " levels",
                   "a spec needs only a few levels; this file is probably not a spec");
      return false;
    }
    std::string ptr;
    json* node = place(std::move(container), &ptr);
    out_.positions.insert_or_assign(ptr, at);
    stack_.push_back({node, std::move(ptr), {}});
    return true;
  }

  bool close() {
    cur_.next_token();
    stack_.pop_back();
    return true;
  }

  std::string_view text_;
  Cursor cur_;
  const std::string& file_;
  size_t max_depth_;
  Diagnostics& diags_;
  PositionedJson& out_;
  std::vector<Frame> stack_;
  bool failed_ = false;
};

}  // namespace

size_t first_invalid_utf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    size_t n;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c < 0x80) {
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      n = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      n = 2;
      if (c == 0xE0) lo = 0xA0;  // overlong
      if (c == 0xED) hi = 0x9F;  // surrogates
    } else if (c >= 0xF0 && c <= 0xF4) {
      n = 3;
      if (c == 0xF0) lo = 0x90;
      if (c == 0xF4) hi = 0x8F;  // > U+10FFFF
    } else {
      return i;
    }
    for (size_t k = 1; k <= n; ++k) {
      if (i + k >= s.size()) return i;
      unsigned char d = static_cast<unsigned char>(s[i + k]);
      unsigned l = k == 1 ? lo : 0x80, h = k == 1 ? hi : 0xBF;
      if (d < l || d > h) return i;
    }
    i += n + 1;
  }
  return std::string_view::npos;
}

std::string json_kind_phrase(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::null: return "null";
    default: return "a number";
  }
}

std::string pointer_append(const std::string& base, std::string_view token) {
  std::string out = base;
  out += '/';
  for (char c : token) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::optional<PositionedJson> parse_positioned(std::string_view text, const std::string& file,
                                               size_t max_depth, Diagnostics& diags) {
  size_t bad = first_invalid_utf8(text);
  if (bad != std::string_view::npos) {
    Cursor c(text);
    c.advance_to(bad);
    auto at = c.pos();
    diags.error("E0004", file, at.first, at.second, "",
                "the file is not UTF-8 text (invalid byte 0x" +
                    [&] {
                      const char* hex = "0123456789abcdef";
                      unsigned char b = static_cast<unsigned char>(text[bad]);
                      return std::string{hex[b >> 4], hex[b & 15]};
                    }() +
                    ")",
                "save the spec as UTF-8; is this a binary file?");
    return std::nullopt;
  }
  std::string_view body = text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
  if (body.find_first_not_of(" \t\r\n") == std::string_view::npos) {
    diags.error("E0002", file, 1, 1, "", "the file is empty",
                "a spec is a JSON object: {\"efc\": 1, \"name\": ..., \"parts\": [...]}");
    return std::nullopt;
  }
  PositionedJson out;
  // About one value or key per 12 bytes of a typical spec: no rehashing.
  out.positions.reserve(text.size() / 12 + 16);
  Handler h(text, file, max_depth, diags, out);
  bool ok = json::sax_parse(text, &h, json::input_format_t::json, /*strict=*/true);
  if (!ok || h.failed()) return std::nullopt;
  return out;
}

}  // namespace efc::frontend
