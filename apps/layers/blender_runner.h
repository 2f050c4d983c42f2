// apps/layers/blender_runner.h -- finding Debian's `blender` and running
// the embedded scripts/blender/crosscheck_sim.py in it (`layers crosscheck`).
#pragma once

#include <string>

#include "child_command.h"

namespace layers::app {

// The script's text, compiled in from scripts/blender/crosscheck_sim.py
// (crosscheck_script.cpp.in), so a clone or an install anywhere runs the
// script it was built with.
extern const char* const kCrosscheckScript;

// `explicit_path` when given (InputError unless it is an executable
// file), else $LAYERS_BLENDER, else `blender` on PATH; InputError with an
// install hint when there is none.
std::string find_blender(const std::string& explicit_path);

// Runs `blender -b -t <threads> --factory-startup --python script --
// <args>` with its output in `log`; returns the exit status (-1 when it
// did not exit normally).
int run_blender(const std::string& blender, int threads, const std::string& script, const std::string& args,
                const std::string& log);

// The line of `log` that says why a run failed: the script's
// "crosscheck_sim: error" line, else Blender's last "Error" line, else the
// last non-empty line.
std::string blender_failure(const std::string& log);

}  // namespace layers::app
