// Spec v1 MAPPING and EFFECT objects from a fitted model: receptor units for
// thresholds and gains, the spec's default ranges where pixels cannot
// measure units (lumens, degrees, litres per minute, metres per second), the
// effector's joint units for geometry. Every value obeys the compiler's type
// rules (thresholds inside the receptor range, finite non-zero gains and
// deltas, two different range ends, geometry inside the effector's range).
#pragma once

#include <Eigen/Geometry>

#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/templates/mapping_fit.h"
#include "pipeline/templates/template_input.h"

namespace efc::pipeline {

// Where the effect's quantity sits, as measured.
struct EffectEstimate {
  std::string type;  // geometry, illumination, temperature, fluid, airflow
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // light, heat, emitter, outlet (object frame)
  Eigen::Vector3d direction = Eigen::Vector3d(0, 0, -1);  // emitter, outlet
  bool has_position = false;
};

struct TemplateJson {
  nlohmann::json mapping, effect;
  nlohmann::json notes = nlohmann::json::object();  // the estimates behind them
};

// `receptor`, `effector`: the parts; `fit`: the chosen model (signal units:
// y = a + b u); `dt`: seconds per frame.
TemplateJson template_json(const MappingModel& fit, const EffectEstimate& effect, const PartObservation& receptor,
                           const PartObservation* effector, double dt);

// Receptor range as the mapping sees it: the joint's, or one turn for a
// continuous joint (or a joint without a range).
void receptor_range(const PartObservation& p, double* lo, double* hi);

}  // namespace efc::pipeline
