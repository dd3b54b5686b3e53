#include "synth/suite/function_pairs.h"

namespace efc::synth::suite {

const std::vector<FunctionPair>& all_function_pairs() {
  static const std::vector<FunctionPair> kPairs = [] {
    std::vector<FunctionPair> pairs;
    for (const char* m : {"binary", "step", "linear", "cumulative"})
      for (const char* e : {"geometry", "illumination", "temperature", "fluid", "airflow"})
        pairs.push_back({m, e});
    return pairs;
  }();
  return kPairs;
}

const std::vector<std::string>& receptor_joint_types() {
  static const std::vector<std::string> kTypes = {"revolute", "prismatic", "continuous"};
  return kTypes;
}

bool continuous_receptor_allowed(const std::string& mapping) { return mapping != "binary"; }

}  // namespace efc::synth::suite
