// Progress line rendering (see progress.h).
#include "layers/core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace layers {

Progress::Progress(std::string label, std::size_t total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), tty_(isatty(2) != 0) {}

std::string Progress::format_duration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e7) return "--:--";
  long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%02ld:%02ld", s / 60, s % 60);
  return buf;
}

void Progress::advance(std::size_t n, const std::string& extra) {
  done_ += n;
  double now = timer_.seconds();
  double interval = tty_ ? 0.2 : 10.0;
  if (last_print_ < 0 || now - last_print_ >= interval) print(false, extra);
}

void Progress::finish(const std::string& extra) { print(true, extra); }

void Progress::print(bool final, const std::string& extra) {
  double elapsed = timer_.seconds();
  last_print_ = elapsed;
  double rate = elapsed > 0 ? done_ / elapsed : 0.0;
  double eta = (rate > 0 && total_ > done_) ? (total_ - done_) / rate : 0.0;
  std::fprintf(stderr, "%s%s  %zu/%zu %s  %.2f/s  %s %s%s%s", tty_ ? "\r\033[K" : "", label_.c_str(), done_, total_,
               unit_.c_str(), rate, final ? "took" : "ETA", format_duration(final ? elapsed : eta).c_str(),
               extra.empty() ? "" : "  ", extra.c_str());
  if (!tty_ || final) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace layers
