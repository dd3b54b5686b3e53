// The resolved IR as JSON (`efc check --dump-ir`): every filled default visible.
#pragma once

#include <nlohmann/json.hpp>

#include "compiler/ir.h"

namespace efc {

nlohmann::json ir_to_json(const Object& obj);

}  // namespace efc
