// Shard choice for `layers generate --shard`: k/n, or auto from a batch
// scheduler's environment (see shard.h).
#include "layers/generate/shard.h"

#include <cstdlib>
#include <optional>

#include "layers/core/error.h"
#include "layers/core/whole_number.h"

namespace layers::generate {
namespace {

constexpr const char* kSlurmId = "SLURM_ARRAY_TASK_ID";
constexpr const char* kSlurmCount = "SLURM_ARRAY_TASK_COUNT";
constexpr const char* kSlurmMin = "SLURM_ARRAY_TASK_MIN";
constexpr const char* kSlurmMax = "SLURM_ARRAY_TASK_MAX";
constexpr const char* kK8sIndex = "JOB_COMPLETION_INDEX";
constexpr const char* kCount = "LAYERS_SHARD_COUNT";
constexpr int kMaxShards = 1000000;

// A plain decimal number in [0, kMaxShards] (no sign, no spaces), or none.
std::optional<int> number(const std::string& text) {
  const std::optional<long long> v = parse_whole_number(text, kMaxShards);
  if (!v) return std::nullopt;
  return static_cast<int>(*v);
}

const std::string* lookup(const Environment& env, const char* name) {
  auto it = env.find(name);
  return it == env.end() || it->second.empty() ? nullptr : &it->second;
}

[[noreturn]] void fail(const std::string& what, const std::string& expected, const std::string& got) {
  throw UsageError(what + ": expected " + expected + ", got " + got);
}

// One variable that must hold a number, when set.
std::optional<int> read_number(const Environment& env, const char* name, const std::string& expected) {
  const std::string* value = lookup(env, name);
  if (!value) return std::nullopt;
  auto n = number(*value);
  if (!n) fail(std::string("--shard auto: ") + name, expected, "'" + *value + "'");
  return n;
}

ShardChoice from_environment(const std::optional<int>& given_count, const Environment& env) {
  const std::string what = "--shard auto";
  const bool slurm = lookup(env, kSlurmId) != nullptr, k8s = lookup(env, kK8sIndex) != nullptr;
  if (slurm && k8s)
    fail(what, std::string("one of ") + kSlurmId + " (Slurm) or " + kK8sIndex + " (Kubernetes)",
         "both ('" + *lookup(env, kSlurmId) + "' and '" + *lookup(env, kK8sIndex) + "')");
  if (!slurm && !k8s)
    fail(what,
         std::string(kSlurmId) + " (a Slurm array job) or " + kK8sIndex +
             " (a Kubernetes Indexed Job) in the environment",
         "neither; outside a scheduler give --shard k/n");
  const char* index_name = slurm ? kSlurmId : kK8sIndex;
  const int index = *read_number(env, index_name, "a shard index (a whole number >= 0)");

  // Every source of the count that is given must agree.
  std::optional<int> count;
  std::string count_from;
  auto agree = [&](const std::optional<int>& n, const std::string& name) {
    if (!n) return;
    if (*n < 1) fail(what + ": " + name, "a shard count >= 1", "'" + std::to_string(*n) + "'");
    if (count && *count != *n)
      fail(what, "one shard count",
           count_from + " says " + std::to_string(*count) + ", " + name + " says " + std::to_string(*n));
    count = n;
    count_from = name;
  };
  agree(given_count, "--shard auto/n");
  agree(read_number(env, kCount, "a shard count (a whole number >= 1)"), kCount);
  if (slurm) agree(read_number(env, kSlurmCount, "the array's task count"), kSlurmCount);
  if (!count)
    fail(what, std::string("the shard count from --shard auto/n or ") + kCount + " (a Kubernetes Job's completions)",
         std::string("neither (") + kK8sIndex + "=" + std::to_string(index) + ")");
  if (slurm) {
    // Array task ids are the shard numbers: --array=0-(n-1), step 1.
    auto min = read_number(env, kSlurmMin, "the array's first task id");
    auto max = read_number(env, kSlurmMax, "the array's last task id");
    if ((min && *min != 0) || (max && *max != *count - 1))
      fail(what,
           "an array numbered 0-" + std::to_string(*count - 1) + " (sbatch --array=0-" + std::to_string(*count - 1) +
               ")",
           "ids " + (min ? std::to_string(*min) : std::string("?")) + "-" +
               (max ? std::to_string(*max) : std::string("?")) + " for " + std::to_string(*count) + " tasks");
  }
  if (index >= *count)
    fail(what + ": " + index_name, "a shard index below the count " + std::to_string(*count) + " (" + count_from + ")",
         "'" + std::to_string(index) + "'");
  return {index, *count, std::string(index_name) + ", count from " + count_from};
}

}  // namespace

const std::vector<std::string>& shard_environment_names() {
  static const std::vector<std::string> names{kSlurmId, kSlurmCount, kSlurmMin, kSlurmMax, kK8sIndex, kCount};
  return names;
}

Environment shard_environment() {
  Environment env;
  for (const auto& name : shard_environment_names())
    if (const char* value = std::getenv(name.c_str())) env[name] = value;
  return env;
}

ShardChoice parse_shard(const std::string& text, const Environment& env) {
  const std::string expected = "k/n with 0 <= k < n (e.g. 0/4), auto or auto/n";
  const auto slash = text.find('/');
  const std::string head = text.substr(0, slash);
  const std::optional<std::string> tail =
      slash == std::string::npos ? std::nullopt : std::optional<std::string>(text.substr(slash + 1));
  if (head == "auto") {
    std::optional<int> count;
    if (tail) {
      count = number(*tail);
      if (!count || *count < 1) fail("--shard", expected, "'" + text + "'");
    }
    return from_environment(count, env);
  }
  if (tail) {
    auto k = number(head), n = number(*tail);
    if (k && n && *n >= 1 && *k < *n) return {*k, *n, "--shard"};
  }
  fail("--shard", expected, "'" + text + "'");
}

std::string shard_list(const std::vector<int>& shards) {
  std::string out;
  for (std::size_t a = 0; a < shards.size();) {
    std::size_t b = a;
    while (b + 1 < shards.size() && shards[b + 1] == shards[b] + 1) ++b;
    if (!out.empty()) out += ", ";
    if (b - a >= 2) {
      out += std::to_string(shards[a]) + "-" + std::to_string(shards[b]);
    } else {
      out += std::to_string(shards[a]);
      if (b > a) out += ", " + std::to_string(shards[b]);
    }
    a = b + 1;
  }
  return out;
}

}  // namespace layers::generate
