// tests/adversarial/test_adversarial_bounds.cpp -- issue 44's M1-M4: small
// inputs within the documented bounds that asked for gigabytes or hours
// (a BVH, YAML aliases and includes, --frames). Each runs the `layers`
// binary in its own process and must end with its one-line refusal within
// 1 GB of peak resident memory (getrusage of that process), while a
// valid input of the same kind succeeds under the same limit; a
// bare non-zero exit proves nothing, so the message is checked too.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "probe.h"
#include "temp_dir.h"
#include "test_paths.h"

using namespace layers;

namespace {

using test::kMaxPeakMiB;
using test::Probe;
using test::probe;

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

class Bounds : public ::testing::Test {
 protected:
  // `args` ends with exit `code` and one line holding `expect`, within
  // the memory limit.
  void refused(const std::string& args, int code, const std::string& expect) {
    const Probe p = probe(args, dir_.file("log-" + std::to_string(++runs_)));
    EXPECT_EQ(p.exit_code, code) << args << "\n" << p.output;
    EXPECT_EQ(lines(p.output), 1u) << args << "\n" << p.output;
    EXPECT_NE(p.output.find(expect), std::string::npos) << args << "\n" << p.output;
    EXPECT_LT(p.peak_mib, kMaxPeakMiB) << args;
  }
  void succeeds(const std::string& args) {
    const Probe p = probe(args, dir_.file("log-" + std::to_string(++runs_)));
    EXPECT_EQ(p.exit_code, 0) << args << "\n" << p.output;
    EXPECT_LT(p.peak_mib, kMaxPeakMiB) << args;
  }
  std::string write(const std::string& name, const std::string& text) { return dir_.write(name, text); }

  test::TempDir dir_{"layers-bounds"};
  int runs_ = 0;
};

// A root of `channels` rotation channels with `children` joints of none.
std::string bvh_header(int channels, int children, long frames, const char* frame_time) {
  const char* kinds[] = {"Zrotation", "Xrotation", "Yrotation"};
  std::string s = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS " + std::to_string(channels);
  for (int c = 0; c < channels; ++c) s += std::string(" ") + kinds[c % 3];
  s += "\n";
  for (int j = 1; j <= children; ++j)
    s += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 0.1 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 0.1 0\n}\n}\n";
  return s + "}\nMOTION\nFrames: " + std::to_string(frames) + "\nFrame Time: " + frame_time + "\n";
}

}  // namespace

// M1: a 2 MB BVH of one channel and 10^6 frames one second apart, and one
// of 500 joints without channels and 10^5 frames: refused from the header.
TEST_F(Bounds, M1_LargeBvhHeadersAreRefusedBeforeReading) {
  std::string one_channel = bvh_header(1, 0, 1000000, "1");
  one_channel.reserve(one_channel.size() + 2000000);
  for (int f = 0; f < 1000000; ++f) one_channel += "0\n";
  const std::string a = write("long.bvh", one_channel);
  refused("body --motion " + a + " --frames 0 --out " + dir_.file("a.h5"), 1,
          "a clip of at most 3600 s (Frames x Frame Time), got 1e+06 s");

  std::string many_joints = bvh_header(0, 499, 100000, "0.0333333");
  many_joints += std::string(100000, '\n');
  const std::string b = write("wide.bvh", many_joints);
  refused("body --motion " + b + " --frames 0 --out " + dir_.file("b.h5"), 1, "joints x frames");
  EXPECT_FALSE(std::ifstream(dir_.file("a.h5")).good());
  EXPECT_FALSE(std::ifstream(dir_.file("b.h5")).good());
  // A body of our own motion under the same limits.
  succeeds("body --motion procedural:walk --frames 30 --out " + dir_.file("ok.h5"));
}

// M2: one 4 MiB string aliased 600 times (a 4.2 MB file).
TEST_F(Bounds, M2_YamlAliasesAreBoundedInBytes) {
  std::string text = "model: {name: skinned}\nnote: &big " + std::string(4u << 20, 'x') + "\nmore: [";
  for (int i = 0; i < 600; ++i) text += (i ? ", *big" : "*big");
  text += "]\n";
  const std::string bomb = write("bomb.yaml", text);
  refused("config " + bomb, 1, "expected a config of at most 64 MiB of keys and values, got more");
  succeeds("config " + write("fine.yaml", "model: {name: skinned}\ndata: {subsets: [&t T, *t]}\n"));
}

// M3: nine files under 1 KB, each including the next ten times.
TEST_F(Bounds, M3_IncludesThatFanOutAreBounded) {
  for (int k = 0; k < 9; ++k) {
    std::string text = "include: [";
    for (int i = 0; i < 10; ++i) text += (i ? ", " : "") + std::string("f") + std::to_string(k + 1) + ".yaml";
    write("f" + std::to_string(k) + ".yaml", text + "]\n");
  }
  write("f9.yaml", "model: {name: skinned}\n");
  refused("config " + dir_.file("f0.yaml"), 1, "a config may load with its includes");
  succeeds("config " + write("one.yaml", "include: [f9.yaml]\n"));
}

// M4: --frames beyond the documented 100,000 is a flag error (exit 2).
TEST_F(Bounds, M4_FramesBeyondTheBoundAreAFlagError) {
  refused("body --motion procedural:walk --frames 200000 --out " + dir_.file("c.h5"), 2, "--frames");
  refused("body --motion procedural:walk --frames 100000000 --out " + dir_.file("d.h5"), 2, "--frames");
}
