#include "pipeline/egofun3d/annotations.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "pipeline/egofun3d/dataset_index.h"

namespace efc::egofun3d {
namespace {

constexpr const char* kCode = "E1046";
constexpr double kPi = 3.14159265358979323846;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The list of items and the pointer prefix; an object keyed by id (the
// compile scripts' variant) is read as its values.
std::vector<std::pair<std::string, const nlohmann::json*>> items(const nlohmann::json& root) {
  std::vector<std::pair<std::string, const nlohmann::json*>> out;
  if (root.is_array())
    for (size_t i = 0; i < root.size(); ++i) out.push_back({pointer_join("", i), &root[i]});
  else if (root.is_object())
    for (auto it = root.begin(); it != root.end(); ++it) out.push_back({pointer_join("", it.key()), &it.value()});
  return out;
}

bool read_part(const JsonDoc& doc, Diagnostics& diags, const std::string& pointer, const char* role,
               long long vertex_count, PartAnnotation* out) {
  const std::string p = pointer_join(pointer, role);
  if (!doc.member(diags, kCode, pointer, role)) return false;
  out->pointer = p;
  const size_t before = diags.error_count();
  out->label = doc.string(diags, kCode, p, "label").value_or("");
  if (const nlohmann::json* pid = doc.member(diags, kCode, p, "pid")) out->pid = *pid;
  if (const nlohmann::json* idx = doc.member(diags, kCode, p, "indices")) {
    if (!idx->is_array() || idx->empty()) {
      doc.error(diags, kCode, pointer_join(p, "indices"),
                std::string("the ") + role + "'s \"indices\" must be a non-empty list of vertex indices");
    } else {
      for (size_t i = 0; i < idx->size(); ++i) {
        if (!(*idx)[i].is_number_integer() || (*idx)[i].get<long long>() < 0) {
          doc.error(diags, kCode, pointer_join(pointer_join(p, "indices"), i), "not a vertex index (an integer >= 0)");
          break;
        }
        if (vertex_count >= 0 && (*idx)[i].get<long long>() >= vertex_count) {
          doc.error(diags, kCode, pointer_join(pointer_join(p, "indices"), i),
                    "vertex index " + std::to_string((*idx)[i].get<long long>()) + " is past the geometry's " +
                        std::to_string(vertex_count) + " vertices",
                    "the indices must refer to the PLY named by geometry_path");
          break;
        }
        out->indices.push_back((*idx)[i].get<long long>());
      }
    }
  }
  return diags.error_count() == before;
}

std::optional<std::array<double, 3>> vec3(const JsonDoc& doc, Diagnostics& diags, const std::string& p,
                                          const std::string& key) {
  auto v = doc.numbers(diags, kCode, p, key, 3);
  if (!v) return std::nullopt;
  return std::array<double, 3>{(*v)[0], (*v)[1], (*v)[2]};
}

bool read_joint(const JsonDoc& doc, Diagnostics& diags, const std::string& p, JointAnnotation* out) {
  const size_t before = diags.error_count();
  out->found = true;
  out->file = doc.file();
  out->pointer = p;
  const std::string type = lower(doc.string(diags, kCode, p, "type").value_or(""));
  if (type == "revolute" || type == "rotation" || type == "rotational" || type == "hinge" || type == "rotate")
    out->type = "revolute";
  else if (type == "prismatic" || type == "translation" || type == "translational" || type == "slider" ||
           type == "slide")
    out->type = "prismatic";
  else if (type == "continuous")
    out->type = "continuous";
  else if (type == "fixed" || type == "static" || type == "none")
    out->type = "fixed";
  else if (diags.error_count() == before)
    doc.error(diags, kCode, pointer_join(p, "type"),
              "joint type '" + type + "' is unknown: expected revolute, prismatic, continuous or fixed");
  if (out->type == "fixed" || out->type.empty()) return diags.error_count() == before;
  if (auto a = vec3(doc, diags, p, "axis")) {
    const double n = std::sqrt((*a)[0] * (*a)[0] + (*a)[1] * (*a)[1] + (*a)[2] * (*a)[2]);
    if (!(n > 1e-9))
      doc.error(diags, kCode, pointer_join(p, "axis"), "the joint axis is zero");
    else
      out->axis = {(*a)[0] / n, (*a)[1] / n, (*a)[2] / n};
  }
  if (out->type != "prismatic") {
    if (auto o = vec3(doc, diags, p, "origin")) out->origin = *o;
  }
  if (out->type == "continuous") return diags.error_count() == before;
  const auto lo = doc.number(diags, kCode, p, "rangeMin");
  const auto hi = doc.number(diags, kCode, p, "rangeMax");
  if (!lo || !hi) return false;
  out->lo = *lo;
  out->hi = *hi;
  // Angles are radians in the spec. An annotation beyond a full turn can
  // only be degrees (the annotation tools offer both); read it as such.
  if (out->type == "revolute" && std::max(std::fabs(out->lo), std::fabs(out->hi)) > 2 * kPi + 1e-6) {
    out->lo *= kPi / 180;
    out->hi *= kPi / 180;
    out->degrees = true;
  }
  if (!(out->lo < out->hi))
    doc.error(diags, kCode, pointer_join(p, "rangeMax"),
              "the joint range [" + std::to_string(*lo) + ", " + std::to_string(*hi) + "] is not ordered (rangeMin < rangeMax)");
  return diags.error_count() == before;
}

}  // namespace

bool read_function_instance(const std::string& path, const nlohmann::json& id, long long vertex_count,
                            Diagnostics& diags, FunctionInstance* out) {
  *out = FunctionInstance{};
  out->file = path;
  JsonDoc doc;
  if (!doc.read(path, kCode, diags)) return false;
  const std::string want = id_text(id);
  const auto all = items(doc.root());
  if (!doc.root().is_array() && !doc.root().is_object()) {
    doc.error(diags, kCode, "", "the part annotation must be a list of function instances");
    return false;
  }
  const size_t before = diags.error_count();
  bool found = false;
  for (const auto& [p, item] : all) {
    if (!item->is_object()) continue;
    // List form: the item names its id; object form: the key is the id.
    std::string item_id;
    if (item->contains("function_instance_id"))
      item_id = id_text((*item)["function_instance_id"]);
    else if (doc.root().is_object())
      item_id = p.substr(1);
    if (doc.root().is_object() && p == "/remove") {
      if (const auto* r = item->contains("remove") ? &(*item)["remove"] : nullptr; r && r->contains("indices") &&
                                                                                   (*r)["indices"].is_array())
        for (const auto& v : (*r)["indices"])
          if (v.is_number_integer() && v.get<long long>() >= 0 && (vertex_count < 0 || v.get<long long>() < vertex_count))
            out->removed.push_back(v.get<long long>());
      continue;
    }
    if (item_id != want) continue;
    found = true;
    read_part(doc, diags, p, "receptor", vertex_count, &out->receptor);
    read_part(doc, diags, p, "effector", vertex_count, &out->effector);
    break;
  }
  if (!found)
    doc.error(diags, kCode, "", "no function instance with function_instance_id " + want,
              "dataset_metadata.json names this id for the video; the part annotation must hold it");
  return found && diags.error_count() == before;
}

bool read_articulations(const std::string& path, const nlohmann::json& receptor_pid,
                        const nlohmann::json& effector_pid, Diagnostics& diags, JointAnnotation* receptor,
                        JointAnnotation* effector) {
  *receptor = JointAnnotation{};
  *effector = JointAnnotation{};
  JsonDoc doc;
  if (!doc.read(path, kCode, diags)) return false;
  if (!doc.root().is_array()) {
    doc.error(diags, kCode, "", "the articulation file must be a list of {pid, type, axis, origin, rangeMin, rangeMax}");
    return false;
  }
  const size_t before = diags.error_count();
  const std::string r = id_text(receptor_pid), e = id_text(effector_pid);
  for (size_t i = 0; i < doc.root().size(); ++i) {
    const auto& item = doc.root()[i];
    if (!item.is_object() || !item.contains("pid")) continue;
    const std::string pid = id_text(item["pid"]);
    const std::string p = pointer_join("", i);
    if (pid == r && !receptor->found) read_joint(doc, diags, p, receptor);
    if (pid == e && !effector->found) read_joint(doc, diags, p, effector);
  }
  receptor->file = effector->file = path;
  return diags.error_count() == before;
}

bool read_function_annotation(const std::string& path, const nlohmann::json& id, Diagnostics& diags,
                              FunctionAnnotation* out) {
  *out = FunctionAnnotation{};
  JsonDoc doc;
  if (!doc.read(path, kCode, diags)) return false;
  const std::string want = id_text(id);
  const size_t before = diags.error_count();
  for (const auto& [p, item] : items(doc.root())) {
    if (!item->is_object()) continue;
    std::string item_id = item->contains("function_instance_id") ? id_text((*item)["function_instance_id"])
                          : doc.root().is_object()              ? p.substr(1)
                                                                : "";
    if (item_id != want) continue;
    out->physics = lower(doc.string(diags, kCode, p, "physics").value_or(""));
    out->func = lower(doc.string(diags, kCode, p, "func").value_or(""));
    if (diags.error_count() != before) return false;
    static const char* physics[] = {"geometry", "illumination", "temperature", "fluid", "airflow"};
    static const char* funcs[] = {"binary", "step", "linear", "cumulative"};
    if (std::none_of(std::begin(physics), std::end(physics), [&](const char* s) { return out->physics == s; }))
      doc.error(diags, kCode, pointer_join(p, "physics"),
                "physics '" + out->physics + "' is unknown: expected geometry, illumination, temperature or fluid");
    if (std::none_of(std::begin(funcs), std::end(funcs), [&](const char* s) { return out->func == s; }))
      doc.error(diags, kCode, pointer_join(p, "func"),
                "func '" + out->func + "' is unknown: expected binary, step, linear or cumulative");
    return diags.error_count() == before;
  }
  doc.error(diags, kCode, "", "no function annotation with function_instance_id " + want);
  return false;
}

}  // namespace efc::egofun3d
