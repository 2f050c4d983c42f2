// Atomic shard writing (see shard_writer.h).
#include "layers/data/shard_writer.h"

#include <set>

#include "h5_io.h"
#include "integrity.h"
#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/content_hash.h"
#include "layers/data/format.h"
#include "sequence_io.h"

namespace layers::data {

struct ShardWriter::Impl {
  explicit Impl(std::string target) : atomic(std::move(target)) {}
  ~Impl() {
    h5::Lock lock;
    try {
      seqs.close();
      file.close();
    } catch (const H5::Exception&) {
      // The temporary file is removed by `atomic` anyway.
    }
  }
  AtomicPath atomic;  // destroyed last: removes the temporary unless committed
  H5::H5File file;
  H5::Group seqs;
  std::vector<std::string> ids;
  std::set<std::string> id_set;
  std::map<std::string, std::string> hashes;  // id -> content hash, the shard's own record
  bool failed = false, committed = false;

  void usable() const {
    if (committed) throw Error("ShardWriter(" + atomic.target() + "): already committed");
    if (failed) throw Error("ShardWriter(" + atomic.target() + "): an earlier write failed");
  }
};

ShardWriter::ShardWriter(std::string path) : impl_(std::make_unique<Impl>(std::move(path))) {
  h5::Lock lock;
  const std::string& target = impl_->atomic.target();
  h5::guard(target, "", [&] {
    impl_->file = h5::create_file(impl_->atomic.temp());
    H5::Group root = impl_->file.openGroup("/");
    h5::set_attr(root, "format", std::string(kFormatName));
    h5::set_attr(root, "format_version", kFormatVersion);
    h5::set_attr(root, "fps", kFps);
    h5::set_attr(root, "units", std::string(kUnits));
    h5::set_attr(root, "up", std::string(kUp));
    impl_->seqs = h5::create_ordered_group(root, "seq");
  });
}

ShardWriter::~ShardWriter() = default;

void ShardWriter::append(const SequenceData& seq) {
  impl_->usable();
  const std::string& target = impl_->atomic.target();
  check_sequence(seq, target);
  if (impl_->id_set.count(seq.id)) {
    throw InputError(target, "/seq/" + seq.id, "a sequence id not yet in the shard", "a duplicate id");
  }
  h5::Lock lock;
  try {
    write_sequence(impl_->seqs, seq);
  } catch (const H5::Exception& e) {
    impl_->failed = true;
    h5::rethrow(e, target, "/seq/" + seq.id);
  } catch (...) {
    impl_->failed = true;
    throw;
  }
  impl_->ids.push_back(seq.id);
  impl_->id_set.insert(seq.id);
  impl_->hashes[seq.id] = sequence_content_hash(seq);
}

std::size_t ShardWriter::size() const { return impl_->ids.size(); }
const std::vector<std::string>& ShardWriter::ids() const { return impl_->ids; }
const std::string& ShardWriter::path() const { return impl_->atomic.target(); }

void ShardWriter::commit() {
  impl_->usable();
  {
    h5::Lock lock;
    h5::guard(impl_->atomic.target(), "", [&] {
      write_shard_content_hashes(impl_->file, impl_->hashes);
      impl_->seqs.close();
      impl_->file.flush(H5F_SCOPE_GLOBAL);
      impl_->file.close();
    });
  }
  impl_->atomic.commit();
  impl_->committed = true;
}

void write_shard(const std::string& path, const std::vector<SequenceData>& sequences) {
  ShardWriter writer(path);
  for (const auto& seq : sequences) writer.append(seq);
  writer.commit();
}

}  // namespace layers::data
