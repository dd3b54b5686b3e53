// The MANIFEST of `efc batch`: one job a line,
//   PATH [ARG...]
// PATH is a spec or a sequence folder (relative paths resolve against the
// manifest's folder); the arguments are added to that job's command line.
// Words are separated by blanks; '...' quotes literally, "..." quotes with
// \" and \\ escapes, a backslash outside quotes escapes the next character.
// An unquoted '#' that starts a word begins a comment; blank and comment-only
// lines are skipped.
#pragma once

#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::batch {

struct Job {
  int line = 0;                   // 1-based line of the manifest
  int index = 0;                  // 0-based position among the manifest's jobs (--shard takes index % N == I)
  std::string text;               // the line as written, blanks trimmed: the results' "job"
  std::string path;               // PATH, absolute and normalised
  std::vector<std::string> args;  // the line's arguments, unquoted
  std::vector<int> arg_cols;      // and where each starts (1-based), for located errors
  std::string id;                 // stable, unique, a safe folder name: "00012-desk_lamp"
};

// One word of a line and its 1-based column.
struct Word {
  std::string text;
  int col = 0;
};

// Splits one line into words. False with *bad_col (1-based) and *why on an
// unterminated quote or a trailing backslash.
bool split_words(const std::string& line, std::vector<Word>* words, int* bad_col, std::string* why);

// "00012-desk_lamp": the line number, zero-padded to 5 digits so that ids sort
// in manifest order, then the file name without its extension, reduced to
// [A-Za-z0-9_.-] (at most 40 characters, never starting with a dot). The line
// number alone makes it unique; no byte of PATH can make it leave DIR/jobs/.
std::string job_id(int line, const std::string& path);

// Reads every job of `manifest`. False after any problem: the file cannot be
// read (E1101, *io_error set), a line is malformed (E1100 at FILE:LINE:COL,
// every such line reported) or there is no job (E1102).
bool read_manifest(const std::string& manifest, Diagnostics& diags, std::vector<Job>* jobs, bool* io_error);

}  // namespace efc::batch
