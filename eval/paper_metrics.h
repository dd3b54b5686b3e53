// The EgoFun3D paper's metrics for one predicted spec against the true one
// (evaluate_pair) and over many pairs (aggregate): articulation (type, axis,
// origin), reconstruction (Chamfer), function templates (effect, mapping,
// both) and, when masks are given, mask IoU with its gating of templates.
// Everything is compared in the world frame, at the reference configuration
// (every joint at position 0, where spec v1 places geometry).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eval/axis_metrics.h"
#include "eval/eval_spec.h"
#include "eval/mask_iou.h"

namespace efc::eval {

struct EvalOptions {
  int chamfer_points = 2000;  // per surface
  uint64_t seed = 1;          // the sampler's: the same for both specs, so equal parts score exactly 0
};

struct JointResult {
  std::string part;  // the true part
  JointScore score;
};

struct FunctionResult {
  std::string name;               // the true function
  std::string receptor, effector; // its true parts (for mask gating)
  bool effect_correct = false, mapping_correct = false;
  // Receptor and effector masks both succeed; true without mask data (a part
  // with no true masks gates nothing).
  bool masks_ok = true;
  bool correct() const { return effect_correct && mapping_correct; }
};

struct ChamferResult {
  std::string part;            // the true part
  std::optional<double> cd_m2; // none: no predicted part to compare
};

struct PairResult {
  bool prediction_loaded = false;
  std::string prediction_problem;        // why not, one line
  std::vector<std::string> matched_part; // per true part: the predicted part's name, "" for none
  std::vector<JointResult> joints;       // every movable joint of the truth
  // The truth's fixed parts (a joint that does not move; not the root), and
  // those of them whose predicted part moves: the paper's type accuracy
  // scores the truth's movable joints only, so a spout or a lamp that the
  // prediction lets slide or turn is counted here instead.
  int fixed_parts = 0;
  std::vector<std::string> spurious_joints;
  std::vector<FunctionResult> functions; // every function of the truth
  std::vector<ChamferResult> chamfer;    // every part of the truth
  std::optional<std::vector<MaskScore>> masks;  // none: no masks given

  int failures() const;  // joints scored as failures
};

// pred null: a failed prediction (every joint and function scored a failure).
PairResult evaluate_pair(const PlacedSpec& gt, const PlacedSpec* pred, const EvalOptions& options);

// Scores the masks of every true part that has them (see score_part_masks),
// then gates the templates on them. False after a located error in diags.
bool add_mask_scores(const seq::Sequence& truth, const std::string& pred_masks_dir, Diagnostics& diags,
                     PairResult* result);

// The paper's tables over many pairs: joints, parts and functions pooled.
// A figure with nothing to average is none.
struct Aggregate {
  bool masks_given = false;  // some pair had masks: the gated figures and the mask table mean something
  int pairs = 0, joints = 0, failed_joints = 0, functions = 0, chamfer_parts = 0, mask_parts = 0;
  int fixed_parts = 0, spurious_joints = 0;      // PairResult's, pooled
  std::optional<double> spurious_joint_rate_pct;  // spurious_joints / fixed_parts
  std::optional<double> type_accuracy_pct, axis_error_rad_mean, origin_error_m_mean, failure_rate_pct;
  std::optional<double> chamfer_m2_median, chamfer_m2_mean;
  // Raw: every function; gated: correct only where both masks succeed.
  std::optional<double> effect_accuracy_pct, mapping_accuracy_pct, overall_accuracy_pct;
  std::optional<double> gated_effect_accuracy_pct, gated_mapping_accuracy_pct, gated_overall_accuracy_pct;
  std::optional<double> mask_mean_iou, mask_success_rate_pct;
};
Aggregate aggregate(const std::vector<PairResult>& pairs);

}  // namespace efc::eval
