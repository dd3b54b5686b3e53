#include "eval/eval_report.h"

#include <cstdio>

namespace efc::eval {

namespace {

nlohmann::json number_or_null(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }

// "12.3450" or "-" for a figure with nothing behind it.
std::string figure(const std::optional<double>& v, const char* format) {
  if (!v) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, *v);
  return buf;
}

std::string row(const std::vector<std::string>& cells, const std::vector<int>& widths) {
  std::string out = " ";
  for (size_t i = 0; i < cells.size(); ++i) {
    std::string cell = cells[i];
    if (i + 1 < cells.size() && cell.size() < static_cast<size_t>(widths[i])) cell.resize(widths[i], ' ');
    out += " " + cell;
  }
  return out + "\n";
}

const char* yes_no(bool b) { return b ? "yes" : "no"; }

// "1 pair", "3 pairs".
std::string count(size_t n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

}  // namespace

nlohmann::json pair_to_json(const PairResult& r, const std::string& pred, const std::string& gt) {
  nlohmann::json j = {{"pred", pred}, {"gt", gt}, {"prediction_loaded", r.prediction_loaded}};
  if (!r.prediction_loaded) j["prediction_problem"] = r.prediction_problem;
  j["joints"] = nlohmann::json::array();
  for (const JointResult& jr : r.joints)
    j["joints"].push_back({{"part", jr.part},
                           {"type_correct", jr.score.type_correct},
                           {"axis_error_rad", jr.score.axis_error_rad},
                           {"origin_error_m", jr.score.origin_error_m},
                           {"failed", jr.score.failed}});
  j["fixed_parts"] = r.fixed_parts;
  j["spurious_joints"] = r.spurious_joints;
  j["functions"] = nlohmann::json::array();
  for (const FunctionResult& f : r.functions)
    j["functions"].push_back({{"name", f.name},
                              {"effect_correct", f.effect_correct},
                              {"mapping_correct", f.mapping_correct},
                              {"correct", f.correct()},
                              {"masks_ok", f.masks_ok}});
  j["chamfer"] = nlohmann::json::array();
  for (const ChamferResult& c : r.chamfer) j["chamfer"].push_back({{"part", c.part}, {"cd_m2", number_or_null(c.cd_m2)}});
  j["masks"] = nullptr;
  if (r.masks) {
    j["masks"] = nlohmann::json::array();
    for (const MaskScore& m : *r.masks)
      j["masks"].push_back({{"part", m.part}, {"mean_iou", m.mean_iou}, {"success", m.success()}});
  }
  j["failures"] = r.failures();
  return j;
}

nlohmann::json aggregate_to_json(const Aggregate& a) {
  nlohmann::json j;
  j["pairs"] = a.pairs;
  j["articulation"] = {{"joints", a.joints},
                       {"failed_joints", a.failed_joints},
                       {"type_accuracy_pct", number_or_null(a.type_accuracy_pct)},
                       {"axis_error_rad_mean", number_or_null(a.axis_error_rad_mean)},
                       {"origin_error_m_mean", number_or_null(a.origin_error_m_mean)},
                       {"failure_rate_pct", number_or_null(a.failure_rate_pct)},
                       {"fixed_parts", a.fixed_parts},
                       {"spurious_joints", a.spurious_joints},
                       {"spurious_joint_rate_pct", number_or_null(a.spurious_joint_rate_pct)}};
  j["reconstruction"] = {{"parts", a.chamfer_parts},
                         {"chamfer_m2_median", number_or_null(a.chamfer_m2_median)},
                         {"chamfer_m2_mean", number_or_null(a.chamfer_m2_mean)}};
  j["template"] = {{"functions", a.functions},
                   {"effect_accuracy_pct", number_or_null(a.effect_accuracy_pct)},
                   {"mapping_accuracy_pct", number_or_null(a.mapping_accuracy_pct)},
                   {"overall_accuracy_pct", number_or_null(a.overall_accuracy_pct)},
                   {"gated", nullptr}};
  j["mask"] = nullptr;
  if (a.masks_given) {
    j["template"]["gated"] = {{"effect_accuracy_pct", number_or_null(a.gated_effect_accuracy_pct)},
                              {"mapping_accuracy_pct", number_or_null(a.gated_mapping_accuracy_pct)},
                              {"overall_accuracy_pct", number_or_null(a.gated_overall_accuracy_pct)}};
    j["mask"] = {{"parts", a.mask_parts},
                 {"mean_iou", number_or_null(a.mask_mean_iou)},
                 {"success_rate_pct", number_or_null(a.mask_success_rate_pct)}};
  }
  return j;
}

std::string pair_to_text(const PairResult& r, const std::string& pred, const std::string& gt) {
  std::string out = "prediction " + pred + " against truth " + gt + "\n";
  if (!r.prediction_loaded) out += "  failed prediction: " + r.prediction_problem + "\n";
  const std::vector<int> w{16, 8, 16, 16};
  out += "joints (" + std::to_string(r.joints.size()) + ", " + std::to_string(r.failures()) + " failed)\n";
  out += row({"part", "type", "axis error rad", "origin error m"}, w);
  for (const JointResult& j : r.joints)
    out += row({j.part, j.score.failed ? "failed" : j.score.type_correct ? "right" : "wrong",
                figure(j.score.axis_error_rad, "%.4f"), figure(j.score.origin_error_m, "%.4f")},
               w);
  out += "fixed parts (" + std::to_string(r.fixed_parts) + "), predicted movable: ";
  if (r.spurious_joints.empty()) out += "none";
  for (size_t i = 0; i < r.spurious_joints.size(); ++i) out += (i ? ", " : "") + r.spurious_joints[i];
  out += "\n";
  out += "functions (" + std::to_string(r.functions.size()) + ")\n";
  out += row({"name", "effect", "mapping", "both", "masks ok"}, {16, 8, 8, 8});
  for (const FunctionResult& f : r.functions)
    out += row({f.name, yes_no(f.effect_correct), yes_no(f.mapping_correct), yes_no(f.correct()),
                r.masks ? yes_no(f.masks_ok) : "-"},
               {16, 8, 8, 8});
  out += "chamfer (m^2)\n";
  for (const ChamferResult& c : r.chamfer) out += row({c.part, c.cd_m2 ? figure(c.cd_m2, "%.3g") : "no part"}, {16});
  if (!r.masks) {
    out += "masks: not given (no mask figures; templates not gated)\n";
  } else {
    out += "masks (mean IoU)\n";
    for (const MaskScore& m : *r.masks)
      out += row({m.part, figure(m.mean_iou, "%.3f"), m.success() ? "success" : "miss"}, {16, 8});
  }
  return out;
}

std::string aggregate_to_text(const Aggregate& a) {
  std::string out = "Articulation (" + count(a.joints, "joint") + ", " + count(a.pairs, "pair") + ")\n";
  out += row({"type acc %", "axis err rad", "origin err m", "failure rate %"}, {14, 14, 14});
  out += row({figure(a.type_accuracy_pct, "%.1f"), figure(a.axis_error_rad_mean, "%.4f"),
              figure(a.origin_error_m_mean, "%.4f"), figure(a.failure_rate_pct, "%.1f")},
             {14, 14, 14});
  out += "fixed parts predicted movable: " + std::to_string(a.spurious_joints) + " of " +
         std::to_string(a.fixed_parts) + " (" + figure(a.spurious_joint_rate_pct, "%.1f") + " %)\n";
  out += "Reconstruction (" + count(a.chamfer_parts, "part") + ")\n";
  out += row({"CD median m^2", "CD mean m^2"}, {14});
  out += row({figure(a.chamfer_m2_median, "%.3g"), figure(a.chamfer_m2_mean, "%.3g")}, {14});
  out += "Template (" + count(a.functions, "function") + ")\n";
  out += row({"", "effect %", "mapping %", "overall %"}, {8, 14, 14});
  out += row({"raw", figure(a.effect_accuracy_pct, "%.1f"), figure(a.mapping_accuracy_pct, "%.1f"),
              figure(a.overall_accuracy_pct, "%.1f")},
             {8, 14, 14});
  if (a.masks_given) {
    out += row({"gated", figure(a.gated_effect_accuracy_pct, "%.1f"), figure(a.gated_mapping_accuracy_pct, "%.1f"),
                figure(a.gated_overall_accuracy_pct, "%.1f")},
               {8, 14, 14});
    out += "Mask (" + count(a.mask_parts, "part") + ")\n";
    out += row({"mean IoU", "success rate %"}, {14});
    out += row({figure(a.mask_mean_iou, "%.3f"), figure(a.mask_success_rate_pct, "%.1f")}, {14});
  } else {
    out += "Mask: not given (no mask figures; templates not gated)\n";
  }
  return out;
}

}  // namespace efc::eval
