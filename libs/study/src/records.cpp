// steps.yaml records and fingerprints (see records.h).
#include "layers/study/records.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "layers/core/atomic_file.h"
#include "layers/core/checksum.h"
#include "layers/core/config.h"
#include "layers/core/text_file.h"
#include "layers/data/run_layout.h"

namespace fs = std::filesystem;

namespace layers::study {

Records::Records(std::string folder) : folder_(std::move(folder)) {
  const fs::path file = fs::path(folder_) / data::run_layout::kSteps;
  if (!fs::exists(file)) return;
  try {
    cfg::Node tree = cfg::parse(read_text_file(file.string()), file.string());
    if (tree.kind != cfg::Node::Kind::Map) return;
    for (const auto& [step, node] : tree.map) entries_.emplace_back(step, cfg::read<Record>(node, step));
  } catch (const std::exception& e) {
    spdlog::warn("{}: ignored (every step of it reruns): {}", file.string(), e.what());
    entries_.clear();
  }
}

const Record* Records::find(const std::string& step) const {
  for (const auto& [name, r] : entries_)
    if (name == step) return &r;
  return nullptr;
}

void Records::put(const std::string& step, const Record& record) {
  for (auto& [name, r] : entries_)
    if (name == step) {
      r = record;
      save();
      return;
    }
  entries_.emplace_back(step, record);
  save();
}

bool Records::current(const std::string& step, const std::string& inputs) const {
  const Record* r = find(step);
  if (!r || r->state != "done" || r->inputs != inputs) return false;
  for (const std::string& out : r->outputs)
    if (!fs::exists(fs::path(folder_) / out)) return false;
  return true;
}

std::string Records::reason(const std::string& step, const std::string& inputs) const {
  const Record* r = find(step);
  if (!r) return "no record";
  if (r->state == "started") return "interrupted before";
  if (r->state == "failed") return "failed before";
  if (r->inputs != inputs) return "inputs changed";
  for (const std::string& out : r->outputs)
    if (!fs::exists(fs::path(folder_) / out)) return out + " missing";
  return "forced";
}

void Records::save() const {
  cfg::Node tree;
  tree.kind = cfg::Node::Kind::Map;
  for (const auto& [name, r] : entries_) tree.map.emplace_back(name, cfg::to_node(r));
  write_text_atomic((fs::path(folder_) / data::run_layout::kSteps).string(),
                    "# written by `layers run` (docs/studies.md): the inputs' fingerprint and outputs of each "
                    "step\n" +
                        cfg::to_yaml(tree) + "\n");
}

Fingerprint& Fingerprint::add(const std::string& key, const std::string& value) {
  text_ += key + "=" + value + "\n";
  return *this;
}

std::string Fingerprint::str() const { return fingerprint_text(text_); }

std::string fingerprint_text(const std::string& text) { return content_hash(text); }

std::string file_stamp(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "missing";
  const auto time = fs::last_write_time(path, ec);
  if (ec) return "missing";
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count();
  return std::to_string(size) + ":" + std::to_string(ns);
}

std::string dataset_fingerprint(const std::string& folder) {
  if (!fs::is_directory(folder)) return "missing";
  std::vector<std::string> names{"dataset.yaml", "splits.yaml", "stats.h5"};
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("shard-", 0) == 0 && entry.path().extension() == ".h5") names.push_back(name);
  }
  std::sort(names.begin() + 3, names.end());
  std::string text;
  for (const std::string& n : names) text += n + "=" + file_stamp((fs::path(folder) / n).string()) + "\n";
  return fingerprint_text(text);
}

}  // namespace layers::study
