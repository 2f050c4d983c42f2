// POINTCACHE2 reading and writing, little-endian (see pc2.h).
#include "layers/data/pc2.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"

namespace layers::data {
namespace {

constexpr char kSignature[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr std::size_t kHeaderBytes = 32;

bool host_is_little_endian() {
  const std::uint32_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// 4-byte little-endian <-> host values (int32 or float32).
template <class T>
void put_le(unsigned char* out, T value) {
  static_assert(sizeof(T) == 4, "4-byte values only");
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, 4);
  for (int i = 0; i < 4; ++i) out[i] = static_cast<unsigned char>(bits >> (8 * i));
}

template <class T>
T get_le(const unsigned char* in) {
  static_assert(sizeof(T) == 4, "4-byte values only");
  std::uint32_t bits = 0;
  for (int i = 0; i < 4; ++i) bits |= std::uint32_t(in[i]) << (8 * i);
  T value;
  std::memcpy(&value, &bits, 4);
  return value;
}

std::uint64_t expected_size(const Pc2Header& h) {
  return kHeaderBytes + 12ull * static_cast<std::uint64_t>(h.n_points) * static_cast<std::uint64_t>(h.n_samples);
}

void check_header_values(const std::string& path, const Pc2Header& h) {
  if (h.n_points < 0) throw InputError(path, "numPoints", "a count >= 0", std::to_string(h.n_points));
  if (h.n_samples < 0) throw InputError(path, "numSamples", "a count >= 0", std::to_string(h.n_samples));
  if (!std::isfinite(h.start_frame))
    throw InputError(path, "startFrame", "a finite number", std::to_string(h.start_frame));
  if (!std::isfinite(h.sample_rate) || h.sample_rate <= 0.0f) {
    throw InputError(path, "sampleRate", "a finite number > 0", std::to_string(h.sample_rate));
  }
}

}  // namespace

struct Pc2Writer::Impl {
  explicit Impl(std::string path) : atomic(std::move(path)) {}
  AtomicPath atomic;
  std::ofstream out;
  Pc2Header header;
  std::int32_t written = 0;
  std::vector<unsigned char> buffer;
};

Pc2Writer::Pc2Writer(std::string path, Pc2Header header) : impl_(std::make_unique<Impl>(std::move(path))) {
  const std::string& target = impl_->atomic.target();
  check_header_values(target, header);
  impl_->header = header;
  impl_->out.open(impl_->atomic.temp(), std::ios::binary | std::ios::trunc);
  if (!impl_->out) throw InputError::message(target, "", "cannot create the file");
  unsigned char head[kHeaderBytes];
  std::memcpy(head, kSignature, 12);
  put_le(head + 12, std::int32_t{1});
  put_le(head + 16, header.n_points);
  put_le(head + 20, header.start_frame);
  put_le(head + 24, header.sample_rate);
  put_le(head + 28, header.n_samples);
  impl_->out.write(reinterpret_cast<const char*>(head), kHeaderBytes);
}

Pc2Writer::~Pc2Writer() = default;

void Pc2Writer::append(const float* xyz) {
  Impl& w = *impl_;
  if (w.written >= w.header.n_samples) {
    throw InputError(w.atomic.target(), "numSamples", std::to_string(w.header.n_samples) + " samples", "one more");
  }
  const std::size_t n = static_cast<std::size_t>(w.header.n_points) * 3;
  if (host_is_little_endian()) {
    w.out.write(reinterpret_cast<const char*>(xyz), static_cast<std::streamsize>(n * sizeof(float)));
  } else {
    w.buffer.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) put_le(w.buffer.data() + 4 * i, xyz[i]);
    w.out.write(reinterpret_cast<const char*>(w.buffer.data()), static_cast<std::streamsize>(w.buffer.size()));
  }
  ++w.written;
}

void Pc2Writer::commit() {
  Impl& w = *impl_;
  if (w.written != w.header.n_samples) {
    throw InputError(w.atomic.target(), "numSamples", std::to_string(w.header.n_samples) + " samples written",
                     std::to_string(w.written));
  }
  w.out.flush();
  const bool ok = static_cast<bool>(w.out);
  w.out.close();
  if (!ok) throw InputError::message(w.atomic.target(), "", "cannot write the file");
  w.atomic.commit();
}

void write_pc2(const std::string& path, const Pc2Cache& cache) {
  const std::size_t per_sample = static_cast<std::size_t>(std::max(cache.header.n_points, 0)) * 3;
  const std::size_t expected = per_sample * static_cast<std::size_t>(std::max(cache.header.n_samples, 0));
  if (cache.positions.size() != expected) {
    throw InputError(path, "positions", std::to_string(expected) + " floats (numSamples x numPoints x 3)",
                     std::to_string(cache.positions.size()));
  }
  Pc2Writer writer(path, cache.header);
  for (std::int32_t s = 0; s < cache.header.n_samples; ++s) writer.append(cache.positions.data() + s * per_sample);
  writer.commit();
}

Pc2Header read_pc2_header(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError::message(path, "", "cannot open the file (missing?)");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (size < kHeaderBytes) {
    throw InputError(path, "header", "at least 32 bytes (a POINTCACHE2 header)", std::to_string(size) + " bytes");
  }
  std::ifstream in(path, std::ios::binary);
  unsigned char head[kHeaderBytes];
  if (!in.read(reinterpret_cast<char*>(head), kHeaderBytes))
    throw InputError::message(path, "", "cannot read the header");
  if (std::memcmp(head, kSignature, 12) != 0) {
    std::string got;
    for (int i = 0; i < 11; ++i) got += std::isprint(head[i]) ? static_cast<char>(head[i]) : '?';
    throw InputError(path, "signature", "\"POINTCACHE2\\0\"", "\"" + got + "\"");
  }
  const auto version = get_le<std::int32_t>(head + 12);
  if (version != 1) throw InputError(path, "file version", "1", std::to_string(version));
  Pc2Header h;
  h.n_points = get_le<std::int32_t>(head + 16);
  h.start_frame = get_le<float>(head + 20);
  h.sample_rate = get_le<float>(head + 24);
  h.n_samples = get_le<std::int32_t>(head + 28);
  check_header_values(path, h);
  if (size != expected_size(h)) {
    throw InputError(path, "file size",
                     std::to_string(expected_size(h)) + " bytes (32 + 12 x " + std::to_string(h.n_points) +
                         " points x " + std::to_string(h.n_samples) + " samples)",
                     std::to_string(size) + " bytes");
  }
  return h;
}

Pc2Cache read_pc2(const std::string& path) {
  Pc2Cache cache;
  cache.header = read_pc2_header(path);
  const std::size_t n =
      static_cast<std::size_t>(cache.header.n_points) * 3 * static_cast<std::size_t>(cache.header.n_samples);
  std::vector<unsigned char> bytes(n * 4);
  std::ifstream in(path, std::ios::binary);
  in.seekg(kHeaderBytes);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    throw InputError::message(path, "", "cannot read the samples");
  }
  cache.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i) cache.positions[i] = get_le<float>(bytes.data() + 4 * i);
  return cache;
}

}  // namespace layers::data
