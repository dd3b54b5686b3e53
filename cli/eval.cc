// efc eval: the EgoFun3D paper's metrics (eval/README.md) for one predicted
// spec against the true one (--pred P --gt G), or aggregated over the pairs of
// a list file (--list PAIRS, or an efc batch's results.jsonl). Tables or one
// JSON object on stdout; every problem on stderr. A missing or broken
// prediction is scored, not an error.
#include <filesystem>
#include <iostream>

#include "cli/commands.h"
#include "eval/batch_results.h"
#include "eval/eval_report.h"
#include "eval/pair_list.h"
#include "eval/paper_metrics.h"

namespace efc {
namespace {

// One pair scored; nullopt with *rc (1 bad input, 2 unreadable) when the
// truth, its sequence or a predicted mask is wrong. `where` prefixes notes
// ("PAIRS:3: " for a list's line).
std::optional<eval::PairResult> evaluate_one(Report& report, const eval::PairEntry& pair, const std::string& where,
                                             int* rc) {
  const bool allow_abs = report.options().allow_absolute_paths;
  bool io_error = false;
  const std::optional<eval::PlacedSpec> gt = eval::load_truth(pair.gt, allow_abs, report.diags(), &io_error);
  report.flush();
  if (!gt) {
    *rc = io_error ? kExitUsage : kExitBadInput;
    return std::nullopt;
  }
  std::string why = pair.failure;
  const std::optional<eval::PlacedSpec> pred =
      pair.failure.empty() ? eval::load_prediction(pair.pred, allow_abs, &why) : std::nullopt;
  if (!pred) report.note(where + "failed prediction, scored as such: " + why);
  eval::PairResult result = eval::evaluate_pair(*gt, pred ? &*pred : nullptr, eval::EvalOptions{});
  if (!pred) result.prediction_problem = why;
  if (pair.gt_seq.empty()) return result;

  seq::Sequence truth;
  const bool masks_ok = truth.open(pair.gt_seq, report.diags()) &&
                        eval::add_mask_scores(truth, pair.pred_masks, report.diags(), &result);
  report.flush();
  if (!masks_ok) {
    *rc = kExitBadInput;
    return std::nullopt;
  }
  std::error_code ec;
  if (!std::filesystem::is_directory(pair.pred_masks, ec))
    report.note(where + "no predicted masks in " + pair.pred_masks + ": every predicted mask is empty");
  return result;
}

int check_usage(Report& report, const EvalArgs& args) {
  const bool single = !args.pred.empty() || !args.gt.empty();
  if (single == !args.list.empty())
    return report.fail("E0910", "give either --pred P --gt G or --list PAIRS", kExitUsage, "see efc eval --help");
  if (single && (args.pred.empty() || args.gt.empty()))
    return report.fail("E0910", "--pred and --gt go together", kExitUsage, "see efc eval --help");
  if (args.pred_masks.empty() != args.gt_seq.empty())
    return report.fail("E0910", "--pred-masks and --gt-seq go together", kExitUsage, "see efc eval --help");
  if (!args.list.empty() && !args.gt_seq.empty())
    return report.fail("E0910", "with --list, masks are the list's third and fourth columns", kExitUsage,
                       "write PRED GT PRED_MASKS GT_SEQ lines");
  return kExitOk;
}

int eval_single(Report& report, const EvalArgs& args) {
  int rc = kExitOk;
  const eval::PairEntry pair{args.pred, args.gt, args.pred_masks, args.gt_seq, 0, ""};
  const std::optional<eval::PairResult> r = evaluate_one(report, pair, "", &rc);
  if (!r) return rc;
  if (args.json)
    std::cout << eval::pair_to_json(*r, args.pred, args.gt).dump(2) << "\n";
  else
    std::cout << eval::pair_to_text(*r, args.pred, args.gt) << "\n" << eval::aggregate_to_text(eval::aggregate({*r}));
  return kExitOk;
}

// Every pair is scored and every problem reported; nothing is printed on
// stdout unless all were good (half a table would pass for a whole one).
int eval_list(Report& report, const EvalArgs& args) {
  std::vector<eval::PairEntry> pairs;
  bool io_error = false;
  // An efc batch's results (DIR or DIR/results.jsonl), or a PAIRS file.
  std::string list = args.list;
  const bool read = eval::is_batch_results(args.list)
                        ? eval::read_batch_results(args.list, report.diags(), &pairs, &io_error, &list)
                        : eval::read_pair_list(args.list, report.diags(), &pairs, &io_error);
  report.flush();
  if (!read) return io_error ? kExitUsage : kExitBadInput;
  int worst = kExitOk;
  std::vector<eval::PairResult> results;
  for (const eval::PairEntry& pair : pairs) {
    int rc = kExitOk;
    std::optional<eval::PairResult> r =
        evaluate_one(report, pair, list + ":" + std::to_string(pair.line) + ": ", &rc);
    if (r)
      results.push_back(std::move(*r));
    else
      worst = std::max(worst, rc);
  }
  if (worst != kExitOk) return worst;
  const eval::Aggregate total = eval::aggregate(results);
  if (args.json) {
    nlohmann::json out = {{"pairs", nlohmann::json::array()}, {"aggregate", eval::aggregate_to_json(total)}};
    for (size_t i = 0; i < results.size(); ++i)
      out["pairs"].push_back(eval::pair_to_json(results[i], pairs[i].pred, pairs[i].gt));
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << eval::aggregate_to_text(total);
  }
  return kExitOk;
}

}  // namespace

int cmd_eval(Report& report, const EvalArgs& args) {
  if (const int rc = check_usage(report, args)) return rc;
  return args.list.empty() ? eval_single(report, args) : eval_list(report, args);
}

}  // namespace efc
