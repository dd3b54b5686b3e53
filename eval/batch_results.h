// `efc eval --list DIR/results.jsonl` (or --list DIR): the results of an
// `efc batch ... -- infer` over sequences as the list of pairs. Each record
// (one JSON object a line, written by efc batch) gives the sequence ("path")
// and the job's folder ("output", relative to the results file's folder);
// the truth is PATH/truth/spec.json, the prediction DIR/OUTPUT/spec.json. A
// job that failed (exit_code != 0) is a failed prediction, scored as such.
#pragma once

#include <string>
#include <vector>

#include "compiler/diagnostics.h"
#include "eval/pair_list.h"

namespace efc::eval {

// Whether `list` names batch results: a file ending in .jsonl, or a folder
// (then its results.jsonl is read).
bool is_batch_results(const std::string& list);

// False after any problem: the file cannot be read (E1022, *io_error set), or
// a line is not a record or its sequence has no truth (E1118 at FILE:LINE,
// every such line reported). *results_file: the file read.
bool read_batch_results(const std::string& list, Diagnostics& diags, std::vector<PairEntry>* out, bool* io_error,
                        std::string* results_file);

}  // namespace efc::eval
