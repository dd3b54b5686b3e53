// Compiler-style diagnostics: collected (never thrown) so one run reports
// every problem, printed as `file:line:col: error[CODE]: message` with the JSON
// pointer and a hint as indented notes, or as JSON lines for tools.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace efc {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string code;     // "E0203"; stable, documented by `efc explain`
  std::string file;
  int line = 0, col = 0;  // 1-based; 0 = unknown
  std::string pointer;  // JSON pointer of the field ("" = whole document)
  std::string message;
  std::string hint;     // optional
  // The source line the position points into, shown under the message with a
  // caret (see Diagnostics::attach_source_lines).
  std::string source_line;
};

class Diagnostics {
 public:
  void add(Diagnostic d) { items_.push_back(std::move(d)); }
  void error(std::string code, std::string file, int line, int col, std::string pointer,
             std::string message, std::string hint = {});
  void warning(std::string code, std::string file, int line, int col, std::string pointer,
               std::string message, std::string hint = {});

  // A message of the program itself, about no spec: progress such as
  // "compiled toaster -> out/mujoco". Text form prints just the message.
  void note(std::string message);

  bool has_errors() const;
  size_t error_count() const;
  size_t warning_count() const;
  const std::vector<Diagnostic>& items() const { return items_; }
  void clear() { items_.clear(); }
  // Sets source_line on every diagnostic in `file` with a line, from `text`
  // (the spec's text). Lines over 200 bytes (minified) or with control
  // characters (a binary file) are left out.
  void attach_source_lines(const std::string& file, std::string_view text);

  // Text (compiler style) or JSON lines.
  void print(std::ostream& os, bool json_lines) const;

 private:
  std::vector<Diagnostic> items_;
};

std::string format_text(const Diagnostic& d);
std::string format_json(const Diagnostic& d);

// The catalogue of codes: title and long explanation, for `efc explain`.
struct CodeInfo {
  const char* code;
  const char* title;
  const char* explanation;  // several lines: what it means, an example, the fix
};
const CodeInfo* find_code(const std::string& code);
const std::vector<CodeInfo>& all_codes();

}  // namespace efc
