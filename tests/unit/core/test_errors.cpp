// Error message formats, atomic writes and progress formatting.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/log.h"
#include "layers/core/memory.h"
#include "layers/core/progress.h"
#include "temp_dir.h"

using namespace layers;

TEST(Errors, InputErrorFormat) {
  InputError e("data/shard-00000.h5", "/seq/a/body/positions", "float32[10,300,3]", "float64[10,300,3]");
  EXPECT_STREQ(e.what(),
               "data/shard-00000.h5: /seq/a/body/positions: expected float32[10,300,3], got float64[10,300,3]");
  EXPECT_EQ(e.field(), "/seq/a/body/positions");
  InputError m = InputError::message("x.yaml:3", "model", "unknown model");
  EXPECT_STREQ(m.what(), "x.yaml:3: model: unknown model");
}

TEST(Errors, LogLevelIsChecked) {
  EXPECT_NO_THROW(set_log_level("warn"));
  try {
    set_log_level("loud");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("got 'loud'"), std::string::npos);
  }
}

TEST(AtomicFile, FailureKeepsPreviousFile) {
  test::TempDir dir;
  std::string path = dir.file("report.md");
  write_text_atomic(path, "first");
  try {
    AtomicPath atomic(path);
    std::ofstream(atomic.temp()) << "half-written";
    throw std::runtime_error("crash while writing");
  } catch (const std::runtime_error&) {
  }
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "first");
  // No temporary left behind.
  int files = 0;
  for (auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
  write_text_atomic(path, "second");
  std::ifstream again(path);
  std::string word;
  again >> word;
  EXPECT_EQ(word, "second");
  EXPECT_THROW(write_text_atomic(dir.file("no/such/dir/x"), "y"), InputError);
}

TEST(AtomicFile, ANewFileNeverReplacesOneThatExists) {
  test::TempDir dir;
  const std::string path = dir.file("frames.csv");
  write_new_text_file(path, "mine", "exists");
  try {
    write_new_text_file(path, "theirs", "exists; pick a new name");
    ADD_FAILURE() << "an existing file was replaced";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exists; pick a new name"), std::string::npos) << e.what();
  }
  std::ifstream in(path);
  std::string word;
  in >> word;
  EXPECT_EQ(word, "mine");
  int files = 0;  // no temporary left behind
  for (auto& entry : std::filesystem::directory_iterator(dir.path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(Progress::format_duration(0), "00:00");
  EXPECT_EQ(Progress::format_duration(61.4), "01:01");
  EXPECT_EQ(Progress::format_duration(3725), "1:02:05");
  EXPECT_EQ(Progress::format_duration(-1), "--:--");
}

TEST(Memory, ResidentIsReported) {
  std::size_t rss = resident_bytes();
  EXPECT_GT(rss, 0u);
  EXPECT_GE(peak_resident_bytes(), rss);
}
