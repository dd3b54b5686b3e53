// truth/: the ground truth written by synth and the importer. Each file
// present is checked for what its consumers (efc eval, the tests) rely on;
// the spec itself is checked by `efc check`, not here.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <iterator>
#include <string_view>

#include "compiler/frontend/positioned_json.h"
#include "sequence/sequence.h"

namespace efc::seq {
namespace {

namespace fs = std::filesystem;
constexpr const char* kCode = "E1008";

bool read_text(const std::string& path, std::string* text) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  text->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return in && !in.bad();
}

bool parse_number(std::string_view s, double* out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && end == s.data() + s.size();
}

std::string_view trim(std::string_view s, int* col) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) {
    s.remove_prefix(1);
    ++*col;
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

struct Field {
  std::string_view text;
  int col = 0;
};

std::vector<Field> split_csv(std::string_view line) {
  std::vector<Field> out;
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    const size_t end = comma == std::string_view::npos ? line.size() : comma;
    int col = static_cast<int>(start) + 1;
    std::string_view text = trim(line.substr(start, end - start), &col);
    out.push_back({text, col});
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

std::pair<int, int> position(const frontend::Positions& positions, const std::string& ptr) {
  auto it = positions.find(ptr);
  return it != positions.end() ? it->second : std::make_pair(1, 1);
}

void check_spec(const std::string& path, const std::string& text, int, Diagnostics& diags) {
  auto doc = frontend::parse_positioned(text, path, 256, diags);
  if (doc && !doc->value.is_object())
    diags.error(kCode, path, 1, 1, "", "truth/spec.json must be a spec v1 document (a JSON object)");
}

// {"object_to_world": [16 numbers, row-major]}, an affine transform.
void check_object_pose(const std::string& path, const std::string& text, int, Diagnostics& diags) {
  auto doc = frontend::parse_positioned(text, path, 256, diags);
  if (!doc) return;
  const auto& v = doc->value;
  if (!v.is_object() || !v.contains("object_to_world")) {
    const auto at = position(doc->positions, "");
    diags.error(kCode, path, at.first, at.second, "", "missing \"object_to_world\"",
                "write {\"object_to_world\": [16 numbers, row-major]}");
    return;
  }
  const auto& m = v["object_to_world"];
  const auto at = position(doc->positions, "/object_to_world");
  if (!m.is_array() || m.size() != 16) {
    diags.error(kCode, path, at.first, at.second, "/object_to_world",
                "\"object_to_world\" must be an array of 16 numbers (a 4x4 matrix, row-major)");
    return;
  }
  for (size_t i = 0; i < 16; ++i) {
    if (!m[i].is_number()) {
      const std::string ptr = "/object_to_world/" + std::to_string(i);
      const auto p = position(doc->positions, ptr);
      diags.error(kCode, path, p.first, p.second, ptr, "element " + std::to_string(i) + " is not a number");
      return;
    }
  }
  const double last[4] = {0, 0, 0, 1};
  for (size_t i = 12; i < 16; ++i)
    if (std::fabs(m[i].get<double>() - last[i - 12]) > 1e-6) {
      diags.error(kCode, path, at.first, at.second, "/object_to_world",
                  "the last row is not [0, 0, 0, 1]: not a rigid transform");
      return;
    }
}

// A header "t,<name>,..." and one row of finite numbers per frame, times
// strictly increasing.
void check_csv(const std::string& path, const std::string& text, int frames, Diagnostics& local) {
  std::vector<Field> header;
  int rows = 0, line_no = 0, last_line = 1, first_extra = 0;
  double previous_t = 0;
  std::string_view rest = text;
  while (!rest.empty()) {
    const size_t nl = rest.find('\n');
    std::string_view line = rest.substr(0, nl);
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
    last_line = ++line_no;
    int col = 1;
    if (trim(line, &col).empty()) continue;
    std::vector<Field> fields = split_csv(line);
    if (header.empty()) {
      header = fields;
      std::set<std::string_view> seen;
      if (fields[0].text != "t")
        local.error(kCode, path, line_no, fields[0].col, "", "the first column must be \"t\" (seconds)");
      for (const Field& f : fields)
        if (f.text.empty() || !seen.insert(f.text).second)
          local.error(kCode, path, line_no, f.col, "",
                      f.text.empty() ? "empty column name" : "duplicate column '" + std::string(f.text) + "'");
      continue;
    }
    if (++rows == frames + 1) first_extra = line_no;
    if (fields.size() != header.size()) {
      local.error(kCode, path, line_no, 1, "",
                  "row has " + std::to_string(fields.size()) + " fields, the header " +
                      std::to_string(header.size()));
      continue;
    }
    for (size_t i = 0; i < fields.size(); ++i) {
      double v = 0;
      if (!parse_number(fields[i].text, &v) || !std::isfinite(v)) {
        local.error(kCode, path, line_no, fields[i].col, "",
                    "'" + std::string(fields[i].text) + "' is not a finite number");
        break;
      }
      if (i == 0 && rows > 1 && !(v > previous_t))
        local.error(kCode, path, line_no, fields[0].col, "", "time is not after the previous row's");
      if (i == 0) previous_t = v;
    }
  }
  if (header.empty())
    local.error(kCode, path, 1, 1, "", "empty file: expected a header \"t,...\" and one row per frame");
  else if (rows != frames)
    local.error("E1007", path, rows > frames ? first_extra : last_line, 1, "",
                "has " + std::to_string(rows) + " rows, meta.json says " + std::to_string(frames) + " frames");
}

}  // namespace

bool check_truth(const std::string& truth_dir, int frames, Diagnostics& diags) {
  using Check = void (*)(const std::string&, const std::string&, int, Diagnostics&);
  const std::pair<const char*, Check> files[] = {{"spec.json", check_spec},
                                                 {"object_pose.json", check_object_pose},
                                                 {"joints.csv", check_csv},
                                                 {"effects.csv", check_csv}};
  const size_t before = diags.error_count();
  for (const auto& [name, check] : files) {
    const std::string path = (fs::path(truth_dir) / name).string();
    std::error_code ec;
    if (!fs::exists(path, ec)) continue;
    std::string text;
    if (!read_text(path, &text)) {
      diags.error(kCode, path, 0, 0, "", "cannot read the file (a folder, or not readable)");
      continue;
    }
    Diagnostics local;
    check(path, text, frames, local);
    local.attach_source_lines(path, text);
    for (const auto& d : local.items()) diags.add(d);
  }
  return diags.error_count() == before;
}

}  // namespace efc::seq
