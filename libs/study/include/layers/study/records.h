// layers/study/records.h -- what `layers run` remembers between runs: the
// steps.yaml record of each step of a folder (state, the fingerprint of
// its inputs, its outputs) and the fingerprints themselves (64-bit
// FNV-1a, 16 hex digits; files by size and modification time).
//
//   # written by `layers run` (docs/studies.md): ...
//   train: {state: done, inputs: 0123456789abcdef, outputs: [checkpoint-last.pt, ...],
//           seconds: 12.5, finished: "2024-01-01 12:00:00"}
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace layers::study {

struct Record {
  std::string state;  // started, done, failed
  std::string inputs;
  std::vector<std::string> outputs;  // relative to the record's folder
  double seconds = 0;
  std::string finished;

  template <class V>
  void visit(V& v) {
    v("state", state);
    v("inputs", inputs);
    v("outputs", outputs);
    v("seconds", seconds);
    v("finished", finished);
  }
};

// The records of one folder (<folder>/steps.yaml), in file order. An
// unreadable file is ignored with a warning (every step of it reruns).
class Records {
 public:
  explicit Records(std::string folder);

  const Record* find(const std::string& step) const;
  // Replaces or appends the record of `step` and saves the file.
  void put(const std::string& step, const Record& record);
  // Done with these inputs, and every output still there.
  bool current(const std::string& step, const std::string& inputs) const;
  // Why `step` is not current (for the log line).
  std::string reason(const std::string& step, const std::string& inputs) const;

 private:
  void save() const;

  std::string folder_;
  std::vector<std::pair<std::string, Record>> entries_;
};

// Lines "key=value" hashed together.
class Fingerprint {
 public:
  Fingerprint& add(const std::string& key, const std::string& value);
  std::string str() const;

 private:
  std::string text_;
};

std::string fingerprint_text(const std::string& text);
// "<size>:<mtime in ns>" of a file; "missing" when it does not exist.
std::string file_stamp(const std::string& path);
// The dataset folder's dataset.yaml, splits.yaml, stats.h5 and shards.
std::string dataset_fingerprint(const std::string& folder);

}  // namespace layers::study
