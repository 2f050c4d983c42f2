// The step loop of `layers run` (layers/study/runner.h) on two real steps
// that copy and upper-case small text files in a temporary folder: order
// by `after`, skipping on a matching fingerprint, reruns when an input
// changes or an output is gone, dry runs, failures blocking what comes
// after, and a bad `after`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/study/runner.h"
#include "temp_dir.h"

using namespace layers;
using study::StepStatus;

namespace {

class RunnerTest : public testing::Test {
 protected:
  void SetUp() override { dir.write("in.txt", "hello"); }

  // "upper" (in.txt -> copy.txt -> upper.txt) listed before the "copy"
  // it comes after.
  std::vector<study::Step> steps() {
    study::Step copy;
    copy.name = "copy", copy.folder = dir.path(), copy.outputs = {"copy.txt"};
    copy.inputs = [this] { return study::fingerprint_text(read_text_file(dir.file("in.txt"))); };
    copy.work = [this](study::StepWork&) {
      ran.push_back("copy");
      if (fail_copy) throw std::runtime_error("disk full");
      dir.write("copy.txt", read_text_file(dir.file("in.txt")));
    };
    study::Step upper;
    upper.name = "upper", upper.after = {"copy"}, upper.folder = dir.path(), upper.outputs = {"upper.txt"};
    upper.inputs = [this] { return study::file_stamp(dir.file("copy.txt")); };
    upper.work = [this](study::StepWork&) {
      ran.push_back("upper");
      std::string text = read_text_file(dir.file("copy.txt"));
      std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
      dir.write("upper.txt", text);
    };
    return {upper, copy};
  }

  std::vector<study::StepOutcome> run(study::RunnerOptions options = {}) {
    std::vector<study::StepOutcome> outcomes;
    study::Runner runner("test", options, outcomes);
    runner.run(steps());
    return outcomes;
  }

  test::TempDir dir{"layers-runner"};
  std::vector<std::string> ran;
  bool fail_copy = false;
};

TEST_F(RunnerTest, OrdersByAfterThenSkipsWhatIsCurrent) {
  const auto first = run();
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].step, "copy");
  EXPECT_EQ(first[1].step, "upper");
  EXPECT_EQ(first[1].status, StepStatus::Ran);
  EXPECT_EQ(ran, (std::vector<std::string>{"copy", "upper"}));
  EXPECT_EQ(read_text_file(dir.file("upper.txt")), "HELLO");

  const auto second = run();
  EXPECT_EQ(second[0].status, StepStatus::Current);
  EXPECT_EQ(second[1].status, StepStatus::Current);
  EXPECT_EQ(ran.size(), 2u);
}

TEST_F(RunnerTest, ChangedInputRerunsItsStepAndWhatReadsItsOutput) {
  run();
  dir.write("in.txt", "changed");
  const auto r = run();
  EXPECT_EQ(r[0].status, StepStatus::Ran);
  EXPECT_EQ(r[1].status, StepStatus::Ran);
  EXPECT_EQ(read_text_file(dir.file("upper.txt")), "CHANGED");
  // A missing output reruns only its step.
  std::filesystem::remove(dir.file("upper.txt"));
  const auto again = run();
  EXPECT_EQ(again[0].status, StepStatus::Current);
  EXPECT_EQ(again[1].status, StepStatus::Ran);
}

TEST_F(RunnerTest, DryRunWritesNothingAndMarksWhatComesAfter) {
  run();
  dir.write("in.txt", "changed");
  study::RunnerOptions dry;
  dry.dry_run = true;
  const auto r = run(dry);
  EXPECT_EQ(r[0].status, StepStatus::WouldRun);
  EXPECT_EQ(r[0].message, "inputs changed");
  EXPECT_EQ(r[1].status, StepStatus::WouldRun);
  EXPECT_EQ(r[1].message, "inputs change");
  EXPECT_EQ(ran.size(), 2u);
  EXPECT_EQ(read_text_file(dir.file("upper.txt")), "HELLO");
}

TEST_F(RunnerTest, FailureBlocksWhatComesAfterAndRerunsNextTime) {
  fail_copy = true;
  const auto r = run();
  EXPECT_EQ(r[0].status, StepStatus::Failed);
  EXPECT_EQ(r[0].message, "disk full");
  EXPECT_EQ(r[1].status, StepStatus::Blocked);
  EXPECT_EQ(r[1].message, "copy failed");
  fail_copy = false;
  const auto again = run();
  EXPECT_EQ(again[0].status, StepStatus::Ran);
  EXPECT_EQ(again[0].message, "");
  EXPECT_EQ(again[1].status, StepStatus::Ran);
}

TEST_F(RunnerTest, ForceRerunsCurrentSteps) {
  run();
  study::RunnerOptions force;
  force.force = true;
  const auto r = run(force);
  EXPECT_EQ(r[0].status, StepStatus::Ran);
  EXPECT_EQ(ran.size(), 4u);
}

TEST_F(RunnerTest, UnknownAfterIsAnError) {
  std::vector<study::StepOutcome> outcomes;
  study::Runner runner("test", {}, outcomes);
  std::vector<study::Step> s = steps();
  s[0].after = {"nothing"};
  EXPECT_THROW(runner.run(s), Error);
}

}  // namespace
