// Walks the global heap collections of an HDF5 file (see h5_heap_check.h;
// the layout is the HDF5 file format specification's "Global Heap": a
// 16-byte collection header -- signature, version, 3 reserved bytes, the
// collection's size -- then objects of a 16-byte header -- index, reference
// count, 4 reserved bytes, size -- and their data padded to 8 bytes; index
// 0 is the free space that ends the list).
#include "h5_heap_check.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string_view>
#include <tuple>
#include <vector>

#include "layers/core/error.h"

namespace layers::data::h5 {
namespace {

constexpr std::array<char, 8> kSignature = {'G', 'C', 'O', 'L', 1, 0, 0, 0};

std::uint64_t little_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int k = 7; k >= 0; --k) v = (v << 8) | p[k];
  return v;
}

std::uint16_t little_u16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }

// "" when the collection at `at` is whole, else what is wrong with it.
std::string check_collection(std::ifstream& in, std::uint64_t at, std::uint64_t file_size) {
  unsigned char header[16];
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  if (!in.read(reinterpret_cast<char*>(header), sizeof header)) return "a collection header cut by the file's end";
  const std::uint64_t size = little_u64(header + 8);
  if (size < 16 || size > file_size - at)
    return "a collection of " + std::to_string(size) + " bytes, " + std::to_string(file_size - at) +
           " left in the file";
  std::vector<unsigned char> body(static_cast<std::size_t>(size - 16));
  if (!in.read(reinterpret_cast<char*>(body.data()), static_cast<std::streamsize>(body.size())))
    return "a collection cut by the file's end";
  std::size_t p = 0;
  while (p + 16 <= body.size()) {
    const std::uint16_t index = little_u16(&body[p]);
    const std::uint64_t object = little_u64(&body[p + 8]);
    if (index == 0) break;  // the free space: the end of the objects
    const std::uint64_t room = body.size() - p - 16;
    const std::uint64_t padded = object > room ? object : (object + 7) / 8 * 8;
    if (padded > room)
      return "object " + std::to_string(index) + " of " + std::to_string(object) + " bytes, " + std::to_string(room) +
             " left in its collection of " + std::to_string(size);
    p += 16 + static_cast<std::size_t>(padded);
  }
  return {};
}

// The first damaged collection's description, "" when none is.
std::string scan(const std::string& path, std::uint64_t file_size) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "global heap", "a readable file", "it cannot be opened");
  std::ifstream probe(path, std::ios::binary);
  constexpr std::size_t kBlock = 1 << 20;
  std::vector<char> block(kBlock + kSignature.size());
  std::size_t carried = 0;  // bytes kept from the previous block (a signature across the boundary)
  std::uint64_t block_start = 0;
  while (in) {
    in.read(block.data() + carried, static_cast<std::streamsize>(kBlock));
    const std::size_t got = carried + static_cast<std::size_t>(in.gcount());
    if (got < kSignature.size()) break;
    const std::string_view view(block.data(), got);
    const std::string_view signature(kSignature.data(), kSignature.size());
    for (std::size_t at = view.find(signature); at != std::string_view::npos; at = view.find(signature, at + 1)) {
      const std::string what = check_collection(probe, block_start + at, file_size);
      if (!what.empty()) return "at byte " + std::to_string(block_start + at) + ": " + what;
    }
    carried = kSignature.size() - 1;
    std::memmove(block.data(), block.data() + got - carried, carried);
    block_start += got - carried;
  }
  return {};
}

}  // namespace

void check_global_heaps(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::uint64_t size = fs::file_size(path, ec);
  if (ec) return;  // not a path we can read again: HDF5 reports what it finds
  const auto time = fs::last_write_time(path, ec);
  using Key = std::tuple<std::string, std::uint64_t, fs::file_time_type::rep>;
  static std::map<Key, std::string> verdicts;
  const Key key{path, size, ec ? 0 : time.time_since_epoch().count()};
  auto it = verdicts.find(key);
  if (it == verdicts.end()) it = verdicts.emplace(key, scan(path, size)).first;
  if (!it->second.empty())
    throw InputError(path, "global heap",
                     "intact variable-length strings (HDF5's global heap, which has no checksum; a file written "
                     "before strings were stored fixed-length)",
                     "a damaged collection " + it->second);
}

}  // namespace layers::data::h5
