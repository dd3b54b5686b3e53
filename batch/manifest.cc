#include "batch/manifest.h"

#include <cctype>
#include <cstdio>
#include <filesystem>

#include "batch/atomic_file.h"

namespace efc::batch {

namespace fs = std::filesystem;

bool split_words(const std::string& line, std::vector<Word>* words, int* bad_col, std::string* why) {
  words->clear();
  size_t i = 0;
  const size_t n = line.size();
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  while (i < n) {
    while (i < n && blank(line[i])) ++i;
    if (i == n) break;
    if (line[i] == '#') break;  // a comment to the end of the line
    Word w;
    w.col = static_cast<int>(i) + 1;
    while (i < n && !blank(line[i])) {
      const char c = line[i];
      if (c == '\'' || c == '"') {
        const size_t open = i++;
        bool closed = false;
        while (i < n) {
          if (line[i] == c) {
            closed = true;
            ++i;
            break;
          }
          if (c == '"' && line[i] == '\\' && i + 1 < n && (line[i + 1] == '"' || line[i + 1] == '\\')) ++i;
          w.text += line[i++];
        }
        if (!closed) {
          *bad_col = static_cast<int>(open) + 1;
          *why = std::string("unterminated ") + (c == '"' ? "double" : "single") + " quote";
          return false;
        }
      } else if (c == '\\') {
        if (i + 1 >= n) {
          *bad_col = static_cast<int>(i) + 1;
          *why = "a backslash at the end of the line escapes nothing";
          return false;
        }
        w.text += line[i + 1];
        i += 2;
      } else {
        w.text += c;
        ++i;
      }
    }
    words->push_back(std::move(w));
  }
  return true;
}

std::string job_id(int line, const std::string& path) {
  char number[16];
  std::snprintf(number, sizeof number, "%05d", line);
  std::string stem = fs::path(path).lexically_normal().filename().string();
  if (stem.empty() || stem == "." || stem == "..")
    stem = fs::path(path).lexically_normal().parent_path().filename().string();
  const size_t dot = stem.rfind('.');
  if (dot != std::string::npos && dot > 0) stem = stem.substr(0, dot);
  std::string safe;
  for (const char c : stem) {
    if (safe.size() >= 40) break;
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    safe += ok ? c : '_';
  }
  while (!safe.empty() && safe.front() == '.') safe.erase(safe.begin());
  return safe.empty() ? std::string(number) : std::string(number) + "-" + safe;
}

bool read_manifest(const std::string& manifest, Diagnostics& diags, std::vector<Job>* jobs, bool* io_error) {
  *io_error = false;
  std::string text;
  if (!read_whole_file(manifest, &text)) {
    *io_error = true;
    diags.error("E1101", manifest, 0, 0, "", "cannot read the manifest",
                "give a text file with one job (a spec or a sequence path) per line");
    return false;
  }
  std::error_code ec;
  const fs::path folder = fs::absolute(manifest, ec).parent_path();
  bool ok = true;
  size_t start = 0;
  for (int n = 1; start < text.size(); ++n) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find('\0') != std::string::npos) {
      diags.error("E1100", manifest, n, static_cast<int>(line.find('\0')) + 1, "",
                  "a NUL byte: the manifest is not a text file", "give a text file, one job per line");
      ok = false;
      break;
    }
    std::vector<Word> words;
    int col = 0;
    std::string why;
    if (!split_words(line, &words, &col, &why)) {
      diags.error("E1100", manifest, n, col, "", why,
                  "close the quote on the same line, or escape it with a backslash");
      ok = false;
      continue;
    }
    if (words.empty()) continue;
    if (words[0].text.empty()) {
      diags.error("E1100", manifest, n, words[0].col, "", "the job's path is empty", "write a spec or sequence path");
      ok = false;
      continue;
    }
    Job job;
    job.line = n;
    job.index = static_cast<int>(jobs->size());
    size_t a = line.find_first_not_of(" \t\v\f");
    size_t b = line.find_last_not_of(" \t\v\f");
    job.text = line.substr(a, b - a + 1);
    const fs::path p(words[0].text);
    job.path = (p.is_absolute() ? p : folder / p).lexically_normal().string();
    if (job.path.size() > 1 && job.path.back() == '/') job.path.pop_back();
    for (size_t k = 1; k < words.size(); ++k) {
      job.args.push_back(words[k].text);
      job.arg_cols.push_back(words[k].col);
    }
    job.id = job_id(n, job.path);
    jobs->push_back(std::move(job));
  }
  if (ok && jobs->empty()) {
    diags.error("E1102", manifest, 0, 0, "", "the manifest holds no jobs",
                "write one spec or sequence path per line ('#' starts a comment)");
    ok = false;
  }
  if (!ok) jobs->clear();
  return ok;
}

}  // namespace efc::batch
