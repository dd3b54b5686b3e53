// How efc eval shows its results: one JSON object (--json) or text tables in
// the layout of the paper's (articulation, reconstruction, template, mask).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/paper_metrics.h"

namespace efc::eval {

// {"pred", "gt", "prediction_loaded", ["prediction_problem"], "joints",
//  "functions", "chamfer", "masks" (null without masks), "failures"}
nlohmann::json pair_to_json(const PairResult& r, const std::string& pred, const std::string& gt);
// {"pairs", "articulation", "reconstruction", "template", "mask"}; a figure
// with nothing behind it is null.
nlohmann::json aggregate_to_json(const Aggregate& a);

// Per joint, function and part of one pair.
std::string pair_to_text(const PairResult& r, const std::string& pred, const std::string& gt);
// The paper's tables.
std::string aggregate_to_text(const Aggregate& a);

}  // namespace efc::eval
