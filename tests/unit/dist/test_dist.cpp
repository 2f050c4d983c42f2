// Data-parallel runs over c10d Gloo on this machine: dist_worker started
// as 2 ranks (or 1 process) with the variables `layers launch` sets.
// - collectives give every rank the right sums, gathers and broadcasts;
// - 2 ranks at batch b train to the parameters of 1 process at batch 2b
//   on the same windows, and resume with another world size;
// - a 2-rank evaluation writes the metrics of a 1-process one;
// - a rank that dies, stalls or never comes fails the others with one
//   line naming what failed, within the timeout (bounded, never a hang).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "file_bytes.h"
#include "layers/train/checkpoint.h"
#include "layers/train/session.h"
#include "layers/train/trainer.h"
#include "temp_dir.h"
#include "train_fixture.h"

namespace layers {
namespace {

struct Exit {
  int code = -1;  // -1: still running at the deadline (then killed)
  std::string out, err;
};

int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

// Starts dist_worker <args> as `ranks` of a world of `world` (world 1: no
// distributed variables at all), waits at most `limit_s` for all of them
// (a hang guard: a rank still running then is killed, code -1). With
// `first_decides`, the others are killed (SIGKILL) once the first has ended.
std::vector<Exit> run_ranks(const std::string& dir, int world, std::vector<int> ranks,
                            const std::vector<std::string>& args, double limit_s = 120, bool first_decides = false) {
  const int port = free_port();
  std::vector<pid_t> pids;
  for (int rank : ranks) {
    const std::string out = dir + "/rank" + std::to_string(rank) + ".out", err = out + ".err";
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (world > 1) {
        ::setenv("RANK", std::to_string(rank).c_str(), 1);
        ::setenv("LOCAL_RANK", std::to_string(rank).c_str(), 1);
        ::setenv("WORLD_SIZE", std::to_string(world).c_str(), 1);
        ::setenv("MASTER_ADDR", "127.0.0.1", 1);
        ::setenv("MASTER_PORT", std::to_string(port).c_str(), 1);
      } else {
        for (const char* v : {"RANK", "WORLD_SIZE", "SLURM_NTASKS", "SLURM_PROCID"}) ::unsetenv(v);
      }
      ::dup2(::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), 1);
      ::dup2(::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644), 2);
      std::vector<std::string> text{LAYERS_TEST_DIST_WORKER};
      text.insert(text.end(), args.begin(), args.end());
      std::vector<char*> argv;
      for (std::string& s : text) argv.push_back(s.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    pids.push_back(pid);
  }
  std::vector<Exit> exits(pids.size());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  for (std::size_t k = 0; k < pids.size(); ++k) {
    int status = 0;
    if (k > 0 && first_decides) ::kill(pids[k], SIGKILL);
    while (::waitpid(pids[k], &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pids[k], SIGKILL);
        ::waitpid(pids[k], &status, 0);
        status = -1;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    exits[k].code = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const std::string out = dir + "/rank" + std::to_string(ranks[k]) + ".out";
    exits[k].out = test::read_bytes(out);
    exits[k].err = test::read_bytes(out + ".err");
  }
  return exits;
}

std::vector<int> all_ranks(int n) {
  std::vector<int> r;
  for (int k = 0; k < n; ++k) r.push_back(k);
  return r;
}

struct Dist : ::testing::Test {
  test::TempDir dir{"layers-dist"};
  std::string dataset;
  void SetUp() override { dataset = train::testing::write_dataset(dir.path() + "/data", 5, 12); }

  // The tiny model's parameters (gain, shift xyz) in <out>/checkpoint-last.pt.
  std::vector<double> parameters(const std::string& out) {
    zoo::Registry registry;
    train::testing::register_test_models(registry);
    train::ExperimentConfig c = train::testing::experiment(dataset, out, "tiny");
    train::Session s = train::open_session(c, registry);
    train::load_checkpoint(train::checkpoint_path(c, "last"), *s.model, nullptr);
    std::vector<double> v;
    for (const at::Tensor& p : s.model->parameters())
      for (std::int64_t i = 0; i < p.numel(); ++i) v.push_back(p.detach().flatten()[i].item<double>());
    return v;
  }
};

TEST_F(Dist, CollectivesOverGloo) {
  const auto r = run_ranks(dir.path(), 2, all_ranks(2), {"collectives", "20"}, 60);
  ASSERT_EQ(r[0].code, 0) << r[0].err;
  ASSERT_EQ(r[1].code, 0) << r[1].err;
  // Sums 1+2 and 0.5+0.5; rank 0's broadcast value 7 * 6 elements; grad a
  // = mean of 1 and 2; b: only rank 1's 4, averaged over both ranks; c has
  // none anywhere; the caller's sums are summed, not averaged.
  for (int k = 0; k < 2; ++k)
    EXPECT_NE(r[k].out.find("rank " + std::to_string(k) +
                            ": sum 3.0 1.0, broadcast 42.0, grad a 1.50, grad b 2.00, grad c none, sums 10.0"),
              std::string::npos)
        << r[k].out;
  EXPECT_NE(r[0].out.find("gathered: [] [bbb]"), std::string::npos) << r[0].out;
  EXPECT_EQ(r[1].out.find("gathered"), std::string::npos);
}

TEST_F(Dist, TwoRanksAtBatchBTrainLikeOneProcessAtBatch2B) {
  const std::string one = dir.file("one"), two = dir.file("two");
  const auto single = run_ranks(dir.path(), 1, {0}, {"train", dataset, one, "4", "2"});
  ASSERT_EQ(single[0].code, 0) << single[0].err;
  const auto pair = run_ranks(dir.path(), 2, all_ranks(2), {"train", dataset, two, "2", "2"});
  ASSERT_EQ(pair[0].code, 0) << pair[0].err;
  ASSERT_EQ(pair[1].code, 0) << pair[1].err;
  const std::vector<double> a = parameters(one), b = parameters(two);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  // The run moved the parameters (gain starts at 0, shift at 0)...
  EXPECT_GT(std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2]) + std::abs(a[3]), 1e-3);
  // ...and both runs moved them alike: 4 Adam steps of lr 0.01.
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-5) << "parameter " << i;
  // The same averaged losses and validation on rank 0 as in one process.
  auto epochs = [](const std::string& out) {
    std::vector<std::string> lines;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("epoch ", 0) == 0) lines.push_back(line);
    return lines;
  };
  const std::vector<std::string> ex_lines = epochs(single[0].out), ey_lines = epochs(pair[0].out);
  ASSERT_EQ(ex_lines.size(), 2u) << single[0].out;
  ASSERT_EQ(ey_lines.size(), 2u) << pair[0].out;
  EXPECT_TRUE(epochs(pair[1].out).empty()) << pair[1].out;  // only rank 0 reports
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string &lx = ex_lines[k], &ly = ey_lines[k];
    double ex = 0, lossx = 0, valx = 0, ey = 0, lossy = 0, valy = 0;
    std::sscanf(lx.c_str(), "epoch %lf: loss %lf val %lf", &ex, &lossx, &valx);
    std::sscanf(ly.c_str(), "epoch %lf: loss %lf val %lf", &ey, &lossy, &valy);
    EXPECT_EQ(ex, ey);
    EXPECT_NEAR(lossx, lossy, 1e-6 * std::max(1.0, std::abs(lossx))) << lx << " | " << ly;
    EXPECT_NEAR(valx, valy, 1e-4) << lx << " | " << ly;
  }

  // One epoch on 2 ranks, resumed for the second in one process: the
  // checkpoint holds nothing of the world size.
  const std::string mixed = dir.file("mixed");
  const auto first = run_ranks(dir.path(), 2, all_ranks(2), {"train", dataset, mixed, "2", "1"});
  ASSERT_EQ(first[0].code, 0) << first[0].err;
  const auto rest = run_ranks(dir.path(), 1, {0}, {"train", dataset, mixed, "4", "2", "resume"});
  ASSERT_EQ(rest[0].code, 0) << rest[0].err;
  EXPECT_EQ(rest[0].out.find("epoch 1:"), std::string::npos) << rest[0].out;
  const std::vector<double> c = parameters(mixed);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], c[i], 1e-5) << "parameter " << i;
}

TEST_F(Dist, TwoRankEvaluationWritesTheMetricsOfOneProcess) {
  const std::string run = dir.file("run");
  ASSERT_EQ(run_ranks(dir.path(), 1, {0}, {"train", dataset, run, "4", "1"})[0].code, 0);
  // eval of the train split (3 sequences: a full round of 2 and a round of 1).
  const std::string one = dir.file("eval1"), two = dir.file("eval2");
  std::filesystem::create_directories(one);
  std::filesystem::create_directories(two);
  auto eval = [&](int world, const std::string& out) {
    const auto r = run_ranks(dir.path(), world, all_ranks(world), {"eval", dataset, run});
    for (const Exit& e : r) EXPECT_EQ(e.code, 0) << e.err;
    std::filesystem::rename(run + "/eval-test", out + "/eval");
  };
  eval(1, one);
  eval(2, two);
  auto metrics = [](const std::string& folder) {
    nlohmann::json j = nlohmann::json::parse(test::read_bytes(folder + "/eval/metrics.json"));
    j.erase("ms_per_frame");  // timing
    return j;
  };
  EXPECT_EQ(metrics(one), metrics(two));
  EXPECT_EQ(test::read_bytes(one + "/eval/sequences.csv"), test::read_bytes(two + "/eval/sequences.csv"));
  EXPECT_FALSE(test::read_bytes(two + "/eval/sequences.csv").empty());
  EXPECT_TRUE(std::filesystem::exists(two + "/eval/predictions.h5"));
}

TEST_F(Dist, ADeadRankFailsTheOthersWithinTheTimeout) {
  const auto r = run_ranks(dir.path(), 2, all_ranks(2), {"die", "5"}, 60);
  EXPECT_EQ(r[1].code, 128 + SIGKILL);
  ASSERT_EQ(r[0].code, 1) << r[0].out << r[0].err;
  // One line: who, which collective, and why.
  EXPECT_EQ(r[0].err.rfind("error: rank 0 of 2: allreduce failed after ", 0), 0u) << r[0].err;
  EXPECT_NE(r[0].err.find("(a rank stopped or did not answer within 5 s; see the other ranks' output)\n"),
            std::string::npos)
      << r[0].err;
  EXPECT_EQ(std::count(r[0].err.begin(), r[0].err.end(), '\n'), 1) << r[0].err;
}

TEST_F(Dist, AStalledRankTimesTheOthersOut) {
  // Rank 1 joins, then never answers (it is alive until rank 0 has ended,
  // then killed): rank 0 can only have ended through its own timeout.
  const auto r = run_ranks(dir.path(), 2, all_ranks(2), {"stall", "2"}, 60, true);
  ASSERT_EQ(r[0].code, 1) << r[0].out << r[0].err;
  EXPECT_EQ(r[1].code, 128 + SIGKILL);  // still waiting when rank 0 gave up
  EXPECT_EQ(r[0].err.rfind("error: rank 0 of 2: allreduce failed after ", 0), 0u) << r[0].err;
  EXPECT_NE(r[0].err.find("did not answer within 2 s"), std::string::npos) << r[0].err;
  EXPECT_EQ(std::count(r[0].err.begin(), r[0].err.end(), '\n'), 1) << r[0].err;
}

TEST_F(Dist, ARankThatNeverComesFailsTheRendezvous) {
  const auto r = run_ranks(dir.path(), 2, {0}, {"collectives", "2"}, 60);
  ASSERT_EQ(r[0].code, 1) << r[0].out << r[0].err;
  EXPECT_EQ(r[0].err.rfind("error: rank 0 of 2: rendezvous with 2 ranks at 127.0.0.1:", 0), 0u) << r[0].err;
  EXPECT_NE(r[0].err.find("did not answer within 2 s"), std::string::npos) << r[0].err;
  EXPECT_EQ(std::count(r[0].err.begin(), r[0].err.end(), '\n'), 1) << r[0].err;
}

}  // namespace
}  // namespace layers
