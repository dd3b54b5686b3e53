#include "compiler/ir.h"

namespace efc {

const char* to_string(GeomKind k) {
  switch (k) {
    case GeomKind::Mesh: return "mesh";
    case GeomKind::Box: return "box";
    case GeomKind::Cylinder: return "cylinder";
    case GeomKind::Sphere: return "sphere";
    case GeomKind::Compound: return "compound";
  }
  return "?";
}

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Fixed: return "fixed";
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
  }
  return "?";
}

const char* to_string(PartRole r) {
  switch (r) {
    case PartRole::Base: return "base";
    case PartRole::Receptor: return "receptor";
    case PartRole::Effector: return "effector";
    case PartRole::Other: return "other";
  }
  return "?";
}

const char* to_string(MappingType t) {
  switch (t) {
    case MappingType::Binary: return "binary";
    case MappingType::Step: return "step";
    case MappingType::Linear: return "linear";
    case MappingType::Cumulative: return "cumulative";
  }
  return "?";
}

const char* to_string(EffectType t) {
  switch (t) {
    case EffectType::Geometry: return "geometry";
    case EffectType::Illumination: return "illumination";
    case EffectType::Temperature: return "temperature";
    case EffectType::Fluid: return "fluid";
    case EffectType::Airflow: return "airflow";
  }
  return "?";
}

}  // namespace efc
