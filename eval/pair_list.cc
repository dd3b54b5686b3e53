#include "eval/pair_list.h"

#include <cctype>
#include <filesystem>
#include <fstream>

namespace efc::eval {

namespace fs = std::filesystem;

namespace {

struct Field {
  std::string text;
  int col = 0;  // 1-based
};

// The whitespace-separated fields of a line before any '#'.
std::vector<Field> split_fields(const std::string& line) {
  std::vector<Field> out;
  const size_t end = line.find('#');
  const std::string body = line.substr(0, end);
  size_t i = 0;
  while (i < body.size()) {
    while (i < body.size() && std::isspace(static_cast<unsigned char>(body[i]))) ++i;
    if (i == body.size()) break;
    const size_t start = i;
    while (i < body.size() && !std::isspace(static_cast<unsigned char>(body[i]))) ++i;
    out.push_back({body.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

std::string relative_to(const fs::path& folder, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() ? p : (folder / path).lexically_normal().string();
}

}  // namespace

bool read_pair_list(const std::string& path, Diagnostics& diags, std::vector<PairEntry>* out, bool* io_error) {
  *io_error = false;
  std::error_code ec;
  std::ifstream in(path);
  if (fs::is_directory(path, ec) || !in) {
    *io_error = true;
    diags.error("E1022", path, 0, 0, "", "cannot read the list of pairs", "give a text file: PRED GT per line");
    return false;
  }
  const fs::path folder = fs::path(path).parent_path();
  const std::string usage = "write PRED GT, or PRED GT PRED_MASKS GT_SEQ";
  bool ok = true;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::vector<Field> f = split_fields(line);
    if (f.empty()) continue;
    if (f.size() != 2 && f.size() != 4) {
      const Field& at = f.size() == 1 ? f[0] : f.size() == 3 ? f[2] : f[4];
      diags.error("E1021", path, n, at.col, "",
                  "a pair line has 2 or 4 columns, this one " + std::to_string(f.size()), usage);
      ok = false;
      continue;
    }
    PairEntry e;
    e.line = n;
    e.pred = relative_to(folder, f[0].text);
    e.gt = relative_to(folder, f[1].text);
    if (!fs::is_regular_file(e.gt, ec)) {
      diags.error("E1021", path, n, f[1].col, "", "the true spec '" + f[1].text + "' does not exist",
                  "GT paths are relative to the list file's folder");
      ok = false;
      continue;
    }
    if (f.size() == 4) {
      e.pred_masks = relative_to(folder, f[2].text);
      e.gt_seq = relative_to(folder, f[3].text);
      if (!fs::is_directory(e.gt_seq, ec)) {
        diags.error("E1021", path, n, f[3].col, "", "the true sequence '" + f[3].text + "' is not a folder",
                    "GT_SEQ paths are relative to the list file's folder");
        ok = false;
        continue;
      }
    }
    out->push_back(e);
  }
  if (ok && out->empty()) {
    diags.error("E1021", path, 0, 0, "", "the list holds no pairs", usage);
    ok = false;
  }
  return ok;
}

}  // namespace efc::eval
