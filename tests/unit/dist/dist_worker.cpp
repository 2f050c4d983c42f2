// tests/unit/dist/dist_worker.cpp -- one rank of the runs test_dist.cpp
// starts (rank and rendezvous from the environment, as `layers launch`
// sets them). Modes:
//   collectives <timeout_s>        allreduce, gather, broadcast and gradient
//                                  averaging; prints what rank 0 got
//   die <timeout_s>                rank 1 kills itself after joining; rank 0
//                                  keeps exchanging and must fail
//   stall <timeout_s>              rank 1 never answers after joining (it
//                                  waits to be killed); rank 0 must time out
//   train <dataset> <out> <batch> <epochs> [resume]
//   eval <dataset> <out>           the tiny test model (tests/unit/train)
// Failures print "error: <message>" on one line and exit 1.
#include <signal.h>
#include <unistd.h>

#include <ATen/ATen.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "layers/dist/group.h"
#include "layers/dist/tensors.h"
#include "layers/train/evaluator.h"
#include "layers/train/trainer.h"
#include "train_fixture.h"

using namespace layers;

namespace {

std::unique_ptr<dist::Group> join(int timeout_s) {
  std::unique_ptr<dist::Group> g = dist::join_from_environment(std::chrono::seconds(timeout_s));
  if (!g) throw Error("dist_worker: no distributed environment");
  return g;
}

int collectives(int timeout_s) {
  auto g = join(timeout_s);
  std::vector<double> v{static_cast<double>(g->rank() + 1), 0.5};
  g->allreduce_sum(v);
  const std::vector<std::string> all = g->gather(std::string(static_cast<std::size_t>(g->rank()) * 3, 'a' + g->rank()));
  // Broadcast: every rank ends with rank 0's values.
  at::Tensor p = at::full({2, 3}, static_cast<float>(g->rank() + 7));
  dist::broadcast_from_root(*g, {p});
  // Averaged gradients: rank r has gradient r+1 on `a`; only rank 1 has one on `b`; nobody on `c`.
  at::Tensor a = at::zeros({3}).requires_grad_(true), b = at::zeros({2}).requires_grad_(true),
             c = at::zeros({1}).requires_grad_(true);
  (a * static_cast<double>(g->rank() + 1)).sum().backward();
  if (g->rank() == 1) (b * 4.0).sum().backward();
  std::vector<double> sums{10.0 * g->rank()};
  dist::average_gradients(*g, {a, b, c}, sums);
  std::printf("rank %d: sum %.1f %.1f, broadcast %.1f, grad a %.2f, grad b %.2f, grad c %s, sums %.1f\n", g->rank(),
              v[0], v[1], p.sum().item<double>(), a.grad()[0].item<double>(),
              b.grad().defined() ? b.grad()[0].item<double>() : -1.0, c.grad().defined() ? "defined" : "none", sums[0]);
  if (g->is_root()) {
    std::printf("gathered:");
    for (const std::string& s : all) std::printf(" [%s]", s.c_str());
    std::printf("\n");
  }
  return 0;
}

int die_or_stall(int timeout_s, bool die) {
  auto g = join(timeout_s);
  if (g->rank() == 1) {
    if (die) ::kill(::getpid(), SIGKILL);
    for (;;) ::pause();  // never answers again (the test stops it)
  }
  for (int i = 0; i < 1000000; ++i) {
    std::vector<double> v{1.0};
    try {
      g->allreduce_sum(v);
    } catch (const dist::Error& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 1;
    }
  }
  return 0;
}

train::ExperimentConfig experiment(const std::string& dataset, const std::string& out) {
  train::ExperimentConfig c = train::testing::experiment(dataset, out, "tiny");
  c.run.dist_timeout_s = 30;
  c.train.windows_per_epoch = 8;
  c.train.val_sequences = 0;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "collectives" && argc == 3) return collectives(std::stoi(argv[2]));
    if ((mode == "die" || mode == "stall") && argc == 3) return die_or_stall(std::stoi(argv[2]), mode == "die");
    zoo::Registry registry;
    train::testing::register_test_models(registry);
    if (mode == "train" && argc >= 6) {
      train::ExperimentConfig c = experiment(argv[2], argv[3]);
      c.train.batch_size = std::stoi(argv[4]);
      c.train.epochs = std::stoi(argv[5]);
      auto g = dist::join_from_environment(std::chrono::seconds(c.run.dist_timeout_s));
      train::TrainOptions o;
      o.progress = false;
      o.resume = argc > 6 && std::string(argv[6]) == "resume";
      o.group = g.get();
      const train::TrainReport r = train::run_training(c, registry, o);
      if (!g || g->is_root())
        for (const auto& e : r.epochs) std::printf("epoch %d: loss %.9g val %.9g\n", e.epoch, e.loss, e.val_error_mm);
      return 0;
    }
    if (mode == "eval" && argc == 4) {
      train::ExperimentConfig c = experiment(argv[2], argv[3]);
      auto g = dist::join_from_environment(std::chrono::seconds(c.run.dist_timeout_s));
      train::EvalOptions o;
      o.progress = false;
      o.checkpoint = "last";
      o.group = g.get();
      train::run_evaluation(c, registry, o);
      return 0;
    }
    std::fprintf(stderr,
                 "usage: dist_worker collectives|die|stall <timeout_s> | train <dataset> <out> <batch> "
                 "<epochs> [resume] | eval <dataset> <out>\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
