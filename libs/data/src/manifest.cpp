// dataset.yaml reading and writing (see manifest.h).
#include "layers/data/manifest.h"

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/format.h"
#include "yaml_util.h"

namespace layers::data {
namespace {

void check_hash_text(const std::string& path, const YAML::Node& node, const std::string& key, const std::string& hash) {
  if (hash.size() != 16 || hash.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError(yaml_where(path, node), key, "16 hex digits", "'" + hash + "'");
}

}  // namespace

std::string manifest_to_yaml(const DatasetManifest& m) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "format" << YAML::Value << kFormatName;
  out << YAML::Key << "format_version" << YAML::Value << m.format_version;
  out << YAML::Key << "name" << YAML::Value << m.name;
  out << YAML::Key << "seed" << YAML::Value << m.seed;
  out << YAML::Key << "sequences_per_shard" << YAML::Value << m.sequences_per_shard;
  out << YAML::Key << "counts" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "sequences" << YAML::Value << m.n_sequences;
  out << YAML::Key << "frames" << YAML::Value << m.n_frames;
  out << YAML::Key << "garments" << YAML::Value << m.n_garments;
  out << YAML::Key << "shards" << YAML::Value << m.n_shards;
  out << YAML::EndMap;
  if (m.n_distinct_motions >= 0) {
    out << YAML::Key << "motions" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "distinct" << YAML::Value << m.n_distinct_motions;
    out << YAML::Key << "families" << YAML::Value << YAML::BeginMap;
    for (const auto& [family, c] : m.motion_families) {
      out << YAML::Key << family << YAML::Value << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "sequences" << YAML::Value << c.sequences;
      out << YAML::Key << "distinct" << YAML::Value << c.distinct;
      out << YAML::Key << "skipped" << YAML::Value << c.skipped;
      const std::pair<const char*, std::int64_t> outcome[] = {{"scenes", c.scenes},
                                                              {"cut", c.cut},
                                                              {"frames_asked", c.frames_asked},
                                                              {"frames_simulated", c.frames_simulated},
                                                              {"frames_stored", c.frames_stored}};
      for (const auto& [key, value] : outcome)
        if (value >= 0) out << YAML::Key << key << YAML::Value << value;
      if (!c.dropped.empty()) {
        out << YAML::Key << "dropped" << YAML::Value << YAML::BeginMap;
        for (const auto& [rule, frames] : c.dropped) out << YAML::Key << rule << YAML::Value << frames;
        out << YAML::EndMap;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap << YAML::EndMap;
  }
  if (!m.shards.empty()) {
    out << YAML::Key << "shards" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const auto& name : m.shards) out << name;
    out << YAML::EndSeq;
  }
  if (!m.stats_hash.empty()) out << YAML::Key << "stats_hash" << YAML::Value << m.stats_hash;
  if (!m.content_hashes.empty()) {
    out << YAML::Key << "content_hashes" << YAML::Value << YAML::BeginMap;
    for (const auto& [id, hash] : m.content_hashes) out << YAML::Key << id << YAML::Value << hash;
    out << YAML::EndMap;
  }
  if (!m.generator_yaml.empty()) {
    out << YAML::Key << "generator" << YAML::Value << parse_yaml_text(m.generator_yaml, "<generator config>");
  }
  if (!m.generator_revision.empty()) out << YAML::Key << "generator_revision" << YAML::Value << m.generator_revision;
  out << YAML::EndMap;
  return std::string("# layers dataset manifest (LAYERS-H5)\n") + out.c_str() + "\n";
}

DatasetManifest read_manifest(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  if (!root.IsMap())
    throw InputError(yaml_where(path, root), "", "a mapping (name, seed, counts, ...)", "something else");
  DatasetManifest m;
  auto required = [&](const char* key) {
    const YAML::Node node = root[key];
    if (!node) throw InputError(path, key, "a value", "nothing (missing key)");
    return node;
  };
  const auto format = yaml_scalar<std::string>(required("format"), path, "format", "a string");
  if (format != kFormatName)
    throw InputError(yaml_where(path, root["format"]), "format", kFormatName, "'" + format + "'");
  m.format_version = yaml_scalar<std::int64_t>(required("format_version"), path, "format_version", "an integer");
  if (m.format_version != kFormatVersion) {
    throw InputError(yaml_where(path, root["format_version"]), "format_version", std::to_string(kFormatVersion),
                     std::to_string(m.format_version));
  }
  m.name = yaml_scalar<std::string>(required("name"), path, "name", "a string");
  if (root["seed"]) m.seed = yaml_scalar<std::uint64_t>(root["seed"], path, "seed", "a non-negative integer");
  if (root["sequences_per_shard"]) {
    m.sequences_per_shard =
        yaml_scalar<std::int64_t>(root["sequences_per_shard"], path, "sequences_per_shard", "an integer");
  }
  if (const YAML::Node counts = root["counts"]) {
    if (!counts.IsMap()) throw InputError(yaml_where(path, counts), "counts", "a mapping", "something else");
    const std::pair<const char*, std::int64_t*> fields[] = {
        {"sequences", &m.n_sequences}, {"frames", &m.n_frames}, {"garments", &m.n_garments}, {"shards", &m.n_shards}};
    for (const auto& [key, target] : fields) {
      if (counts[key])
        *target = yaml_scalar<std::int64_t>(counts[key], path, std::string("counts.") + key, "an integer");
    }
  }
  if (const YAML::Node motions = root["motions"]) {
    if (!motions.IsMap()) throw InputError(yaml_where(path, motions), "motions", "a mapping", "something else");
    m.n_distinct_motions = yaml_scalar<std::int64_t>(motions["distinct"], path, "motions.distinct", "an integer");
    if (const YAML::Node families = motions["families"]) {
      if (!families.IsMap())
        throw InputError(yaml_where(path, families), "motions.families", "a mapping", "something else");
      for (const auto& kv : families) {
        const std::string family = kv.first.as<std::string>(), at = "motions.families." + family;
        MotionFamilyCount& c = m.motion_families[family];
        if (!kv.second.IsMap()) throw InputError(yaml_where(path, kv.second), at, "a mapping", "something else");
        const std::pair<const char*, std::int64_t*> fields[] = {{"sequences", &c.sequences},
                                                                {"distinct", &c.distinct},
                                                                {"skipped", &c.skipped},
                                                                {"scenes", &c.scenes},
                                                                {"cut", &c.cut},
                                                                {"frames_asked", &c.frames_asked},
                                                                {"frames_simulated", &c.frames_simulated},
                                                                {"frames_stored", &c.frames_stored}};
        for (const auto& [key, target] : fields)
          if (kv.second[key]) *target = yaml_scalar<std::int64_t>(kv.second[key], path, at + "." + key, "an integer");
        if (const YAML::Node dropped = kv.second["dropped"]) {
          if (!dropped.IsMap())
            throw InputError(yaml_where(path, dropped), at + ".dropped", "a mapping rule: frames", "something else");
          for (const auto& d : dropped) {
            const std::string rule = d.first.as<std::string>();
            c.dropped[rule] = yaml_scalar<std::int64_t>(d.second, path, at + ".dropped." + rule, "an integer");
          }
        }
      }
    }
  }
  if (const YAML::Node hashes = root["content_hashes"]) {
    if (!hashes.IsMap())
      throw InputError(yaml_where(path, hashes), "content_hashes", "a mapping id: hash", "something else");
    for (const auto& kv : hashes) {
      const std::string id = kv.first.as<std::string>();
      const std::string hash = yaml_scalar<std::string>(kv.second, path, "content_hashes." + id, "a string");
      check_hash_text(path, kv.second, "content_hashes." + id, hash);
      m.content_hashes[id] = hash;
    }
  }
  if (const YAML::Node shards = root["shards"]) {
    if (!shards.IsSequence())
      throw InputError(yaml_where(path, shards), "shards", "a list of shard file names", "something else");
    for (std::size_t i = 0; i < shards.size(); ++i) {
      const std::string at = "shards[" + std::to_string(i) + "]";
      const auto name = yaml_scalar<std::string>(shards[i], path, at, "a file name");
      if (name.empty() || name.find('/') != std::string::npos || name.find("..") != std::string::npos)
        throw InputError(yaml_where(path, shards[i]), at, "a file name in the dataset folder", "'" + name + "'");
      m.shards.push_back(name);
    }
  }
  if (const YAML::Node stats = root["stats_hash"]) {
    m.stats_hash = yaml_scalar<std::string>(stats, path, "stats_hash", "a string");
    check_hash_text(path, stats, "stats_hash", m.stats_hash);
  }
  if (const YAML::Node generator = root["generator"]) {
    YAML::Emitter out;
    out << generator;
    m.generator_yaml = out.c_str();
  }
  if (root["generator_revision"])
    m.generator_revision = yaml_scalar<std::string>(root["generator_revision"], path, "generator_revision", "a string");
  return m;
}

void write_manifest(const std::string& path, const DatasetManifest& manifest) {
  write_text_atomic(path, manifest_to_yaml(manifest));
}

}  // namespace layers::data
