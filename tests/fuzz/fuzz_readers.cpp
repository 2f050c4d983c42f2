// tests/fuzz/fuzz_readers.cpp -- a seeded mutation fuzzer for the readers
// that take user files: BVH clips, YAML configs (experiment and generator)
// and LAYERS-H5 shards. Each mutant of a seed file (bit flips, byte runs,
// cut and duplicated spans, numbers swapped for extreme values) goes
// through the real reader; an InputError (or another layers::Error) is the
// expected answer to bad input, anything else -- another exception, an
// allocation beyond the memory limit, a signal -- is a finding. The input
// being parsed is written to <work>/current.<ext> first, so a crash leaves
// it behind (scripts/fuzz.sh keeps it in tests/fuzz/regressions/).
//
//   layers_fuzz <bvh|yaml|h5> <seed file> <iterations> <rng seed> <work dir> [regression files...]
//
// Regression files are parsed first, unmutated. Exit 0 when every input was
// handled, 1 on a finding (the input is saved as <work>/finding.<ext>).
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "file_bytes.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/validate.h"
#include "layers/generate/generator_config.h"
#include "layers/motion/bvh.h"
#include "layers/train/experiment_config.h"

namespace fs = std::filesystem;
using namespace layers;

namespace {

using test::read_bytes;

void write_file(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// One reader: parse `bytes` (stored at `path`) as a user's file would be.
void parse_bvh(const std::string& bytes, const std::string&) {
  std::istringstream in(bytes);
  const motion::BvhClip clip = motion::parse_bvh(in, "fuzz.bvh");
  motion::resample(clip, 30.0);
}

// A generator config (it has `sequences`) or an experiment.
void parse_yaml(const std::string& bytes, const std::string&) {
  const cfg::Node tree = cfg::parse(bytes, "fuzz.yaml");
  if (tree.find("sequences"))
    generate::check(cfg::read<generate::GeneratorConfig>(tree), "fuzz.yaml");
  else
    train::read_experiment(tree, "fuzz.yaml");
}

void parse_h5(const std::string&, const std::string& path) {
  data::validate_dataset(path);
  const data::Dataset ds = data::Dataset::open(path);
  for (const std::string& id : ds.ids()) ds.read_sequence(id);
}

// Numbers a mutation may put in place of a number of the text.
const char* kExtremes[] = {
    "1e300",  "-1e300",     "1e30", "nan", "inf", "-1", "0", "2147483648", "-2147483649", "99999999999999999999",
    "1e-320", "0x7fffffff", ""};

// The largest mutant made (bytes).
constexpr std::size_t kMaxMutant = 64u << 20;

std::string mutate(const std::string& seed, std::mt19937_64& rng, bool text) {
  std::string s = seed;
  const int rounds = 1 + static_cast<int>(rng() % 4);
  for (int r = 0; r < rounds && !s.empty(); ++r) {
    const std::size_t at = rng() % s.size();
    switch (rng() % (text ? 6 : 4)) {
      case 0:  // flip bits
        s[at] = static_cast<char>(s[at] ^ (1 << (rng() % 8)));
        break;
      case 1: {  // overwrite a run with random bytes
        const std::size_t n = std::min<std::size_t>(1 + rng() % 64, s.size() - at);
        for (std::size_t i = 0; i < n; ++i) s[at + i] = static_cast<char>(rng());
        break;
      }
      case 2: {  // cut a span
        const std::size_t n = std::min<std::size_t>(1 + rng() % 256, s.size() - at);
        s.erase(at, n);
        break;
      }
      case 3: {  // duplicate a span
        const std::size_t n = std::min<std::size_t>(1 + rng() % 256, s.size() - at);
        s.insert(at, s.substr(at, n));
        break;
      }
      case 4: {  // a number -> an extreme value
        std::size_t b = s.find_first_of("0123456789", at);
        if (b == std::string::npos) break;
        std::size_t e = s.find_first_not_of("0123456789.eE+-", b);
        if (e == std::string::npos) e = s.size();
        s.replace(b, e - b, kExtremes[rng() % (sizeof kExtremes / sizeof *kExtremes)]);
        break;
      }
      default: {  // a line -> repeated many times (size bounds)
        const std::size_t b = s.rfind('\n', at), e = s.find('\n', at);
        const std::size_t from = b == std::string::npos ? 0 : b + 1;
        const std::string line = s.substr(from, (e == std::string::npos ? s.size() : e) - from) + "\n";
        // Repeated rounds on a long line would compound (x200 each: seed
        // 3005, mutant 88 reached 2.2 GB in this function, before any
        // reader ran); the readers' size bounds are met well below this.
        if (s.size() + 200 * line.size() > kMaxMutant) break;
        std::string many;
        for (int i = 0; i < 200; ++i) many += line;
        s.insert(from, many);
        break;
      }
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr,
                 "usage: layers_fuzz <bvh|yaml|h5> <seed file> <iterations> <rng seed> <work dir> [regressions...]\n");
    return 2;
  }
  const std::string kind = argv[1], seed_file = argv[2], work = argv[5];
  const long iterations = std::atol(argv[3]);
  std::mt19937_64 rng(std::strtoull(argv[4], nullptr, 10));
  void (*parse)(const std::string&, const std::string&) = kind == "bvh"    ? parse_bvh
                                                          : kind == "yaml" ? parse_yaml
                                                          : kind == "h5"   ? parse_h5
                                                                           : nullptr;
  if (!parse) {
    std::fprintf(stderr, "layers_fuzz: unknown reader '%s' (bvh, yaml or h5)\n", kind.c_str());
    return 2;
  }
  // Memory proportional to the input: a reader that grows without bound
  // meets this limit as std::bad_alloc, which counts as a finding.
  const rlim_t limit = 4ull << 30;
  rlimit rl{limit, limit};
  setrlimit(RLIMIT_AS, &rl);

  fs::create_directories(work);
  const std::string current = work + "/current." + kind;
  const std::string seed = read_bytes(seed_file);
  if (seed.empty()) {
    std::fprintf(stderr, "layers_fuzz: empty or missing seed file %s\n", seed_file.c_str());
    return 2;
  }
  std::vector<std::string> inputs;
  for (int i = 6; i < argc; ++i) inputs.push_back(read_bytes(argv[i]));
  const std::size_t regressions = inputs.size();
  long refused = 0, accepted = 0;
  for (long i = 0; i < static_cast<long>(regressions) + iterations; ++i) {
    const std::string bytes =
        i < static_cast<long>(regressions) ? inputs[static_cast<std::size_t>(i)] : mutate(seed, rng, kind != "h5");
    write_file(current, bytes);
    try {
      parse(bytes, current);
      ++accepted;
    } catch (const Error&) {
      ++refused;  // the expected answer to bad input (InputError is an Error)
    } catch (const std::exception& e) {
      const std::string finding = work + "/finding." + kind;
      write_file(finding, bytes);
      std::printf(
          "layers_fuzz %s: input %ld: %s: %s (saved as %s)\n", kind.c_str(), i,
          dynamic_cast<const std::bad_alloc*>(&e) ? "allocation beyond the memory limit" : "unexpected exception",
          e.what(), finding.c_str());
      return 1;
    } catch (...) {  // e.g. an HDF5 exception that escaped its translation
      const std::string finding = work + "/finding." + kind;
      write_file(finding, bytes);
      std::printf("layers_fuzz %s: input %ld: an exception that is not a std::exception (saved as %s)\n", kind.c_str(),
                  i, finding.c_str());
      return 1;
    }
  }
  fs::remove(current);
  std::printf(
      "layers_fuzz %s: %zu regression inputs and %ld mutants of %s: %ld refused with an error, %ld accepted, "
      "no crash\n",
      kind.c_str(), regressions, iterations, seed_file.c_str(), refused, accepted);
  return 0;
}
