// `layers info`: what a dataset folder or shard file holds (sequences,
// frames, garments, vertex counts, splits), read from the index only.
#include <cstdio>
#include <iostream>

#include "dataset_access.h"
#include "layers/data/dataset.h"
#include "verbs.h"

namespace layers::app {
namespace {

std::string join(const std::vector<std::string>& items, const char* sep = ",") {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : sep) + s;
  return out;
}

void print_sequence(const data::SequenceInfo& s, bool garments) {
  std::int64_t garment_vertices = 0;
  for (const auto& g : s.garments) garment_vertices += g.n_vertices;
  std::printf("  %-24s %6lld frames  motion %-22s tags %-8s body %6lld v  garments %zu (%lld v)\n", s.id.c_str(),
              static_cast<long long>(s.n_frames), s.motion.c_str(), s.tags.empty() ? "-" : join(s.tags).c_str(),
              static_cast<long long>(s.body_vertices), s.garments.size(), static_cast<long long>(garment_vertices));
  if (!garments) return;
  for (const auto& g : s.garments)
    std::printf("      garment %-3s %-14s type %-12s layer %d  %6lld vertices %6lld faces %6lld uv\n", g.group.c_str(),
                g.name.c_str(), g.type.c_str(), g.layer, static_cast<long long>(g.n_vertices),
                static_cast<long long>(g.n_faces), static_cast<long long>(g.n_uv));
}

}  // namespace

VerbRun register_info(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("info", "Show what a dataset folder or shard file holds");
  struct Args {
    bool allow_unhashed = false;
    std::string path, sequence;
    std::size_t max_rows = 40;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("path", args->path, "dataset folder or shard .h5 file")->required();
  add_allow_unhashed(*cmd, args->allow_unhashed);
  cmd->add_option("--sequence", args->sequence, "show only this sequence, with its garments");
  cmd->add_option("--max-rows", args->max_rows, "list at most this many sequences")->capture_default_str();
  return [args]() {
    data::Dataset ds = open_dataset(args->path, args->allow_unhashed);
    if (!args->sequence.empty()) {
      print_sequence(ds.info(args->sequence), true);
      return static_cast<int>(kOk);
    }
    auto ids = ds.ids();
    std::int64_t frames = 0, garments = 0;
    for (const auto& id : ids) {
      frames += ds.info(id).n_frames;
      garments += static_cast<std::int64_t>(ds.info(id).garments.size());
    }
    const auto& m = ds.manifest();
    std::printf("dataset   %s\npath      %s\n", m.name.empty() ? "-" : m.name.c_str(), ds.path().c_str());
    if (!m.generator_revision.empty()) std::printf("generator %s\n", m.generator_revision.c_str());
    std::printf("sequences %zu  frames %lld  garments %lld\n", ids.size(), static_cast<long long>(frames),
                static_cast<long long>(garments));
    std::printf("splits   ");
    if (ds.splits().empty()) std::printf(" (none)");
    for (const auto& name : ds.splits().names()) std::printf(" %s=%zu", name.c_str(), ds.splits().get(name).size());
    std::printf("\nsequences:\n");
    for (std::size_t i = 0; i < ids.size() && i < args->max_rows; ++i) print_sequence(ds.info(ids[i]), false);
    if (ids.size() > args->max_rows) std::printf("  ... %zu more (--max-rows)\n", ids.size() - args->max_rows);
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
