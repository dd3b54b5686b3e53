// The command every job runs (what follows `--`): which efc commands batch
// can run, and each job's command line
//   EFC NAME PATH OPTIONS... LINE-ARGS... [-o DIR/jobs/ID]
// The path goes right after the command's name: an option that takes several
// values (compile's --target) would swallow a path that followed it. So
// `-- compile --target all` and a line `lamp.json` make
// `efc compile /abs/lamp.json --target all -o DIR/jobs/00001-lamp`.
#pragma once

#include <string>
#include <vector>

#include "batch/manifest.h"
#include "compiler/diagnostics.h"

namespace efc::batch {

// Folder: the command writes a folder given by -o (compile, synth, infer,
// synth-suite, import-egofun3d), which batch sets to the job's folder. None:
// it writes no folder of its own (check, play, replay, convert, ...); it
// still runs inside its job folder, so a relative output path on its line
// (play --csv log.csv) lands there.
enum class OutputKind { Folder, None };

// False with *why when `command` is empty, does not start with an efc
// command (or is `batch` itself), or gives -o/--output where batch gives it.
bool check_command(const std::vector<std::string>& command, OutputKind* kind, std::string* why);

// Whether `arg` sets the output (-o X, -oX, --output X, --output=X).
bool is_output_flag(const std::string& arg);

// E1100 at MANIFEST:LINE:COL for each line argument that sets the output when
// batch sets it (Folder commands). False if there was any.
bool check_line_args(const std::vector<Job>& jobs, OutputKind kind, const std::string& manifest, Diagnostics& diags);

// The job's argv: efc_exe, the command's name, the job's path, the rest of
// the command, the line's arguments, and -o job_dir for Folder commands.
std::vector<std::string> job_argv(const std::string& efc_exe, const std::vector<std::string>& command, const Job& job,
                                  OutputKind kind, const std::string& job_dir);

}  // namespace efc::batch
