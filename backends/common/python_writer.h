// One indent-aware writer for the Python every Python target generates, so
// indentation and docstrings are right by construction. Text from a spec
// enters Python only as a string literal (text::python_string_literal) or
// through docstring(), which escapes what could end it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace efc {

class PythonWriter {
 public:
  // One line at the current indentation ("" writes an empty line).
  void line(const std::string& code);
  // `header` (ending in ':') then indents what follows, until close().
  void open(const std::string& header);
  void close();
  // A triple-quoted docstring whose body is `text` escaped: backslashes,
  // quotes that could close it, control characters but newline, and non-ASCII
  // (as \uXXXX) cannot end it or hide in it.
  void docstring(const std::string& text);
  // callee(key=value, ...), one argument per line when it would not fit.
  void call(const std::string& callee, const std::vector<std::pair<std::string, std::string>>& kwargs);

  const std::string& text() const { return out_; }

 private:
  std::string indent() const { return std::string(4 * depth_, ' '); }
  std::string out_;
  int depth_ = 0;
};

// Word-wraps `text` at `width` columns, each line prefixed by `indent`.
std::string wrap_text(const std::string& text, size_t width, const std::string& indent = "");

}  // namespace efc
