// tests/fuzz/fuzz_readers.cpp -- a seeded mutation fuzzer for the readers
// that take user files: BVH clips, YAML configs (experiment and generator),
// LAYERS-H5 shards, and the importers of users' garments (OBJ, PLY, STL,
// glTF/GLB, a garment's side file) and meshes sequences (PC2). Each mutant of a seed file (bit flips, byte runs,
// cut and duplicated spans, numbers swapped for extreme values) goes
// through the real reader; an InputError (or another layers::Error) is the
// expected answer to bad input, anything else -- another exception, an
// allocation beyond the memory limit, a signal -- is a finding. The input
// being parsed is written to <work>/current.<ext> first, so a crash leaves
// it behind (scripts/fuzz.sh keeps it in tests/fuzz/regressions/).
//
//   layers_fuzz <bvh|yaml|h5|obj|ply|stl|glb|side|pc2> <seed file> <iterations> <rng seed> <work dir>
//               [regression files...]
//   layers_fuzz seed <obj|ply|stl|glb|side|pc2> <file>   writes the importer's built-in seed (a small tube)
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
#include "layers/data/glb.h"
#include "layers/data/pc2.h"
#include "layers/data/validate.h"
#include "layers/generate/generator_config.h"
#include "layers/import/body_import.h"
#include "layers/import/garment_file.h"
#include "layers/import/mesh_import.h"
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

std::string tube_obj();

// The importers: a garment mesh by its extension; a side file as
// <work>/tube.yaml beside a fixed mesh <work>/tube.obj; a PC2 cache of that
// mesh.
void parse_mesh(const std::string&, const std::string& path) { import::import_mesh(path); }

std::string fixed_tube(const std::string& path) {
  const fs::path mesh = fs::path(path).parent_path() / "tube.obj";
  if (!fs::exists(mesh)) write_file(mesh.string(), tube_obj());
  return mesh.string();
}

void parse_side(const std::string& bytes, const std::string& path) {
  const std::string mesh = fixed_tube(path);
  write_file(fs::path(mesh).replace_extension(".yaml").string(), bytes);
  import::read_garment_file("file:" + mesh);
}

void parse_pc2(const std::string&, const std::string& path) { import::import_mesh_sequence(path, fixed_tube(path)); }

// A tube of 8 x 2 quads (0.2 m radius, 0.5 m tall), open at both ends.
struct Tube {
  std::vector<float> xyz;
  std::vector<std::int32_t> faces;
  Tube() {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 8; ++c) {
        const double a = 2 * M_PI * c / 8;
        xyz.insert(xyz.end(), {static_cast<float>(0.2 * std::sin(a)), static_cast<float>(0.25 * r),
                               static_cast<float>(0.2 * std::cos(a))});
      }
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 8; ++c) {
        const int a = r * 8 + c, b = r * 8 + (c + 1) % 8;
        faces.insert(faces.end(), {a, b, b + 8, a, b + 8, a + 8});
      }
  }
  std::string obj() const {
    std::string s;
    for (std::size_t v = 0; v < xyz.size(); v += 3)
      s += "v " + std::to_string(xyz[v]) + " " + std::to_string(xyz[v + 1]) + " " + std::to_string(xyz[v + 2]) + "\n";
    for (std::size_t f = 0; f < faces.size(); f += 3)
      s += "f " + std::to_string(faces[f] + 1) + " " + std::to_string(faces[f + 1] + 1) + " " +
           std::to_string(faces[f + 2] + 1) + "\n";
    return s;
  }
};

std::string seed_bytes(const std::string& kind) {
  const Tube t;
  const std::size_t nv = t.xyz.size() / 3, nf = t.faces.size() / 3;
  if (kind == "obj") return t.obj();
  if (kind == "side") return "name: tube\nscale: 1.0\nself_contact: false\nattributes: {mass: 0.3, bending: 40}\n";
  if (kind == "ply") {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
    s.append(reinterpret_cast<const char*>(t.xyz.data()), t.xyz.size() * sizeof(float));
    for (std::size_t f = 0; f < t.faces.size(); f += 3) {
      s += static_cast<char>(3);
      s.append(reinterpret_cast<const char*>(&t.faces[f]), 3 * sizeof(std::int32_t));
    }
    return s;
  }
  if (kind == "stl") {
    std::string s(80, ' ');
    const auto count = static_cast<std::uint32_t>(nf);
    s.append(reinterpret_cast<const char*>(&count), 4);
    for (std::size_t f = 0; f < t.faces.size(); f += 3) {
      const float normal[3] = {0, 0, 0};
      s.append(reinterpret_cast<const char*>(normal), sizeof normal);
      for (int k = 0; k < 3; ++k)
        s.append(reinterpret_cast<const char*>(&t.xyz[3 * t.faces[f + k]]), 3 * sizeof(float));
      s.append(2, '\0');
    }
    return s;
  }
  if (kind == "glb") return data::glb_bytes({data::GlbMesh{"tube", t.faces, {t.xyz, t.xyz}}}, 30.0);
  return {};
}

std::string tube_obj() { return Tube().obj(); }

// Two frames of the tube, the second lifted 1 cm, as a .pc2 file.
void write_tube_pc2(const std::string& path) {
  const Tube t;
  data::Pc2Cache cache;
  cache.header.n_points = static_cast<std::int32_t>(t.xyz.size() / 3);
  cache.header.n_samples = 2;
  cache.positions = t.xyz;
  for (std::size_t v = 0; v < t.xyz.size(); v += 3)
    cache.positions.insert(cache.positions.end(), {t.xyz[v], t.xyz[v + 1] + 0.01f, t.xyz[v + 2]});
  data::write_pc2(path, cache);
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
  if (argc >= 2 && std::string(argv[1]) == "seed") {
    if (argc == 4 && std::string(argv[2]) == "pc2") {
      write_tube_pc2(argv[3]);
      return 0;
    }
    const std::string bytes = argc == 4 ? seed_bytes(argv[2]) : "";
    if (bytes.empty()) {
      std::fprintf(stderr, "usage: layers_fuzz seed <obj|ply|stl|glb|side|pc2> <file>\n");
      return 2;
    }
    write_file(argv[3], bytes);
    return 0;
  }
  if (argc < 6) {
    std::fprintf(
        stderr,
        "usage: layers_fuzz <bvh|yaml|h5|obj|ply|stl|glb|side|pc2> <seed file> <iterations> <rng seed> <work dir> "
        "[regressions...]\n");
    return 2;
  }
  const std::string kind = argv[1], seed_file = argv[2], work = argv[5];
  const long iterations = std::atol(argv[3]);
  std::mt19937_64 rng(std::strtoull(argv[4], nullptr, 10));
  const bool mesh = kind == "obj" || kind == "ply" || kind == "stl" || kind == "glb";
  const bool text = kind == "bvh" || kind == "yaml" || kind == "obj" || kind == "side";
  void (*parse)(const std::string&, const std::string&) = kind == "bvh"    ? parse_bvh
                                                          : kind == "yaml" ? parse_yaml
                                                          : kind == "h5"   ? parse_h5
                                                          : mesh           ? parse_mesh
                                                          : kind == "side" ? parse_side
                                                          : kind == "pc2"  ? parse_pc2
                                                                           : nullptr;
  if (!parse) {
    std::fprintf(stderr, "layers_fuzz: unknown reader '%s' (bvh, yaml, h5, obj, ply, stl, glb, side or pc2)\n",
                 kind.c_str());
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
        i < static_cast<long>(regressions) ? inputs[static_cast<std::size_t>(i)] : mutate(seed, rng, text);
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
