// poses.txt (TUM lines) and hands.txt: whitespace-separated numbers, one line
// per frame. Every problem is at file:line:col, the column of the number at
// fault, with the line quoted under it.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>

#include "sequence/sequence.h"

namespace efc::seq {
namespace {

constexpr const char* kLineCode = "E1006";
constexpr const char* kCountCode = "E1007";

struct Token {
  std::string_view text;
  int col = 0;  // 1-based
};

// One data line: its number in the file, its tokens and their values.
struct Row {
  int line = 0;
  std::vector<Token> tokens;
  std::vector<double> values;
};

// A track file's layout, for parsing and for messages.
struct Layout {
  const char* what;    // "pose"
  size_t count;        // numbers per line
  const char* fields;  // "t tx ty tz qx qy qz qw"
};
const Layout kPoses{"pose", 8, "t tx ty tz qx qy qz qw"};
const Layout kHands{"hand", 4, "t x y z"};

std::vector<Token> split(std::string_view line) {
  std::vector<Token> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

// The whole token as a number ("nan" and "inf" included; the checks decide).
bool parse_number(std::string_view s, double* out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && end == s.data() + s.size();
}

bool read_text(const std::string& path, std::string* text) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  text->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return in && !in.bad();
}

// Every data line parsed: a line with the wrong count or a token that is no
// number is reported and kept out of `rows`, but still counts as a line (the
// frame count is compared with what the user wrote, not with what parsed).
struct Parsed {
  std::vector<Row> rows;
  std::vector<int> line_of_data;  // the line number of each data line
  int last_line = 1;
};

Parsed parse_rows(std::string_view text, const std::string& file, const Layout& layout, Diagnostics& diags) {
  Parsed p;
  int line_no = 0;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    at = end + 1;
    ++line_no;
    p.last_line = line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    Row row;
    row.line = line_no;
    row.tokens = split(line);
    if (row.tokens.empty() || row.tokens[0].text[0] == '#') continue;
    p.line_of_data.push_back(line_no);
    if (row.tokens.size() != layout.count) {
      const int col = row.tokens.size() > layout.count ? row.tokens[layout.count].col
                                                       : static_cast<int>(line.size()) + 1;
      diags.error(kLineCode, file, line_no, col, "",
                  std::string("a ") + layout.what + " line has " + std::to_string(layout.count) +
                      " numbers (" + layout.fields + "), this one has " + std::to_string(row.tokens.size()));
      continue;
    }
    bool ok = true;
    for (const Token& t : row.tokens) {
      double v = 0;
      if (!parse_number(t.text, &v)) {
        diags.error(kLineCode, file, line_no, t.col, "", "'" + std::string(t.text) + "' is not a number");
        ok = false;
        break;
      }
      row.values.push_back(v);
    }
    if (ok) p.rows.push_back(std::move(row));
  }
  return p;
}

// Times strictly increase, line after line.
bool check_time(const Row& row, const Row* previous, const std::string& file, Diagnostics& diags) {
  const double t = row.values[0];
  if (!std::isfinite(t)) {
    diags.error(kLineCode, file, row.line, row.tokens[0].col, "", "time is " + std::string(row.tokens[0].text));
    return false;
  }
  if (previous && !(t > previous->values[0])) {
    diags.error(kLineCode, file, row.line, row.tokens[0].col, "",
                "time " + std::string(row.tokens[0].text) + " is not after the previous line's (" +
                    std::string(previous->tokens[0].text) + ")",
                "one line per frame, in frame order");
    return false;
  }
  return true;
}

bool check_pose(const Row& row, const std::string& file, Diagnostics& diags) {
  static const char* names[] = {"t", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  for (size_t i = 1; i < 8; ++i)
    if (!std::isfinite(row.values[i])) {
      diags.error(kLineCode, file, row.line, row.tokens[i].col, "",
                  std::string(names[i]) + " is " + std::string(row.tokens[i].text) + "; a pose must be finite",
                  "every frame needs a finite pose: interpolate one from its neighbours");
      return false;
    }
  const double norm = std::sqrt(row.values[4] * row.values[4] + row.values[5] * row.values[5] +
                                row.values[6] * row.values[6] + row.values[7] * row.values[7]);
  if (std::fabs(1 - norm) > 1e-3) {
    char msg[96];
    std::snprintf(msg, sizeof msg, "the quaternion (qx qy qz qw) has length %.6g, not 1", norm);
    diags.error(kLineCode, file, row.line, row.tokens[4].col, "", msg, "normalise it");
    return false;
  }
  return true;
}

// "t x y z" or "t nan nan nan"; nothing in between.
bool check_hand(const Row& row, const std::string& file, Diagnostics& diags) {
  int nans = 0;
  for (size_t i = 1; i < 4; ++i) nans += std::isnan(row.values[i]);
  if (nans == 0 || nans == 3) {
    for (size_t i = 1; i < 4; ++i)
      if (std::isinf(row.values[i])) {
        diags.error(kLineCode, file, row.line, row.tokens[i].col, "",
                    "hand coordinate is " + std::string(row.tokens[i].text));
        return false;
      }
    return true;
  }
  size_t first = 1;
  while (!std::isnan(row.values[first])) ++first;
  diags.error(kLineCode, file, row.line, row.tokens[first].col, "",
              "only some of x y z are nan",
              "write \"t nan nan nan\" when no hand is seen, or all three coordinates");
  return false;
}

// The count against meta.json's "frames": at the first line too many, or at
// the end of a file too short.
void check_count(const Parsed& p, int frames, const std::string& file, const Layout& layout,
                 Diagnostics& diags) {
  const int lines = static_cast<int>(p.line_of_data.size());
  if (frames < 0 || lines == frames) return;
  const int line = lines > frames ? p.line_of_data[frames] : p.last_line;
  diags.error(kCountCode, file, line, 1, "",
              "has " + std::to_string(lines) + " " + layout.what + " lines, meta.json says " +
                  std::to_string(frames) + " frames",
              "one line per frame, in frame order");
}

// Reads, parses, checks; diagnostics quoting their line.
template <typename T, typename Check, typename Convert>
bool read_track(const std::string& path, int frames, const Layout& layout, Diagnostics& diags,
                std::vector<T>* out, Check check, Convert convert) {
  out->clear();
  std::string text;
  if (!read_text(path, &text)) {
    diags.error(kLineCode, path, 0, 0, "", "cannot read the file (missing, a folder, or not readable)");
    return false;
  }
  Diagnostics local;
  Parsed p = parse_rows(text, path, layout, local);
  const Row* previous = nullptr;
  for (const Row& row : p.rows) {
    if (!check_time(row, previous, path, local) || !check(row, path, local)) continue;
    previous = &row;
    out->push_back(convert(row));
  }
  check_count(p, frames, path, layout, local);
  local.attach_source_lines(path, text);
  for (const auto& d : local.items()) diags.add(d);
  return !local.has_errors();
}

Pose to_pose(const Row& r) {
  Pose p;
  p.t = r.values[0];
  for (int i = 0; i < 3; ++i) p.p[i] = r.values[1 + i];
  for (int i = 0; i < 4; ++i) p.q[i] = r.values[4 + i];
  return p;
}

HandPoint to_hand(const Row& r) {
  HandPoint h;
  h.t = r.values[0];
  h.seen = !std::isnan(r.values[1]);
  if (h.seen)
    for (int i = 0; i < 3; ++i) h.p[i] = r.values[1 + i];
  return h;
}

// The shortest text that reads back as the same double.
void append_number(std::string* out, double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out->append(buf, ec == std::errc() ? end : buf);
}

}  // namespace

bool write_text_file(const std::string& path, const std::string& text, std::string* error) {
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) {
    *error = "cannot write " + path;
    return false;
  }
  const bool wrote = std::fwrite(text.data(), 1, text.size(), fp) == text.size();
  if (std::fclose(fp) != 0 || !wrote) {
    *error = "cannot write " + path + " (disk full?)";
    std::remove(path.c_str());
    return false;
  }
  return true;
}

bool read_poses(const std::string& path, int frames, Diagnostics& diags, std::vector<Pose>* out) {
  return read_track(path, frames, kPoses, diags, out, check_pose, to_pose);
}

bool read_hands(const std::string& path, int frames, Diagnostics& diags, std::vector<HandPoint>* out) {
  return read_track(path, frames, kHands, diags, out, check_hand, to_hand);
}

bool read_poses(const std::string& path, Diagnostics& diags, std::vector<Pose>* out) {
  return read_poses(path, -1, diags, out);
}

bool read_hands(const std::string& path, Diagnostics& diags, std::vector<HandPoint>* out) {
  return read_hands(path, -1, diags, out);
}

bool write_poses(const std::string& path, const std::vector<Pose>& poses, std::string* error) {
  std::string text = "# t tx ty tz qx qy qz qw  (camera-to-world, TUM)\n";
  for (size_t i = 0; i < poses.size(); ++i) {
    const Pose& p = poses[i];
    const double values[8] = {p.t, p.p[0], p.p[1], p.p[2], p.q[0], p.q[1], p.q[2], p.q[3]};
    for (int k = 0; k < 8; ++k) {
      if (!std::isfinite(values[k])) {
        *error = "pose " + std::to_string(i) + " is not finite";
        return false;
      }
      if (k) text += ' ';
      append_number(&text, values[k]);
    }
    text += '\n';
  }
  return write_text_file(path, text, error);
}

bool write_hands(const std::string& path, const std::vector<HandPoint>& hands, std::string* error) {
  std::string text = "# t x y z  (hand contact point, world frame; nan: no hand seen)\n";
  for (size_t i = 0; i < hands.size(); ++i) {
    const HandPoint& h = hands[i];
    const bool finite = std::isfinite(h.t) && (!h.seen || (std::isfinite(h.p[0]) && std::isfinite(h.p[1]) &&
                                                           std::isfinite(h.p[2])));
    if (!finite) {
      *error = "hand point " + std::to_string(i) + " is not finite";
      return false;
    }
    append_number(&text, h.t);
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      if (h.seen)
        append_number(&text, h.p[k]);
      else
        text += "nan";
    }
    text += '\n';
  }
  return write_text_file(path, text, error);
}

}  // namespace efc::seq
