// Files that are either absent, or whole: a batch may be killed at any
// instant (SIGKILL, a node lost, a Slurm time limit), and what it leaves must
// still read as a valid record or results file.
#pragma once

#include <string>

namespace efc::batch {

// Writes `bytes` to a temporary file beside `path` (a name unique across
// hosts sharing the folder: host, pid, counter), fsyncs it and renames it over
// `path`. False with *error on failure; the temporary file is removed.
bool write_file_atomically(const std::string& path, const std::string& bytes, std::string* error);

// The whole file; false when it cannot be read.
bool read_whole_file(const std::string& path, std::string* out);

// The prefix of every temporary file the batch writes (so a folder check can
// tell them from the user's files).
constexpr const char* kTempPrefix = ".efc-batch-tmp-";

}  // namespace efc::batch
