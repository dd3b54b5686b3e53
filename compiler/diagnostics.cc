#include "compiler/diagnostics.h"

#include <algorithm>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

namespace efc {

void Diagnostics::error(std::string code, std::string file, int line, int col,
                        std::string pointer, std::string message, std::string hint) {
  items_.push_back({Severity::Error, std::move(code), std::move(file), line, col,
                    std::move(pointer), std::move(message), std::move(hint), {}});
}

void Diagnostics::warning(std::string code, std::string file, int line, int col,
                          std::string pointer, std::string message, std::string hint) {
  items_.push_back({Severity::Warning, std::move(code), std::move(file), line, col,
                    std::move(pointer), std::move(message), std::move(hint), {}});
}

void Diagnostics::note(std::string message) {
  items_.push_back({Severity::Note, {}, {}, 0, 0, {}, std::move(message), {}, {}});
}

bool Diagnostics::has_errors() const { return error_count() > 0; }

size_t Diagnostics::error_count() const {
  size_t n = 0;
  for (const auto& d : items_) n += d.severity == Severity::Error;
  return n;
}

size_t Diagnostics::warning_count() const {
  size_t n = 0;
  for (const auto& d : items_) n += d.severity == Severity::Warning;
  return n;
}

static const char* severity_name(Severity s) {
  switch (s) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

std::string format_text(const Diagnostic& d) {
  if (d.severity == Severity::Note && d.file.empty() && d.code.empty()) return d.message + "\n";
  std::string out = d.file.empty() ? std::string("efc") : d.file;
  if (d.line > 0) {
    out += ":" + std::to_string(d.line);
    if (d.col > 0) out += ":" + std::to_string(d.col);
  }
  out += ": ";
  out += severity_name(d.severity);
  if (!d.code.empty()) out += "[" + d.code + "]";
  out += ": " + d.message + "\n";
  if (!d.source_line.empty() && d.line > 0) {
    // The line, then a caret under the column (columns count code points;
    // tabs are kept so the caret lines up in a terminal).
    const std::string number = std::to_string(d.line);
    out += "  " + number + " | " + d.source_line + "\n";
    out += "  " + std::string(number.size(), ' ') + " | ";
    int col = 1;
    for (size_t i = 0; i < d.source_line.size() && col < d.col; ++i) {
      unsigned char c = static_cast<unsigned char>(d.source_line[i]);
      if ((c & 0xC0) == 0x80) continue;
      out += c == '\t' ? '\t' : ' ';
      ++col;
    }
    out += "^\n";
  }
  if (!d.pointer.empty()) out += "  at " + d.pointer + "\n";
  if (!d.hint.empty()) out += "  hint: " + d.hint + "\n";
  return out;
}

std::string format_json(const Diagnostic& d) {
  nlohmann::json j = {{"severity", severity_name(d.severity)},
                      {"code", d.code},
                      {"file", d.file},
                      {"line", d.line},
                      {"column", d.col},
                      {"pointer", d.pointer},
                      {"message", d.message}};
  if (!d.hint.empty()) j["hint"] = d.hint;
  // Replace invalid UTF-8 rather than throw: messages may quote user bytes.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void Diagnostics::attach_source_lines(const std::string& file, std::string_view text) {
  auto wants_line = [&](const Diagnostic& d) {
    return d.file == file && d.line > 0 && d.source_line.empty();
  };
  // Nothing to do on the common path (no diagnostics): skip indexing the text.
  if (std::none_of(items_.begin(), items_.end(), wants_line)) return;
  // Line start offsets, computed once.
  std::vector<size_t> starts{0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  for (auto& d : items_) {
    if (!wants_line(d) || static_cast<size_t>(d.line) > starts.size()) continue;
    size_t begin = starts[d.line - 1];
    size_t end = text.find('\n', begin);
    std::string line(text.substr(begin, end == std::string_view::npos ? text.size() - begin
                                                                      : end - begin));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() > 200) continue;  // a minified file: the caret would not help
    // Control characters would garble the terminal (a binary file): no line.
    // (Other bytes are shown as they are: a Latin-1 line still helps.)
    const bool control = std::any_of(line.begin(), line.end(), [](char ch) {
      const unsigned char u = static_cast<unsigned char>(ch);
      return (u < 0x20 && u != '\t') || u == 0x7f;
    });
    if (control) continue;
    d.source_line = std::move(line);
  }
}

void Diagnostics::print(std::ostream& os, bool json_lines) const {
  for (const auto& d : items_) os << (json_lines ? format_json(d) : format_text(d));
}

}  // namespace efc
