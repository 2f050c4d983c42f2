// Typed HDF5 helpers, the HDF5 mutex and error translation (see h5_io.h).
#include "h5_io.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "h5_heap_check.h"
#include "layers/core/error.h"

namespace layers::data::h5 {
namespace {

std::recursive_mutex& hdf5_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

herr_t innermost_entry(unsigned /*n*/, const H5E_error2_t* entry, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (out->empty() && entry != nullptr && entry->desc != nullptr && entry->desc[0] != '\0') {
    *out = entry->desc;
  }
  return 0;
}

// The name of the file holding object `id` ("" when HDF5 cannot say).
std::string file_of(hid_t id) {
  const ssize_t n = H5Fget_name(id, nullptr, 0);
  if (n <= 0) return {};
  std::string name(static_cast<std::size_t>(n) + 1, '\0');
  H5Fget_name(id, name.data(), name.size());
  name.resize(static_cast<std::size_t>(n));
  return name;
}

// Reads every element of a string dataset or attribute (`object`). `read`
// reads the whole extent into a buffer with a given memory type.
// Variable-length strings are read only from a file whose global heap is
// whole (h5_heap_check.h).
template <class ReadFn>
std::vector<std::string> read_string_values(hid_t object, const H5::StrType& file_type, hssize_t n,
                                            const H5::DataSpace& space, ReadFn&& read) {
  std::vector<std::string> out;
  if (n <= 0) return out;
  out.reserve(static_cast<std::size_t>(n));
  if (file_type.isVariableStr()) {
    const std::string file = file_of(object);
    if (!file.empty()) check_global_heaps(file);
    H5::StrType mem(H5::PredType::C_S1, H5T_VARIABLE);
    mem.setCset(file_type.getCset());
    std::vector<char*> buffer(static_cast<std::size_t>(n), nullptr);
    read(buffer.data(), mem);
    for (char* s : buffer) out.emplace_back(s != nullptr ? s : "");
    H5Dvlen_reclaim(mem.getId(), space.getId(), H5P_DEFAULT, buffer.data());
  } else {
    const std::size_t len = file_type.getSize();
    std::vector<char> buffer(static_cast<std::size_t>(n) * len);
    read(buffer.data(), file_type);
    for (hssize_t i = 0; i < n; ++i) {
      const char* s = buffer.data() + static_cast<std::size_t>(i) * len;
      out.emplace_back(s, strnlen(s, len));
    }
  }
  return out;
}

// Strings are written fixed-length (null-padded UTF-8, as long as the
// longest value): they then live in the object header (attributes) or in a
// checksummed chunk (datasets), never in HDF5's global heap, which has no
// checksum -- a damaged heap entry crashed libhdf5 1.10.8 in our fuzzing.
// Readers accept variable-length strings too (files written before).
H5::StrType fixed_utf8(const std::vector<std::string>& values) {
  std::size_t longest = 1;
  for (const auto& v : values) longest = std::max(longest, v.size());
  H5::StrType type(H5::PredType::C_S1, longest);
  type.setCset(H5T_CSET_UTF8);
  type.setStrpad(H5T_STR_NULLPAD);
  return type;
}

// `values` packed into a fixed-length buffer of `type`.
std::vector<char> packed(const std::vector<std::string>& values, const H5::StrType& type) {
  const std::size_t len = type.getSize();
  std::vector<char> buffer(values.size() * len, '\0');
  for (std::size_t i = 0; i < values.size(); ++i)
    std::copy(values[i].begin(), values[i].end(), buffer.begin() + i * len);
  return buffer;
}

void remove_attr_if_present(H5::H5Object& obj, const std::string& name) {
  if (obj.attrExists(name)) obj.removeAttr(name);
}

template <class T>
void set_numeric_attr(H5::H5Object& obj, const std::string& name, const H5::PredType& file_type,
                      const H5::PredType& mem_type, T value) {
  remove_attr_if_present(obj, name);
  H5::Attribute attr = obj.createAttribute(name, file_type, H5::DataSpace(H5S_SCALAR));
  attr.write(mem_type, &value);
}

template <class T>
T read_numeric_attr(const H5::H5Object& obj, const std::string& name, const H5::PredType& mem_type) {
  T value{};
  obj.openAttribute(name).read(mem_type, &value);
  return value;
}

}  // namespace

Lock::Lock() {
  hdf5_mutex().lock();
  static const bool quiet = [] {
    H5::Exception::dontPrint();
    return true;
  }();
  (void)quiet;
}

Lock::~Lock() { hdf5_mutex().unlock(); }

std::string error_text(const H5::Exception& e) {
  std::string inner;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost_entry, &inner);
  std::string text = e.getDetailMsg();
  if (!inner.empty() && text.find(inner) == std::string::npos) text += " (" + inner + ")";
  return text;
}

std::string damage_text(const H5::Exception& e) {
  const std::string detail = error_text(e);
  // The part of the file the failing HDF5 call reads, by its API prefix
  // ("H5Aexists failed", "H5Oget_info_by_name failed", ...).
  static const std::pair<const char*, const char*> kParts[] = {
      {"H5Dread", "the array's values"}, {"H5D", "the array"}, {"H5A", "the attributes"}, {"H5G", "the group"},
      {"H5O", "the object header"},      {"H5L", "the link"},  {"H5F", "the file"},       {"H5T", "the data type"},
      {"H5S", "the array's shape"}};
  std::string part = "the file's structure";
  const std::size_t api = detail.find("H5");
  for (const auto& [prefix, name] : kParts) {
    if (api != std::string::npos && detail.compare(api, std::strlen(prefix), prefix) == 0) {
      part = name;
      break;
    }
  }
  if (detail.find("Fletcher32") != std::string::npos) return "expected chunks that pass their checksum, got " + detail;
  return "expected " + part + " readable, got a damaged or foreign file (HDF5: " + detail + ")";
}

void rethrow(const H5::Exception& e, const std::string& file, const std::string& object) {
  throw InputError::message(file, object, damage_text(e));
}

std::string dims_text(const Dims& dims) {
  std::ostringstream out;
  out << '[';
  for (std::size_t i = 0; i < dims.size(); ++i) out << (i ? "," : "") << dims[i];
  out << ']';
  return out.str();
}

std::string dtype_text(const H5::DataType& type) {
  const std::size_t bits = type.getSize() * 8;
  switch (type.getClass()) {
    case H5T_FLOAT:
      return "float" + std::to_string(bits);
    case H5T_INTEGER:
      return (H5Tget_sign(type.getId()) == H5T_SGN_NONE ? "uint" : "int") + std::to_string(bits);
    case H5T_STRING:
      return "string";
    case H5T_COMPOUND:
      return "compound";
    case H5T_ENUM:
      return "enum";
    case H5T_ARRAY:
      return "array";
    case H5T_VLEN:
      return "vlen";
    default:
      return "other";
  }
}

bool dtype_matches(const H5::DataType& type, DType expected) {
  switch (expected) {
    case DType::Float32:
      return type.getClass() == H5T_FLOAT && type.getSize() == 4;
    case DType::Float64:
      return type.getClass() == H5T_FLOAT && type.getSize() == 8;
    case DType::Int32:
      return type.getClass() == H5T_INTEGER && type.getSize() == 4 && H5Tget_sign(type.getId()) == H5T_SGN_2;
    case DType::String:
      return type.getClass() == H5T_STRING;
  }
  return false;
}

H5::H5File create_file(const std::string& path) {
  Lock lock;
  // File format of HDF5 1.8 and later: the superblock, object headers and
  // chunk indices carry their own checksums, so damaged metadata is refused
  // by the library instead of being parsed (an old-format header with
  // flipped bytes can crash libhdf5 itself). Every HDF5 >= 1.8 reads it.
  H5::FileAccPropList fapl;
  fapl.setLibverBounds(H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  // No modification time on the root group either: same data, same bytes.
  H5::FileCreatPropList fcpl;
  H5Pset_obj_track_times(fcpl.getId(), false);
  return H5::H5File(path, H5F_ACC_TRUNC, fcpl, fapl);
}

H5::H5File open_read(const std::string& path, const H5::FileAccPropList& fapl) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw InputError(path, "", "an existing dataset folder or HDF5 file", "nothing (no such file or folder)");
  if (fs::is_directory(path, ec)) throw InputError(path, "", "an HDF5 file", "a directory");
  // Before libhdf5 opens it: a FIFO would block, a device has no size.
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "", "an HDF5 file", "a pipe, socket or device");
  const auto size = fs::file_size(path, ec);
  Lock lock;
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(path, "", "an HDF5 file",
                     "no HDF5 signature (not an HDF5 file, " + std::to_string(size) + " bytes)");
  }
  try {
    return H5::H5File(path, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, fapl);
  } catch (const H5::Exception& e) {
    throw InputError::message(
        path, "",
        "cannot open the HDF5 file (" + std::to_string(size) + " bytes; truncated or damaged?): " + error_text(e));
  }
}

H5::FileAccPropList bounded_access(std::size_t chunk_cache_bytes) {
  Lock lock;
  H5::FileAccPropList fapl;
  fapl.setCache(0, 521, chunk_cache_bytes, 0.75);
  H5AC_cache_config_t config;
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Pget_mdc_config(fapl.getId(), &config) >= 0) {
    config.set_initial_size = true;
    config.min_size = 256 << 10;
    config.initial_size = 512 << 10;
    config.max_size = 4 << 20;
    H5Pset_mdc_config(fapl.getId(), &config);
  }
  return fapl;
}

bool exists(const H5::Group& loc, const std::string& path) {
  std::size_t pos = 0;
  while (true) {
    const std::size_t slash = path.find('/', pos);
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(loc.getId(), prefix.c_str(), H5P_DEFAULT) <= 0) {
      H5Eclear2(H5E_DEFAULT);
      return false;
    }
    if (slash == std::string::npos) return true;
    pos = slash + 1;
  }
}

bool is_dataset(const H5::Group& loc, const std::string& path) {
  return exists(loc, path) && loc.childObjType(path) == H5O_TYPE_DATASET;
}

std::vector<std::string> member_names(const H5::Group& group) {
  Lock lock;
  std::vector<std::string> names;
  const hsize_t n = group.getNumObjs();
  names.reserve(n);
  // Creation order where the group tracks it (the writer's groups do),
  // name order otherwise.
  for (hsize_t i = 0; i < n; ++i) {
    const ssize_t len =
        H5Lget_name_by_idx(group.getId(), ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) {
      H5Eclear2(H5E_DEFAULT);
      names.clear();
      for (hsize_t j = 0; j < n; ++j) names.push_back(group.getObjnameByIdx(j));
      return names;
    }
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group.getId(), ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    names.push_back(std::move(name));
  }
  return names;
}

namespace {
// Groups without modification times, so the same data gives the same bytes.
H5::Group create_group_with(H5::Group& parent, const std::string& name, bool ordered) {
  Lock lock;
  const hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, false);
  if (ordered) H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  const hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  if (id < 0) throw H5::GroupIException("create_group", "H5Gcreate2 failed for " + name);
  H5::Group group(id);
  H5Gclose(id);  // the C++ object took its own reference
  return group;
}
}  // namespace

H5::Group create_ordered_group(H5::Group& parent, const std::string& name) {
  return create_group_with(parent, name, true);
}

H5::Group create_group(H5::Group& parent, const std::string& name) { return create_group_with(parent, name, false); }

Dims dims_of(const H5::DataSet& ds) {
  H5::DataSpace space = ds.getSpace();
  const int rank = space.getSimpleExtentNdims();
  Dims dims(static_cast<std::size_t>(rank > 0 ? rank : 0));
  if (rank > 0) space.getSimpleExtentDims(dims.data());
  return dims;
}

H5::DataSet open_checked(const Where& where, const H5::Group& loc, const std::string& rel, DType dtype,
                         const Dims& expected) {
  const std::string expected_text = std::string(dtype_name(dtype)) + " " + dims_text(expected);
  return guard(where.file, where.object, [&] {
    if (!is_dataset(loc, rel))
      throw InputError(where.file, where.object, "dataset " + expected_text, "nothing (missing)");
    H5::DataSet ds = loc.openDataSet(rel);
    const Dims got = dims_of(ds);
    const H5::DataType type = ds.getDataType();
    if (!dtype_matches(type, dtype) || got != expected) {
      throw InputError(where.file, where.object, expected_text, dtype_text(type) + " " + dims_text(got));
    }
    return ds;
  });
}

// A dataset's read failed: with a Fletcher32 filter the chunk is damaged
// (or unreadable), which says more than HDF5's "H5Dread failed".
[[noreturn]] static void rethrow_read(const H5::Exception& e, const H5::DataSet& ds) {
  const H5::DSetCreatPropList plist = ds.getCreatePlist();
  unsigned flags = 0, config = 0;
  std::size_t n = 0;
  char name[32];
  const bool checksummed =
      H5Pget_filter_by_id2(plist.getId(), H5Z_FILTER_FLETCHER32, &flags, &n, nullptr, sizeof name, name, &config) >= 0;
  if (checksummed)
    throw H5::DataSetIException(
        "",
        "a chunk that fails its Fletcher32 checksum or cannot be decoded: the file is damaged (" + error_text(e) + ")");
  throw;
}

template <class T>
void read_rows_into(const H5::DataSet& ds, const Dims& dims, hsize_t first, hsize_t count, T* out) {
  if (count == 0) return;
  bool empty = false;
  for (hsize_t d : dims) empty |= d == 0;
  if (empty) return;
  Dims start(dims.size(), 0), extent = dims;
  start[0] = first;
  extent[0] = count;
  H5::DataSpace file_space = ds.getSpace();
  file_space.selectHyperslab(H5S_SELECT_SET, extent.data(), start.data());
  H5::DataSpace mem_space(static_cast<int>(extent.size()), extent.data());
  try {
    ds.read(out, Native<T>::mem(), mem_space, file_space);
  } catch (const H5::Exception& e) {
    rethrow_read(e, ds);
  }
}

template <class T>
std::vector<T> read_all(const Where& where, const H5::Group& loc, const std::string& rel, const Dims& expected) {
  Lock lock;
  return guard(where.file, where.object, [&] {
    H5::DataSet ds = open_checked(where, loc, rel, Native<T>::dtype, expected);
    std::size_t n = 1;
    for (hsize_t d : expected) n *= d;
    std::vector<T> out(n);
    if (n > 0) {
      try {
        ds.read(out.data(), Native<T>::mem());
      } catch (const H5::Exception& e) {
        rethrow_read(e, ds);
      }
    }
    return out;
  });
}

template <class T>
std::vector<T> read_rows(const Where& where, const H5::Group& loc, const std::string& rel, const Dims& expected,
                         hsize_t first, hsize_t count) {
  Lock lock;
  return guard(where.file, where.object, [&] {
    H5::DataSet ds = open_checked(where, loc, rel, Native<T>::dtype, expected);
    if (expected.empty() || first + count > expected[0]) {
      throw InputError(where.file, where.object,
                       "rows within [0," + std::to_string(expected.empty() ? 0 : expected[0]) + ")",
                       "rows [" + std::to_string(first) + "," + std::to_string(first + count) + ")");
    }
    std::size_t row = 1;
    for (std::size_t i = 1; i < expected.size(); ++i) row *= expected[i];
    std::vector<T> out(row * count);
    read_rows_into(ds, expected, first, count, out.data());
    return out;
  });
}

std::vector<std::string> read_strings(const H5::DataSet& ds) {
  Lock lock;
  const H5::StrType type = ds.getStrType();
  const H5::DataSpace space = ds.getSpace();
  return read_string_values(ds.getId(), type, space.getSimpleExtentNpoints(), space,
                            [&](void* buffer, const H5::DataType& mem) { ds.read(buffer, mem); });
}

std::vector<std::string> read_strings(const Where& where, const H5::Group& loc, const std::string& rel,
                                      const Dims& expected) {
  Lock lock;
  return guard(where.file, where.object,
               [&] { return read_strings(open_checked(where, loc, rel, DType::String, expected)); });
}

template <class T>
void write(H5::Group& loc, const std::string& name, const std::vector<T>& data, const Dims& dims, bool chunk_by_frame) {
  Lock lock;
  H5::DataSpace space(static_cast<int>(dims.size()), dims.data());
  H5::DSetCreatPropList plist;
  H5Pset_obj_track_times(plist.getId(), false);  // same data, same bytes
  bool any_zero = false;
  for (hsize_t d : dims) any_zero |= d == 0;
  if (!dims.empty() && !any_zero) {
    // Every non-empty numeric dataset is chunked (a frame per chunk, or the
    // whole array as one) so that it can carry a Fletcher32 checksum per
    // chunk: a read of a damaged chunk fails instead of returning garbage.
    Dims chunk = dims;
    if (chunk_by_frame) chunk[0] = 1;
    plist.setChunk(static_cast<int>(chunk.size()), chunk.data());
    plist.setFletcher32();
  }
  H5::DataSet ds = loc.createDataSet(name, Native<T>::file(), space, plist);
  if (!data.empty()) ds.write(data.data(), Native<T>::mem());
}

void write_strings(H5::Group& loc, const std::string& name, const std::vector<std::string>& values) {
  Lock lock;
  const H5::StrType type = fixed_utf8(values);
  const Dims dims{values.size()};
  H5::DSetCreatPropList plist;
  H5Pset_obj_track_times(plist.getId(), false);
  if (!values.empty()) {
    plist.setChunk(1, dims.data());
    plist.setFletcher32();
  }
  H5::DataSet ds = loc.createDataSet(name, type, H5::DataSpace(1, dims.data()), plist);
  if (!values.empty()) ds.write(packed(values, type).data(), type);
}

void set_attr(H5::H5Object& obj, const std::string& name, const std::string& value) {
  Lock lock;
  remove_attr_if_present(obj, name);
  const H5::StrType type = fixed_utf8({value});
  H5::Attribute attr = obj.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attr.write(type, packed({value}, type).data());
}

void set_attr(H5::H5Object& obj, const std::string& name, std::int64_t value) {
  Lock lock;
  set_numeric_attr(obj, name, H5::PredType::STD_I64LE, H5::PredType::NATIVE_INT64, value);
}

void set_attr(H5::H5Object& obj, const std::string& name, std::uint64_t value) {
  Lock lock;
  set_numeric_attr(obj, name, H5::PredType::STD_U64LE, H5::PredType::NATIVE_UINT64, value);
}

void set_attr(H5::H5Object& obj, const std::string& name, double value) {
  Lock lock;
  set_numeric_attr(obj, name, H5::PredType::IEEE_F64LE, H5::PredType::NATIVE_DOUBLE, value);
}

void set_attr(H5::H5Object& obj, const std::string& name, const std::vector<std::string>& values) {
  Lock lock;
  remove_attr_if_present(obj, name);
  const H5::StrType type = fixed_utf8(values);
  const Dims dims{values.size()};
  H5::DataSpace space = values.empty() ? H5::DataSpace(H5S_NULL) : H5::DataSpace(1, dims.data());
  H5::Attribute attr = obj.createAttribute(name, type, space);
  if (!values.empty()) attr.write(type, packed(values, type).data());
}

AttrKind attr_kind(const H5::H5Object& obj, const std::string& name) {
  Lock lock;
  if (!obj.attrExists(name)) return AttrKind::Missing;
  const H5::Attribute attr = obj.openAttribute(name);
  const H5::DataSpace space = attr.getSpace();
  const hssize_t n = space.getSimpleExtentType() == H5S_NULL ? 0 : space.getSimpleExtentNpoints();
  switch (attr.getTypeClass()) {
    case H5T_STRING:
      return AttrKind::String;
    case H5T_INTEGER:
      return n == 1 ? AttrKind::Integer : AttrKind::Other;
    case H5T_FLOAT:
      return n == 1 ? AttrKind::Float : AttrKind::Other;
    default:
      return AttrKind::Other;
  }
}

const char* attr_kind_text(AttrKind kind) {
  switch (kind) {
    case AttrKind::Missing:
      return "nothing (missing)";
    case AttrKind::String:
      return "a string";
    case AttrKind::Integer:
      return "an integer";
    case AttrKind::Float:
      return "a float";
    case AttrKind::Other:
      return "another type (array or non-numeric)";
  }
  return "?";
}

std::vector<std::string> attr_names(const H5::H5Object& obj) {
  Lock lock;
  std::vector<std::string> names;
  const int n = obj.getNumAttrs();
  for (int i = 0; i < n; ++i) names.push_back(obj.openAttribute(static_cast<unsigned>(i)).getName());
  return names;
}

std::vector<std::string> attr_strings(const H5::H5Object& obj, const std::string& name) {
  Lock lock;
  const H5::Attribute attr = obj.openAttribute(name);
  const H5::DataSpace space = attr.getSpace();
  const hssize_t n = space.getSimpleExtentType() == H5S_NULL ? 0 : space.getSimpleExtentNpoints();
  return read_string_values(attr.getId(), attr.getStrType(), n, space,
                            [&](void* buffer, const H5::DataType& mem) { attr.read(mem, buffer); });
}

std::string attr_string(const H5::H5Object& obj, const std::string& name) {
  const auto values = attr_strings(obj, name);
  return values.empty() ? std::string() : values.front();
}

std::int64_t attr_int(const H5::H5Object& obj, const std::string& name) {
  Lock lock;
  return read_numeric_attr<std::int64_t>(obj, name, H5::PredType::NATIVE_INT64);
}

std::uint64_t attr_uint(const H5::H5Object& obj, const std::string& name) {
  Lock lock;
  return read_numeric_attr<std::uint64_t>(obj, name, H5::PredType::NATIVE_UINT64);
}

double attr_double(const H5::H5Object& obj, const std::string& name) {
  Lock lock;
  return read_numeric_attr<double>(obj, name, H5::PredType::NATIVE_DOUBLE);
}

#define LAYERS_H5_INSTANTIATE(T)                                                                                 \
  template std::vector<T> read_all<T>(const Where&, const H5::Group&, const std::string&, const Dims&);          \
  template std::vector<T> read_rows<T>(const Where&, const H5::Group&, const std::string&, const Dims&, hsize_t, \
                                       hsize_t);                                                                 \
  template void read_rows_into<T>(const H5::DataSet&, const Dims&, hsize_t, hsize_t, T*);                        \
  template void write<T>(H5::Group&, const std::string&, const std::vector<T>&, const Dims&, bool);
LAYERS_H5_INSTANTIATE(float)
LAYERS_H5_INSTANTIATE(std::int32_t)
LAYERS_H5_INSTANTIATE(double)
#undef LAYERS_H5_INSTANTIATE

}  // namespace layers::data::h5
