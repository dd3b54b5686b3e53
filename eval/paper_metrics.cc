#include "eval/paper_metrics.h"

#include <algorithm>
#include <cmath>

#include "eval/chamfer.h"
#include "eval/part_matching.h"
#include "eval/surface_sampling.h"

namespace efc::eval {

namespace {

AxisLine world_axis(const Joint& j, const WorldFrame& world) {
  return {world.point(j.origin), world.direction(j.axis)};
}

std::vector<Vec3> world_surface(const Part& p, const WorldFrame& world, const EvalOptions& options) {
  std::vector<Vec3> points = sample_surface(p.geometry, options.chamfer_points, options.seed);
  for (Vec3& q : points) q = world.point(q);
  return points;
}

// The predicted function standing for gt's f: the same name, else the one
// joining the predicted receptor and effector matched to f's.
const Function* match_function(const Function& f, const Object& gt, const Object& pred,
                               const std::vector<std::string>& matched_part) {
  for (const Function& p : pred.functions)
    if (p.name == f.name) return &p;
  const std::string& receptor = matched_part[gt.find_part(f.receptor)];
  const std::string& effector = matched_part[gt.find_part(f.effector)];
  if (receptor.empty() || effector.empty()) return nullptr;
  for (const Function& p : pred.functions)
    if (p.receptor == receptor && p.effector == effector) return &p;
  return nullptr;
}

// The predicted part matched to true part g, where it has a joint that moves.
const Part* moving_prediction(const PlacedSpec* pred, const PairResult& r, size_t g) {
  if (!pred || r.matched_part[g].empty()) return nullptr;
  const Part& pp = pred->object.parts[pred->object.find_part(r.matched_part[g])];
  return pp.joint && pp.joint->movable() ? &pp : nullptr;
}

void score_joints(const PlacedSpec& gt, const PlacedSpec* pred, PairResult* r) {
  for (size_t g = 0; g < gt.object.parts.size(); ++g) {
    const Part& part = gt.object.parts[g];
    if (!part.joint) continue;  // the root
    const Part* pp = moving_prediction(pred, *r, g);
    if (!part.joint->movable()) {
      ++r->fixed_parts;
      if (pp) r->spurious_joints.push_back(part.name);
      continue;
    }
    JointResult jr{part.name, JointScore{}};  // the failure values unless a movable prediction exists
    if (pp)
      jr.score = score_joint(pp->joint->type, world_axis(*pp->joint, pred->world), part.joint->type,
                             world_axis(*part.joint, gt.world));
    r->joints.push_back(jr);
  }
}

void score_functions(const PlacedSpec& gt, const PlacedSpec* pred, PairResult* r) {
  for (const Function& f : gt.object.functions) {
    FunctionResult fr;
    fr.name = f.name, fr.receptor = f.receptor, fr.effector = f.effector;
    if (const Function* p = pred ? match_function(f, gt.object, pred->object, r->matched_part) : nullptr) {
      fr.effect_correct = p->effect.type == f.effect.type;
      fr.mapping_correct = p->mapping.type == f.mapping.type;
    }
    r->functions.push_back(fr);
  }
}

void score_surfaces(const PlacedSpec& gt, const PlacedSpec* pred, const EvalOptions& options, PairResult* r) {
  for (size_t g = 0; g < gt.object.parts.size(); ++g) {
    const Part& part = gt.object.parts[g];
    ChamferResult cr{part.name, std::nullopt};
    if (pred && !r->matched_part[g].empty()) {
      const Part& pp = pred->object.parts[pred->object.find_part(r->matched_part[g])];
      const double cd = chamfer_distance(world_surface(part, gt.world, options),
                                         world_surface(pp, pred->world, options));
      if (std::isfinite(cd)) cr.cd_m2 = cd;
    }
    r->chamfer.push_back(cr);
  }
}

std::optional<double> ratio_pct(int hits, int total) {
  if (total == 0) return std::nullopt;
  return 100.0 * hits / total;
}

std::optional<double> mean(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

std::optional<double> median(std::vector<double> v) {
  if (v.empty()) return std::nullopt;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

}  // namespace

int PairResult::failures() const {
  return static_cast<int>(std::count_if(joints.begin(), joints.end(), [](const JointResult& j) { return j.score.failed; }));
}

PairResult evaluate_pair(const PlacedSpec& gt, const PlacedSpec* pred, const EvalOptions& options) {
  PairResult r;
  r.prediction_loaded = pred != nullptr;
  r.matched_part.assign(gt.object.parts.size(), "");
  if (pred) {
    const std::vector<int> match = match_parts(gt.object, gt.world, pred->object, pred->world);
    for (size_t g = 0; g < match.size(); ++g)
      if (match[g] >= 0) r.matched_part[g] = pred->object.parts[match[g]].name;
  }
  score_joints(gt, pred, &r);
  score_functions(gt, pred, &r);
  score_surfaces(gt, pred, options, &r);
  return r;
}

bool add_mask_scores(const seq::Sequence& truth, const std::string& pred_masks_dir, Diagnostics& diags,
                     PairResult* result) {
  std::vector<MaskScore> scores;
  for (size_t g = 0; g < result->chamfer.size(); ++g) {  // chamfer lists every true part, in order
    bool has_truth = false;
    MaskScore s;
    if (!score_part_masks(truth, result->chamfer[g].part, pred_masks_dir, result->matched_part[g], diags,
                          &has_truth, &s))
      return false;
    if (has_truth) scores.push_back(s);
  }
  auto succeeds = [&scores](const std::string& part) {
    for (const MaskScore& s : scores)
      if (s.part == part) return s.success();
    return true;  // no true masks: nothing to gate on
  };
  for (FunctionResult& f : result->functions) f.masks_ok = succeeds(f.receptor) && succeeds(f.effector);
  result->masks = std::move(scores);
  return true;
}

Aggregate aggregate(const std::vector<PairResult>& pairs) {
  Aggregate a;
  a.pairs = static_cast<int>(pairs.size());
  int type_hits = 0, effect = 0, mapping = 0, overall = 0, g_effect = 0, g_mapping = 0, g_overall = 0,
      mask_hits = 0;
  std::vector<double> axis, origin, chamfer, iou;
  for (const PairResult& p : pairs) {
    for (const JointResult& j : p.joints) {
      ++a.joints;
      a.failed_joints += j.score.failed;
      type_hits += j.score.type_correct;
      axis.push_back(j.score.axis_error_rad);
      origin.push_back(j.score.origin_error_m);
    }
    a.fixed_parts += p.fixed_parts;
    a.spurious_joints += static_cast<int>(p.spurious_joints.size());
    for (const FunctionResult& f : p.functions) {
      ++a.functions;
      effect += f.effect_correct, mapping += f.mapping_correct, overall += f.correct();
      g_effect += f.effect_correct && f.masks_ok, g_mapping += f.mapping_correct && f.masks_ok,
          g_overall += f.correct() && f.masks_ok;
    }
    for (const ChamferResult& c : p.chamfer)
      if (c.cd_m2) chamfer.push_back(*c.cd_m2);
    a.masks_given = a.masks_given || p.masks.has_value();
    if (p.masks)
      for (const MaskScore& m : *p.masks) {
        ++a.mask_parts;
        mask_hits += m.success();
        iou.push_back(m.mean_iou);
      }
  }
  a.chamfer_parts = static_cast<int>(chamfer.size());
  a.type_accuracy_pct = ratio_pct(type_hits, a.joints);
  a.axis_error_rad_mean = mean(axis);
  a.origin_error_m_mean = mean(origin);
  a.failure_rate_pct = ratio_pct(a.failed_joints, a.joints);
  a.spurious_joint_rate_pct = ratio_pct(a.spurious_joints, a.fixed_parts);
  a.chamfer_m2_median = median(chamfer);
  a.chamfer_m2_mean = mean(chamfer);
  a.effect_accuracy_pct = ratio_pct(effect, a.functions);
  a.mapping_accuracy_pct = ratio_pct(mapping, a.functions);
  a.overall_accuracy_pct = ratio_pct(overall, a.functions);
  a.gated_effect_accuracy_pct = ratio_pct(g_effect, a.functions);
  a.gated_mapping_accuracy_pct = ratio_pct(g_mapping, a.functions);
  a.gated_overall_accuracy_pct = ratio_pct(g_overall, a.functions);
  a.mask_mean_iou = mean(iou);
  a.mask_success_rate_pct = ratio_pct(mask_hits, a.mask_parts);
  return a;
}

}  // namespace efc::eval
