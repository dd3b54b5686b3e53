// The PAIRS file of `efc eval --list`: one pair a line,
//   PRED GT [PRED_MASKS GT_SEQ]
// whitespace-separated, paths relative to the list file's folder, '#' starts
// a comment, blank lines skipped. A PRED that does not exist is a failed
// prediction (scored, not an error); a GT that does not exist is an error.
#pragma once

#include <string>
#include <vector>

#include "compiler/diagnostics.h"

namespace efc::eval {

struct PairEntry {
  std::string pred, gt;
  std::string pred_masks, gt_seq;  // both or neither
  int line = 0;
  // Set when the prediction is known to have failed (an efc batch job that
  // exited non-zero): scored as a failure, with this as the reason.
  std::string failure;
};

// False after any problem: the file cannot be read (E1022, *io_error set),
// or a line is malformed (E1021 at FILE:LINE:COL; every such line reported).
bool read_pair_list(const std::string& path, Diagnostics& diags, std::vector<PairEntry>* out, bool* io_error);

}  // namespace efc::eval
