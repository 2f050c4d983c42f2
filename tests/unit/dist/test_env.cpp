// dist::read_env and first_node: the variables torchrun, `layers launch`
// and Slurm set, their precedence, and one clear line for each bad value.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/dist/env.h"

namespace layers::dist {
namespace {

std::optional<DistEnv> read(const std::map<std::string, std::string>& vars) {
  return read_env([&](const char* name) -> const char* {
    auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  });
}

std::string error(const std::map<std::string, std::string>& vars) {
  try {
    read(vars);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DistEnv, NothingSetOrAWorldOfOneIsOneProcess) {
  EXPECT_FALSE(read({}).has_value());
  EXPECT_FALSE(read({{"WORLD_SIZE", "1"}, {"RANK", "0"}}).has_value());
  EXPECT_FALSE(read({{"SLURM_NTASKS", "1"}, {"SLURM_PROCID", "0"}, {"SLURM_JOB_NODELIST", "n1"}}).has_value());
}

TEST(DistEnv, TorchrunVariables) {
  const auto e = read(
      {{"RANK", "3"}, {"WORLD_SIZE", "4"}, {"LOCAL_RANK", "1"}, {"MASTER_ADDR", "node07"}, {"MASTER_PORT", "29501"}});
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->rank, 3);
  EXPECT_EQ(e->world_size, 4);
  EXPECT_EQ(e->local_rank, 1);
  EXPECT_EQ(e->master_addr, "node07");
  EXPECT_EQ(e->master_port, 29501);
  EXPECT_EQ(e->launcher, "torchrun");
}

TEST(DistEnv, SlurmVariablesTakeTheFirstNodeAndAPortFromTheJob) {
  const auto e = read({{"SLURM_PROCID", "5"},
                       {"SLURM_NTASKS", "8"},
                       {"SLURM_LOCALID", "1"},
                       {"SLURM_JOB_NODELIST", "gpu[03-04,09]"},
                       {"SLURM_JOB_ID", "123456"}});
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->rank, 5);
  EXPECT_EQ(e->world_size, 8);
  EXPECT_EQ(e->local_rank, 1);
  EXPECT_EQ(e->master_addr, "gpu03");
  EXPECT_EQ(e->master_port, 29500 + 3456);
  EXPECT_EQ(e->launcher, "slurm");
  // MASTER_ADDR / MASTER_PORT (set by the sbatch script) win.
  const auto set = read({{"SLURM_PROCID", "0"},
                         {"SLURM_NTASKS", "2"},
                         {"SLURM_JOB_NODELIST", "gpu[03-04]"},
                         {"MASTER_ADDR", "10.0.0.3"},
                         {"MASTER_PORT", "4000"}});
  EXPECT_EQ(set->master_addr, "10.0.0.3");
  EXPECT_EQ(set->master_port, 4000);
  // torchrun's variables win over Slurm's (torchrun started by srun).
  const auto both = read({{"RANK", "1"},
                          {"WORLD_SIZE", "2"},
                          {"MASTER_ADDR", "a"},
                          {"MASTER_PORT", "1"},
                          {"SLURM_PROCID", "0"},
                          {"SLURM_NTASKS", "1"}});
  EXPECT_EQ(both->rank, 1);
  EXPECT_EQ(both->launcher, "torchrun");
}

TEST(DistEnv, FirstNodeOfASlurmNodeList) {
  EXPECT_EQ(first_node("node[01-04,07]"), "node01");
  EXPECT_EQ(first_node("node[07,01-04]"), "node07");
  EXPECT_EQ(first_node("n1,n2,n3"), "n1");
  EXPECT_EQ(first_node("gpu3,node[1-2]"), "gpu3");
  EXPECT_EQ(first_node("rack[2-3]-n[10-12]"), "rack2-n10");
  EXPECT_EQ(first_node("single"), "single");
  EXPECT_EQ(test::error_of([] { first_node("node[01-04"); }),
            "environment: SLURM_JOB_NODELIST: expected a Slurm node list such as node[01-04,07], got 'node[01-04'");
  EXPECT_EQ(test::error_of([] { first_node(""); }),
            "environment: SLURM_JOB_NODELIST: expected a Slurm node list such as node[01-04,07], got ''");
  EXPECT_NE(test::error_of([] { first_node("a]b["); }), "");
}

TEST(DistEnv, BadValuesAreOneLineNamingTheVariable) {
  const std::map<std::string, std::string> ok{
      {"RANK", "0"}, {"WORLD_SIZE", "2"}, {"MASTER_ADDR", "127.0.0.1"}, {"MASTER_PORT", "29500"}};
  auto with = [&](const std::string& k, const std::string& v) {
    auto m = ok;
    m[k] = v;
    return m;
  };
  auto without = [&](const std::string& k) {
    auto m = ok;
    m.erase(k);
    return m;
  };
  EXPECT_EQ(error(with("RANK", "2")), "environment: RANK: expected an integer in [0, 2) (WORLD_SIZE), got '2'");
  EXPECT_EQ(error(with("RANK", "-1")), "environment: RANK: expected an integer in [0, 2) (WORLD_SIZE), got '-1'");
  EXPECT_EQ(error(with("WORLD_SIZE", "two")), "environment: WORLD_SIZE: expected an integer in [1, 65536], got 'two'");
  EXPECT_EQ(error(with("WORLD_SIZE", "0")), "environment: WORLD_SIZE: expected an integer in [1, 65536], got '0'");
  EXPECT_EQ(error(with("LOCAL_RANK", "9")),
            "environment: LOCAL_RANK: expected an integer in [0, 2) (WORLD_SIZE), got '9'");
  EXPECT_EQ(error(with("MASTER_PORT", "70000")),
            "environment: MASTER_PORT: expected a TCP port in [1, 65535], got '70000'");
  EXPECT_EQ(error(with("MASTER_PORT", "")), "environment: MASTER_PORT: expected a TCP port in [1, 65535], got ''");
  EXPECT_EQ(error(without("MASTER_ADDR")),
            "environment: MASTER_ADDR: expected the host name or address of rank 0 (WORLD_SIZE > 1), got unset");
  EXPECT_EQ(error(without("RANK")), "environment: RANK: expected an integer in [0, 2) (WORLD_SIZE is set), got unset");
  EXPECT_EQ(error({{"RANK", "0"}}),
            "environment: WORLD_SIZE: expected set together with RANK (as torchrun sets them), got unset");
  EXPECT_EQ(error({{"SLURM_NTASKS", "2"}, {"SLURM_PROCID", "2"}, {"SLURM_JOB_NODELIST", "n1"}}),
            "environment: SLURM_PROCID: expected an integer in [0, 2) (SLURM_NTASKS), got '2'");
  EXPECT_EQ(error({{"SLURM_NTASKS", "2"}, {"SLURM_PROCID", "1"}}),
            "environment: MASTER_ADDR: expected the host of rank 0 (or SLURM_JOB_NODELIST to take it from), got "
            "unset");
}

}  // namespace
}  // namespace layers::dist
