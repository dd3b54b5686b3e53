// The frames shown to the vision-language model: before and after the
// actuation (the receptor at its lowest and highest observed state, and the
// last frame), the receptor's pixels tinted green and the effector's
// magenta, as PNG bytes. Frames that cannot be read are left out.
#pragma once

#include <string>
#include <vector>

#include "pipeline/templates/template_input.h"

namespace efc::pipeline {

std::vector<std::string> vlm_frames(const TemplateInput& input, const std::string& receptor,
                                    const std::string& effector, const std::vector<double>& s_R);

}  // namespace efc::pipeline
