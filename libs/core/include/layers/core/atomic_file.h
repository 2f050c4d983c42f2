// layers/core/atomic_file.h -- write-then-rename, so that a file a user
// made is either the old one or the complete new one, never half-written.
#pragma once

#include <string>

namespace layers {

// A temporary name next to `target`; commit() renames it onto the target,
// and the destructor removes the temporary if commit() was never reached
// (e.g. an exception while writing).
class AtomicPath {
 public:
  explicit AtomicPath(std::string target);
  ~AtomicPath();
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;

  const std::string& temp() const { return temp_; }
  const std::string& target() const { return target_; }
  void commit();

 private:
  std::string target_, temp_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically; throws InputError on failure.
void write_text_atomic(const std::string& path, const std::string& text);

}  // namespace layers
