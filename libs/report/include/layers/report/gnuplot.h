// layers/report/gnuplot.h -- gnuplot as a subprocess: finding it, picking
// its PNG terminal, and running a generated script whose image appears
// atomically (drawn to a temporary name, renamed when gnuplot succeeded).
// Scripts and their data files stay next to the PNG, so a chart can be
// redrawn or restyled by hand (`cd charts && gnuplot name.gp`).
#pragma once

#include <string>

namespace layers::report {

class Gnuplot {
 public:
  // Finds `program` (a path, or a name looked up on PATH) and picks the
  // PNG terminal: pngcairo when this gnuplot has it, else png. Throws
  // layers::Error naming the missing tool and the package to install.
  static Gnuplot find(const std::string& program = "gnuplot");

  const std::string& program() const { return program_; }
  const std::string& terminal() const { return terminal_; }

  // First lines of a script: the terminal at width x height pixels,
  // output to the variable `out` (default "<name>.png"), plain (not
  // enhanced) text.
  std::string preamble(const std::string& name, int width, int height) const;

  // Writes <dir>/<name>.gp and runs it in `dir`. <dir>/<name>.png appears
  // only when gnuplot exited 0 and drew a non-empty image; otherwise throws
  // layers::Error quoting gnuplot's messages. Returns the PNG's path.
  std::string plot(const std::string& dir, const std::string& name, const std::string& script) const;

 private:
  Gnuplot(std::string program, std::string terminal) : program_(std::move(program)), terminal_(std::move(terminal)) {}
  std::string program_, terminal_;
};

}  // namespace layers::report
