// efc batch --merge DIR: joins the shards' results (DIR/results-I-of-N.jsonl)
// into DIR/results.jsonl, each job of DIR/batch.json once, in manifest order.
// Nothing is guessed: a shard file that is missing, shards of different N, a
// line that is not a record, or a job without a result in its shard is an
// error, and then DIR/results.jsonl is left as it was.
#pragma once

#include <string>

#include "compiler/diagnostics.h"

namespace efc::batch {

struct MergeSummary {
  int shards = 0, jobs = 0, failed = 0;
};

// 0 merged (failed jobs included: they are results too), 1 something missing
// or malformed (every problem reported), 2 DIR or batch.json unreadable, or
// results.jsonl not writable.
int merge_shards(const std::string& dir, Diagnostics& diags, MergeSummary* summary);

}  // namespace efc::batch
