// layers/data/pc2.h -- POINTCACHE2 (.pc2) vertex caches, as read by
// Blender's Mesh Cache modifier.
//
// Little-endian layout: char[12] "POINTCACHE2\0", int32 version (1),
// int32 numPoints, float32 startFrame, float32 sampleRate, int32
// numSamples, then numSamples x numPoints x float32[3].
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace layers::data {

struct Pc2Header {
  std::int32_t n_points = 0;
  float start_frame = 0.0f;
  float sample_rate = 1.0f;
  std::int32_t n_samples = 0;
};

struct Pc2Cache {
  Pc2Header header;
  std::vector<float> positions;  // [n_samples, n_points, 3]
};

// Streams samples into a .pc2 file, written atomically by commit().
class Pc2Writer {
 public:
  Pc2Writer(std::string path, Pc2Header header);
  ~Pc2Writer();
  Pc2Writer(const Pc2Writer&) = delete;
  Pc2Writer& operator=(const Pc2Writer&) = delete;
  // One sample: n_points x 3 floats.
  void append(const float* xyz);
  // Throws if fewer or more samples than header.n_samples were appended.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

void write_pc2(const std::string& path, const Pc2Cache& cache);
// Checks signature, version, counts and that the file size matches the
// header; InputError otherwise.
Pc2Header read_pc2_header(const std::string& path);
Pc2Cache read_pc2(const std::string& path);

}  // namespace layers::data
