#include "backends/common/python_writer.h"

#include <cstdio>
#include <sstream>

namespace efc {

namespace {

// A docstring body that cannot end early or smuggle a look-alike character.
std::string docstring_body(const std::string& s) {
  std::string out;
  char buf[16];
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '"') {
      out += "\\\"";  // no run of three quotes can form
    } else if (c == '\n') {
      out += '\n';
    } else if (c < 0x20 || c == 0x7f) {
      out += ' ';
    } else if (c < 0x80) {
      out += static_cast<char>(c);
    } else {
      // Decode the UTF-8 sequence and write it as an escape (invalid bytes: U+FFFD).
      int len = (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
      unsigned cp = 0xFFFD;
      if (len && i + len <= s.size()) {
        cp = len == 2 ? (c & 0x1F) : len == 3 ? (c & 0x0F) : (c & 0x07);
        for (int k = 1; k < len; ++k) {
          const unsigned char b = static_cast<unsigned char>(s[i + k]);
          if ((b >> 6) != 2) {
            cp = 0xFFFD;
            len = 1;
            break;
          }
          cp = (cp << 6) | (b & 0x3F);
        }
        i += len - 1;
      }
      if (cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = 0xFFFD;
      std::snprintf(buf, sizeof buf, cp < 0x10000 ? "\\u%04x" : "\\U%08x", cp);
      out += buf;
    }
  }
  return out;
}

}  // namespace

std::string wrap_text(const std::string& text, size_t width, const std::string& indent) {
  std::string out, line;
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    if (!line.empty() && indent.size() + line.size() + 1 + word.size() > width) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) out += indent + line + "\n";
  return out;
}

void PythonWriter::line(const std::string& code) { out_ += code.empty() ? "\n" : indent() + code + "\n"; }

void PythonWriter::open(const std::string& header) {
  line(header);
  ++depth_;
}

void PythonWriter::close() {
  if (depth_ > 0) --depth_;
}

void PythonWriter::docstring(const std::string& text) {
  std::string body = docstring_body(text);
  // Indent continuation lines; a trailing backslash cannot occur (escaped).
  std::string indented;
  const std::string pad = indent();
  for (size_t i = 0; i < body.size(); ++i) {
    indented += body[i];
    if (body[i] == '\n' && i + 1 < body.size() && body[i + 1] != '\n') indented += pad;
  }
  out_ += pad + "\"\"\"" + indented + "\"\"\"\n";
}

void PythonWriter::call(const std::string& callee,
                        const std::vector<std::pair<std::string, std::string>>& kwargs) {
  std::string one = callee + "(";
  for (size_t i = 0; i < kwargs.size(); ++i)
    one += (i ? ", " : "") + kwargs[i].first + "=" + kwargs[i].second;
  one += ")";
  if (indent().size() + one.size() <= 88) {
    line(one);
    return;
  }
  open(callee + "(");
  for (const auto& [key, value] : kwargs) line(key + "=" + value + ",");
  close();
  line(")");
}

}  // namespace efc
