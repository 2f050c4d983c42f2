// Temporary-name-then-rename file writing (see atomic_file.h).
#include "layers/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "layers/core/error.h"

namespace layers {

AtomicPath::AtomicPath(std::string target) : target_(std::move(target)) {
  static std::atomic<unsigned> counter{0};
  temp_ = target_ + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

AtomicPath::~AtomicPath() {
  if (!committed_) std::remove(temp_.c_str());
}

void AtomicPath::commit() {
  std::error_code ec;
  std::filesystem::rename(temp_, target_, ec);
  if (ec) throw InputError::message(target_, "", "cannot move the finished file into place: " + ec.message());
  committed_ = true;
}

void write_text_atomic(const std::string& path, const std::string& text) {
  AtomicPath atomic(path);
  {
    std::ofstream out(atomic.temp(), std::ios::binary);
    out << text;
    out.flush();
    if (!out) throw InputError::message(path, "", "cannot write file");
  }
  atomic.commit();
}

}  // namespace layers
