// apps/layers/child_command.h -- running another program from the CLI
// with its output in a log file (Blender for `layers crosscheck`, a lane
// of `layers run --lanes`): /bin/sh quoting and one call that waits for it;
// and the path of this binary, for verbs that start copies of it.
#pragma once

#include <string>

namespace layers::app {

// `text` quoted for /bin/sh.
std::string shell_quote(const std::string& text);

// Runs the /bin/sh `command` with stdin from /dev/null and stdout and
// stderr written to `log` (appended to when `append`); waits for it and
// returns its exit status (-1 when it did not exit normally). Safe to call
// from several threads at once.
int run_logged(const std::string& command, const std::string& log, bool append = false);

// This binary's path (/proc/self/exe); layers::Error starting with `verb`
// when it cannot be read.
std::string this_executable(const std::string& verb);

}  // namespace layers::app
