// Temporary-name-then-rename file writing (see atomic_file.h).
#include "layers/core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
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

namespace {

void write_temp(const AtomicPath& atomic, const std::string& text) {
  std::ofstream out(atomic.temp(), std::ios::binary);
  out << text;
  out.flush();
  if (!out) throw InputError::message(atomic.target(), "", "cannot write file");
}

}  // namespace

void AtomicPath::commit_new(const std::string& exists_message) {
  // link() fails if the target exists, so an existing file is never replaced.
  if (::link(temp_.c_str(), target_.c_str()) != 0) {
    const int error = errno;
    if (error == EEXIST) throw InputError::message(target_, "", exists_message);
    throw InputError::message(target_, "", std::string("cannot create the file: ") + std::strerror(error));
  }
  std::remove(temp_.c_str());
  committed_ = true;
}

void write_text_atomic(const std::string& path, const std::string& text) {
  AtomicPath atomic(path);
  write_temp(atomic, text);
  atomic.commit();
}

void write_new_text_file(const std::string& path, const std::string& text, const std::string& exists_message) {
  AtomicPath atomic(path);
  write_temp(atomic, text);
  atomic.commit_new(exists_message);
}

}  // namespace layers
