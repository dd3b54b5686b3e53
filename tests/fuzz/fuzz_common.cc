#include "tests/fuzz/fuzz_common.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace efc_fuzz {
namespace {

std::string make_base_dir() {
  std::string tmpl = (fs::temp_directory_path() / "efc-fuzz-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) {
    std::perror("efc-fuzz: mkdtemp");
    std::abort();
  }
  fs::create_directories(fs::path(tmpl) / "meshes");
  for (const char* mesh : {"faucet_handle.obj", "faucet_spout.obj"})
    std::ofstream(fs::path(tmpl) / "meshes" / mesh) << "# empty\n";
  // libFuzzer leaves through exit() (or _Exit on a crash, leaving the folder).
  static std::string dir = tmpl;
  std::atexit([] {
    std::error_code ec;
    fs::remove_all(dir, ec);
  });
  return tmpl;
}

std::string escaped(std::string_view s) {
  std::string out;
  for (unsigned char c : s) {
    if (c == '\n') out += "\\n";
    else if (c == '\\') out += "\\\\";
    else if (c >= 0x20 && c < 0x7f) out += static_cast<char>(c);
    else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

}  // namespace

const std::string& base_dir() {
  static const std::string dir = make_base_dir();
  return dir;
}

void fail(const std::string& what, std::string_view input) {
  std::fprintf(stderr, "\n==efc-fuzz== oracle failed: %s\n", what.c_str());
  if (input.size() <= 4096)
    std::fprintf(stderr, "==efc-fuzz== input (%zu bytes): \"%s\"\n", input.size(),
                 escaped(input).c_str());
  std::fflush(stderr);
  __builtin_trap();
}

void check_diagnostics(const efc::Diagnostics& diags, std::string_view text, bool rejected,
                       const char* stage) {
  const std::string where = std::string(stage) + ": ";
  if (rejected && !diags.has_errors()) fail(where + "returned nothing without an error", text);
  const int lines = 1 + static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  for (const efc::Diagnostic& d : diags.items()) {
    const std::string text_form = efc::format_text(d);
    if (d.code.empty() || !efc::find_code(d.code))
      fail(where + "diagnostic with an uncatalogued code: " + text_form, text);
    if (d.line < 0 || d.line > lines + 1 || d.col < 0 || (d.line == 0 && d.col != 0))
      fail(where + "diagnostic outside the text (" + std::to_string(lines) +
               " lines): " + text_form, text);
    const std::string json_form = efc::format_json(d);
    if (!nlohmann::json::accept(json_form))
      fail(where + "diagnostic is not one JSON line: " + json_form, text);
  }
}

}  // namespace efc_fuzz
