// h5_io.h (private) -- small typed helpers over the HDF5 C++ API.
//
// Owns: the process-wide HDF5 mutex (HDF5 is not thread-safe), turning
// off HDF5's own error printing, turning H5::Exception into InputError
// naming the file and object, dtype names and checks, typed whole-array
// and hyperslab (row range) reads with dtype/shape checks, array writes
// (optionally chunked by frame), string arrays and attributes.
#pragma once

#include <H5Cpp.h>

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "layers/data/format.h"

namespace layers::data::h5 {

using Dims = std::vector<hsize_t>;

// Holds the process-wide HDF5 mutex (recursive) for its lifetime; the
// first one also switches off HDF5's automatic error printing.
class Lock {
 public:
  Lock();
  ~Lock();
  Lock(const Lock&) = delete;
  Lock& operator=(const Lock&) = delete;
};

// The message of an HDF5 failure: the C++ wrapper's text plus the innermost
// entry of HDF5's error stack (e.g. "truncated file: eof = ...").
std::string error_text(const H5::Exception& e);
// "expected <the part of the file> readable, got a damaged or foreign file
// (HDF5: ...)": the message of an HDF5 failure, in plain words.
std::string damage_text(const H5::Exception& e);
[[noreturn]] void rethrow(const H5::Exception& e, const std::string& file, const std::string& object);

// Runs f(); an H5::Exception becomes InputError(file, object).
template <class F>
auto guard(const std::string& file, const std::string& object, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const H5::Exception& e) {
    rethrow(e, file, object);
  }
}

// "[20,300,3]"
std::string dims_text(const Dims& dims);
// "float32", "float64", "int32", "uint8", "string", "compound", ...
std::string dtype_text(const H5::DataType& type);
bool dtype_matches(const H5::DataType& type, DType expected);

template <class T>
struct Native;
template <>
struct Native<float> {
  static const H5::PredType& mem() { return H5::PredType::NATIVE_FLOAT; }
  static const H5::PredType& file() { return H5::PredType::IEEE_F32LE; }
  static constexpr DType dtype = DType::Float32;
};
template <>
struct Native<std::int32_t> {
  static const H5::PredType& mem() { return H5::PredType::NATIVE_INT32; }
  static const H5::PredType& file() { return H5::PredType::STD_I32LE; }
  static constexpr DType dtype = DType::Int32;
};
template <>
struct Native<double> {
  static const H5::PredType& mem() { return H5::PredType::NATIVE_DOUBLE; }
  static const H5::PredType& file() { return H5::PredType::IEEE_F64LE; }
  static constexpr DType dtype = DType::Float64;
};

// Creates (truncates) an HDF5 file in the 1.8+ format, whose metadata
// carries checksums (every writer of the toolkit uses it).
H5::H5File create_file(const std::string& path);

// Opening files. open_read checks existence and the HDF5 signature first
// so that the errors say "does not exist" / "not an HDF5 file"; a
// truncated file fails with HDF5's own "truncated file" detail.
H5::H5File open_read(const std::string& path, const H5::FileAccPropList& fapl = H5::FileAccPropList::DEFAULT);
// File access list with a small raw-chunk cache and a small metadata cache.
H5::FileAccPropList bounded_access(std::size_t chunk_cache_bytes);

// Whether every component of a relative path exists below `loc`.
bool exists(const H5::Group& loc, const std::string& path);
bool is_dataset(const H5::Group& loc, const std::string& path);
// Member names, in creation order where the group tracks it.
std::vector<std::string> member_names(const H5::Group& group);
// A group that tracks the creation order of its members.
H5::Group create_ordered_group(H5::Group& parent, const std::string& name);
// A group without modification times (deterministic bytes).
H5::Group create_group(H5::Group& parent, const std::string& name);
Dims dims_of(const H5::DataSet& ds);

// A dataset to read: file (for messages), the dataset's full HDF5 path
// (for messages) and its location.
struct Where {
  const std::string& file;
  std::string object;  // full path, e.g. /seq/a/body/positions
};

// Opens `rel` below `loc` and checks dtype and shape; InputError
// "expected float32 [20,300,3], got float64 [20,300,3]" otherwise.
H5::DataSet open_checked(const Where& where, const H5::Group& loc, const std::string& rel, DType dtype,
                         const Dims& expected);

template <class T>
std::vector<T> read_all(const Where& where, const H5::Group& loc, const std::string& rel, const Dims& expected);
// Rows [first, first + count) along axis 0 of a dataset of shape `expected`.
template <class T>
std::vector<T> read_rows(const Where& where, const H5::Group& loc, const std::string& rel, const Dims& expected,
                         hsize_t first, hsize_t count);
// Rows of an already opened dataset (no checks).
template <class T>
void read_rows_into(const H5::DataSet& ds, const Dims& dims, hsize_t first, hsize_t count, T* out);

std::vector<std::string> read_strings(const Where& where, const H5::Group& loc, const std::string& rel,
                                      const Dims& expected);
std::vector<std::string> read_strings(const H5::DataSet& ds);

// Writes a dataset with a Fletcher32 checksum on each chunk; chunk_by_frame
// chunks as [1, dims[1:]...], otherwise the whole array is one chunk.
template <class T>
void write(H5::Group& loc, const std::string& name, const std::vector<T>& data, const Dims& dims,
           bool chunk_by_frame = false);
void write_strings(H5::Group& loc, const std::string& name, const std::vector<std::string>& values);

// Attributes.
void set_attr(H5::H5Object& obj, const std::string& name, const std::string& value);
void set_attr(H5::H5Object& obj, const std::string& name, std::int64_t value);
void set_attr(H5::H5Object& obj, const std::string& name, std::uint64_t value);
void set_attr(H5::H5Object& obj, const std::string& name, double value);
void set_attr(H5::H5Object& obj, const std::string& name, const std::vector<std::string>& values);

enum class AttrKind { Missing, String, Integer, Float, Other };
AttrKind attr_kind(const H5::H5Object& obj, const std::string& name);
const char* attr_kind_text(AttrKind kind);
std::vector<std::string> attr_names(const H5::H5Object& obj);
// Readers assume the kind was checked (String: scalar or array of strings).
std::string attr_string(const H5::H5Object& obj, const std::string& name);
std::vector<std::string> attr_strings(const H5::H5Object& obj, const std::string& name);
std::int64_t attr_int(const H5::H5Object& obj, const std::string& name);
std::uint64_t attr_uint(const H5::H5Object& obj, const std::string& name);
double attr_double(const H5::H5Object& obj, const std::string& name);

}  // namespace layers::data::h5
