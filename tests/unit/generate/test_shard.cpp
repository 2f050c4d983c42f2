// `--shard` parsing (libs/generate/shard.h): k/n, and auto from a Slurm
// array job's or a Kubernetes Indexed Job's environment, given as a map;
// every bad value is a one-line UsageError naming what it read.
#include <gtest/gtest.h>

#include <string>

#include "layers/core/error.h"
#include "layers/generate/shard.h"

namespace layers {
namespace {

using generate::Environment;
using generate::parse_shard;

// The UsageError message of parse_shard(text, env); fails the test if none.
std::string usage_error(const std::string& text, const Environment& env = {}) {
  try {
    auto s = parse_shard(text, env);
    ADD_FAILURE() << "'" << text << "' gave " << s.index << "/" << s.count << " (" << s.source << ")";
  } catch (const UsageError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Shard, KOverN) {
  auto s = parse_shard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  EXPECT_EQ(s.source, "--shard");
  s = parse_shard("0/1", {{"SLURM_ARRAY_TASK_ID", "3"}});  // the environment is read for auto only
  EXPECT_EQ(s.index, 0);
  EXPECT_EQ(s.count, 1);
  for (const char* bad : {"2/2", "-1/2", "1/0", "1", "a/b", "1/2/3", " 1/2", "1/+2", "", "/", "0/99999999"})
    EXPECT_TRUE(contains(usage_error(bad), "--shard: expected k/n")) << bad;
}

TEST(Shard, SlurmArray) {
  Environment env{{"SLURM_ARRAY_TASK_ID", "2"},
                  {"SLURM_ARRAY_TASK_COUNT", "3"},
                  {"SLURM_ARRAY_TASK_MIN", "0"},
                  {"SLURM_ARRAY_TASK_MAX", "2"}};
  auto s = parse_shard("auto", env);
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(contains(s.source, "SLURM_ARRAY_TASK_ID")) << s.source;
  s = parse_shard("auto/3", env);  // an explicit count that agrees
  EXPECT_EQ(s.count, 3);

  // A count that disagrees, from the flag or LAYERS_SHARD_COUNT.
  EXPECT_TRUE(contains(usage_error("auto/4", env), "--shard auto/n says 4")) << usage_error("auto/4", env);
  Environment counted = env;
  counted["LAYERS_SHARD_COUNT"] = "5";
  EXPECT_TRUE(contains(usage_error("auto", counted), "LAYERS_SHARD_COUNT says 5, SLURM_ARRAY_TASK_COUNT says 3"))
      << usage_error("auto", counted);

  // Arrays not numbered 0..n-1: --array=1-3, and --array=0-4:2 (3 tasks).
  Environment shifted{{"SLURM_ARRAY_TASK_ID", "3"},
                      {"SLURM_ARRAY_TASK_COUNT", "3"},
                      {"SLURM_ARRAY_TASK_MIN", "1"},
                      {"SLURM_ARRAY_TASK_MAX", "3"}};
  EXPECT_TRUE(
      contains(usage_error("auto", shifted), "expected an array numbered 0-2 (sbatch --array=0-2), got ids 1-3"))
      << usage_error("auto", shifted);
  Environment stepped{{"SLURM_ARRAY_TASK_ID", "4"},
                      {"SLURM_ARRAY_TASK_COUNT", "3"},
                      {"SLURM_ARRAY_TASK_MIN", "0"},
                      {"SLURM_ARRAY_TASK_MAX", "4"}};
  EXPECT_TRUE(contains(usage_error("auto", stepped), "got ids 0-4 for 3 tasks")) << usage_error("auto", stepped);
  // Without MIN/MAX (older Slurm), the index is still checked against the count.
  EXPECT_TRUE(contains(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}),
                       "SLURM_ARRAY_TASK_ID: expected a shard index below the count 3"));
  // Not numbers.
  EXPECT_TRUE(contains(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "x"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}),
                       "SLURM_ARRAY_TASK_ID: expected a shard index (a whole number >= 0), got 'x'"));
  EXPECT_TRUE(contains(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "-3"}}),
                       "SLURM_ARRAY_TASK_COUNT: expected the array's task count, got '-3'"));
  EXPECT_TRUE(contains(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "0"}}),
                       "SLURM_ARRAY_TASK_COUNT: expected a shard count >= 1, got '0'"));
}

TEST(Shard, KubernetesIndexedJob) {
  // The index alone does not say how many shards there are.
  const std::string none = usage_error("auto", {{"JOB_COMPLETION_INDEX", "1"}});
  EXPECT_TRUE(contains(none, "--shard auto/n or LAYERS_SHARD_COUNT")) << none;
  EXPECT_TRUE(contains(none, "JOB_COMPLETION_INDEX=1")) << none;

  auto s = parse_shard("auto/3", {{"JOB_COMPLETION_INDEX", "1"}});
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
  s = parse_shard("auto", {{"JOB_COMPLETION_INDEX", "2"}, {"LAYERS_SHARD_COUNT", "3"}});
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  EXPECT_TRUE(contains(s.source, "JOB_COMPLETION_INDEX, count from LAYERS_SHARD_COUNT")) << s.source;
  // Slurm's count is not read outside a Slurm array.
  s = parse_shard("auto/2", {{"JOB_COMPLETION_INDEX", "0"}, {"SLURM_ARRAY_TASK_COUNT", "7"}});
  EXPECT_EQ(s.count, 2);

  EXPECT_TRUE(contains(usage_error("auto", {{"JOB_COMPLETION_INDEX", "3"}, {"LAYERS_SHARD_COUNT", "3"}}),
                       "JOB_COMPLETION_INDEX: expected a shard index below the count 3 (LAYERS_SHARD_COUNT), got '3'"));
  EXPECT_TRUE(contains(usage_error("auto", {{"JOB_COMPLETION_INDEX", "0"}, {"LAYERS_SHARD_COUNT", "three"}}),
                       "LAYERS_SHARD_COUNT: expected a shard count (a whole number >= 1), got 'three'"));
  EXPECT_TRUE(contains(usage_error("auto/0", {{"JOB_COMPLETION_INDEX", "0"}}), "--shard: expected k/n"));
  EXPECT_TRUE(contains(usage_error("auto/x", {{"JOB_COMPLETION_INDEX", "0"}}), "got 'auto/x'"));
}

TEST(Shard, AutoNeedsExactlyOneScheduler) {
  const std::string neither = usage_error("auto");
  EXPECT_TRUE(contains(neither, "SLURM_ARRAY_TASK_ID (a Slurm array job) or JOB_COMPLETION_INDEX")) << neither;
  EXPECT_TRUE(contains(neither, "got neither")) << neither;
  // Set but empty counts as not set.
  EXPECT_TRUE(contains(usage_error("auto", {{"SLURM_ARRAY_TASK_ID", ""}}), "got neither"));
  const std::string both = usage_error(
      "auto/2", {{"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_COUNT", "2"}, {"JOB_COMPLETION_INDEX", "0"}});
  EXPECT_TRUE(contains(both, "got both ('1' and '0')")) << both;
}

TEST(Shard, ListsRunsAsRanges) {
  EXPECT_EQ(generate::shard_list({}), "");
  EXPECT_EQ(generate::shard_list({4}), "4");
  EXPECT_EQ(generate::shard_list({1, 2}), "1, 2");
  EXPECT_EQ(generate::shard_list({0, 1, 2}), "0-2");
  EXPECT_EQ(generate::shard_list({3, 4, 5, 6, 7, 9}), "3-7, 9");
  EXPECT_EQ(generate::shard_list({0, 2, 3, 5, 6, 7, 10, 11}), "0, 2, 3, 5-7, 10, 11");
}

}  // namespace
}  // namespace layers
