// efc replay SPEC --profile P --duration S [--dt D] --csv FILE: the function
// templates over a profile with no simulator (runtime/efc_replay.h): ideal
// joints, measured = the effect's state. The same log, byte for byte, as
// `python3 efc_templates.py <name>_functions.json` of a Python target.
#include <filesystem>

#include "backends/common/lowering.h"
#include "cli/commands.h"
#include "cli/spec_text.h"

namespace efc {

int cmd_replay(Report& report, const ReplayArgs& args) {
  Profile profile;
  int rc = kExitOk;
  std::optional<Object> obj = load_for_run(report, args.spec, args.profile, args.duration, args.dt, &profile, &rc);
  if (!obj) return rc;
  const lowering::ReplayModel model = lowering::replay_model(*obj);
  if (profile.kind == Profile::Kind::Csv)
    for (const ReplayJoint& j : model.joints)
      if (j.profile_driven && !profile.csv_parts.count(j.name))
        report.diags().warning("W0902", profile.csv_path, 1, 1, "",
                               "profile CSV has no column for receptor '" + j.name +
                                   "'; it holds its initial position");
  report.flush();
  const ReplayLog log = replay_templates(model.joints, model.functions, profile, args.duration, args.dt);
  std::string error;
  if (!write_atomically(args.csv, replay_csv(log), &error)) return report.fail("E0900", error, kExitUsage);
  return kExitOk;
}

}  // namespace efc
