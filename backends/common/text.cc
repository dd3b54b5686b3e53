#include "backends/common/text.h"

#include <charconv>
#include <cstdint>
#include <cstdio>

namespace efc {
namespace text {

std::string number(double v) {
  if (v == 0) return "0";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string vec3(const Vec3& v) { return number(v[0]) + " " + number(v[1]) + " " + number(v[2]); }

std::string cpp_double(double v) {
  std::string s = number(v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '-': out += (!out.empty() && out.back() == '-') ? " -" : "-"; break;  // no "--" in comments
      default:
        out += (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') ? ' ' : c;
    }
  }
  return out;
}

std::string xml_comment(const std::string& s) {
  std::string out;
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u < 0x20 && c != '\n' && c != '\t') {
      out += ' ';
    } else if (c == '-' && !out.empty() && out.back() == '-') {
      out += " -";
    } else {
      out += c;
    }
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

std::string cpp_string_literal(const std::string& s) {
  std::string out = "\"";
  char buf[8];
  for (char c : s) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += c;
    } else if (u >= 0x20 && u < 0x7f && c != '?') {  // '?' escaped: no trigraphs
      out += c;
    } else {
      std::snprintf(buf, sizeof buf, "\\%03o", u);  // octal takes at most 3 digits
      out += buf;
    }
  }
  return out + "\"";
}

std::string cpp_comment(const std::string& s) {
  std::string out;
  for (char c : s) out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
  // GCC continues a line ending in a backslash even with spaces after it.
  const size_t last = out.find_last_not_of(' ');
  if (last != std::string::npos && out[last] == '\\') out += '.';
  return out;
}

namespace {

// Decodes one UTF-8 sequence at s[i]; returns the code point and advances i,
// or U+FFFD for a malformed, overlong or surrogate sequence (advancing one byte).
uint32_t next_code_point(const std::string& s, size_t* i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(*i);
  int len = b0 < 0x80 ? 1 : (b0 >> 5) == 6 ? 2 : (b0 >> 4) == 14 ? 3 : (b0 >> 3) == 30 ? 4 : 0;
  if (len == 0 || *i + len > s.size()) {
    ++*i;
    return 0xFFFD;
  }
  uint32_t cp = len == 1 ? b0 : len == 2 ? (b0 & 0x1F) : len == 3 ? (b0 & 0x0F) : (b0 & 0x07);
  for (int k = 1; k < len; ++k) {
    const unsigned char b = byte(*i + k);
    if ((b >> 6) != 2) {
      ++*i;
      return 0xFFFD;
    }
    cp = (cp << 6) | (b & 0x3F);
  }
  static const uint32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
    ++*i;
    return 0xFFFD;
  }
  *i += len;
  return cp;
}

}  // namespace

std::string python_string_literal(const std::string& s) {
  std::string out = "'";
  char buf[16];
  for (size_t i = 0; i < s.size();) {
    const uint32_t cp = next_code_point(s, &i);
    if (cp == '\\' || cp == '\'') {
      out += '\\';
      out += static_cast<char>(cp);
    } else if (cp == '\n') {
      out += "\\n";
    } else if (cp == '\t') {
      out += "\\t";
    } else if (cp == '\r') {
      out += "\\r";
    } else if (cp >= 0x20 && cp < 0x7f) {
      out += static_cast<char>(cp);
    } else if (cp < 0x100) {
      std::snprintf(buf, sizeof buf, "\\x%02x", cp);
      out += buf;
    } else if (cp < 0x10000) {
      std::snprintf(buf, sizeof buf, "\\u%04x", cp);
      out += buf;
    } else {
      std::snprintf(buf, sizeof buf, "\\U%08x", cp);
      out += buf;
    }
  }
  return out + "'";
}

}  // namespace text
}  // namespace efc
