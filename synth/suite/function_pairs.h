// The vocabulary the suite covers: spec v1's 4 mappings x 5 effects (the
// paper's function templates) and the three movable receptor joint types.
#pragma once

#include <string>
#include <vector>

namespace efc::synth::suite {

struct FunctionPair {
  std::string mapping;  // binary, step, linear, cumulative
  std::string effect;   // geometry, illumination, temperature, fluid, airflow
  bool operator==(const FunctionPair& o) const {
    return mapping == o.mapping && effect == o.effect;
  }
};

// The 20 pairs, mapping-major, in spec order.
const std::vector<FunctionPair>& all_function_pairs();

// revolute, prismatic, continuous.
const std::vector<std::string>& receptor_joint_types();

// Whether the suite gives a continuous receptor this mapping. A continuous
// joint has no range, so the spec wants an explicit threshold or gain; a
// hand-wheel or encoder that sets a level (linear), switches past an angle
// (step) or counts turns (cumulative) is a real device, while a plain binary
// switch without end stops is not, so binary receptors are bounded.
bool continuous_receptor_allowed(const std::string& mapping);

}  // namespace efc::synth::suite
