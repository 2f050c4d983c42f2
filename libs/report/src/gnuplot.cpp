// gnuplot as a subprocess (see gnuplot.h).
#include "layers/report/gnuplot.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "text.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

bool executable(const fs::path& p) { return fs::is_regular_file(p) && ::access(p.c_str(), X_OK) == 0; }

// `program` as an executable path ("" when not found).
std::string locate(const std::string& program) {
  if (program.empty()) return "";
  if (program.find('/') != std::string::npos) return executable(program) ? program : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (executable(candidate)) return candidate.string();
  }
  return "";
}

// Runs a shell command; its exit status (-1 when it could not run).
int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

std::string last_lines(const std::string& text, std::size_t max_chars) {
  return text.size() <= max_chars ? text : "..." + text.substr(text.size() - max_chars);
}

}  // namespace

Gnuplot Gnuplot::find(const std::string& program) {
  const std::string path = locate(program);
  if (path.empty())
    throw Error("gnuplot is missing: '" + program +
                "' was not found (install the Debian package gnuplot-nox, as scripts/setup.sh does); "
                "the tables were written, the charts were not");
  const bool cairo = shell(shell_word(path) + " -e 'set terminal pngcairo' >/dev/null 2>&1") == 0;
  if (!cairo && shell(shell_word(path) + " -e 'set terminal png' >/dev/null 2>&1") != 0)
    throw Error("gnuplot at '" + path + "' has neither the pngcairo nor the png terminal: no charts drawn");
  return Gnuplot(path, cairo ? "pngcairo" : "png");
}

std::string Gnuplot::preamble(const std::string& name, int width, int height) const {
  std::ostringstream s;
  s << "# Drawn by `layers report`; redraw with: gnuplot " << name << ".gp\n"
    << "set terminal " << terminal_ << " size " << width << "," << height
    << (terminal_ == "pngcairo" ? " font 'Sans,10' noenhanced" : " noenhanced") << "\n"
    << "if (!exists('out')) out = " << gnuplot_string(name + ".png") << "\n"
    << "set output out\n";
  return s.str();
}

std::string Gnuplot::plot(const std::string& dir_in, const std::string& name, const std::string& script) const {
  const std::string dir = fs::absolute(dir_in).string();  // the command runs in it
  const fs::path png = fs::path(dir) / (name + ".png");
  write_text_atomic((fs::path(dir) / (name + ".gp")).string(), script);
  AtomicPath image(png.string());
  const std::string temp_name = fs::path(image.temp()).filename().string();
  const fs::path log = fs::path(image.temp() + ".log");
  const std::string command = "cd " + shell_word(dir) + " && " + shell_word(program_) + " -e " +
                              shell_word("out = " + gnuplot_string(temp_name)) + " " + shell_word(name + ".gp") + " >" +
                              shell_word(log.string()) + " 2>&1";
  const int status = shell(command);
  std::string messages;
  {
    std::ifstream in(log);
    std::stringstream buffer;
    buffer << in.rdbuf();
    messages = buffer.str();
  }
  std::error_code ec;
  fs::remove(log, ec);
  const bool drawn = fs::exists(image.temp()) && fs::file_size(image.temp(), ec) > 0;
  if (status != 0 || !drawn)
    throw Error("gnuplot failed on " + (fs::path(dir) / (name + ".gp")).string() + " (exit status " +
                std::to_string(status) + (drawn ? "" : ", no image") + ")" +
                (messages.empty() ? std::string() : ": " + last_lines(messages, 600)));
  image.commit();
  return png.string();
}

}  // namespace layers::report
