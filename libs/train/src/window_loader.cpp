// The prefetching window loader (see window_loader.h).
#include "layers/train/window_loader.h"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <list>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include "layers/core/error.h"

namespace layers::train {

std::vector<std::string> select_sequences(const data::Dataset& dataset, const std::string& split,
                                          const std::vector<std::string>& subsets) {
  const std::vector<std::string>& ids = dataset.splits().get(split);
  if (subsets.empty()) return ids;
  std::set<std::string> keep;
  for (const std::string& s : subsets)
    for (const std::string& id : dataset.splits().get(s)) keep.insert(id);
  std::vector<std::string> out;
  for (const std::string& id : ids)
    if (keep.count(id)) out.push_back(id);
  return out;
}

struct WindowLoader::Impl {
  const data::Dataset& dataset;
  LoaderOptions options;
  std::vector<std::string> ids;

  // Converted statics, most recently used first (touched by the loader thread only).
  std::list<std::pair<std::string, std::shared_ptr<const zoo::SequenceStatic>>> cache;

  // Epoch state shared with the loader thread.
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Batch> queue;
  std::exception_ptr error;
  bool producer_done = false, stop = false;
  std::size_t batches = 0, delivered = 0;
  std::thread worker;

  Impl(const data::Dataset& d, LoaderOptions o) : dataset(d), options(std::move(o)) {
    ids = select_sequences(dataset, options.split, options.subsets);
  }

  std::shared_ptr<const zoo::SequenceStatic> statics(const std::string& id) {
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (it->first == id) {
        cache.splice(cache.begin(), cache, it);
        return it->second;
      }
    }
    auto s = std::make_shared<const zoo::SequenceStatic>(to_model_static(*dataset.statics(id), options.selection));
    cache.emplace_front(id, s);
    while (cache.size() > std::max<std::size_t>(options.static_cache, 1)) cache.pop_back();
    return s;
  }

  void halt() {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    changed.notify_all();
    if (worker.joinable()) worker.join();
  }

  void produce(std::vector<WindowRef> order, std::int64_t horizon) {
    try {
      const std::size_t bs = static_cast<std::size_t>(options.batch_size);
      for (std::size_t b = 0; b < batches; ++b) {
        Batch batch;
        for (std::size_t i = b * bs; i < std::min(order.size(), (b + 1) * bs); ++i) {
          const WindowRef& ref = order[i];
          Sample sample;
          sample.id = ref.id;
          sample.start = ref.start;
          sample.statics = statics(ref.id);
          const data::Window w = dataset.read_window(ref.id, ref.start, options.history, horizon);
          sample.frames = to_frame_tensors(w, dataset.statics(ref.id)->garments, options.selection);
          batch.push_back(std::move(sample));
        }
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return stop || queue.size() < static_cast<std::size_t>(options.prefetch); });
        if (stop) return;
        queue.push_back(std::move(batch));
        changed.notify_all();
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    producer_done = true;
    changed.notify_all();
  }
};

WindowLoader::WindowLoader(const data::Dataset& dataset, LoaderOptions options)
    : impl_(std::make_unique<Impl>(dataset, std::move(options))) {}

WindowLoader::~WindowLoader() { impl_->halt(); }

const std::vector<std::string>& WindowLoader::sequences() const { return impl_->ids; }

std::size_t WindowLoader::windows(std::int64_t horizon) const {
  return all_windows(impl_->dataset, impl_->ids, impl_->options, horizon).size();
}

std::vector<WindowRef> all_windows(const data::Dataset& dataset, const std::vector<std::string>& sequences,
                                   const LoaderOptions& options, std::int64_t horizon) {
  std::vector<WindowRef> out;
  for (const std::string& id : sequences) {
    const std::int64_t n = dataset.info(id).n_frames;
    for (std::int64_t s = options.history; s + horizon < n; s += options.stride) out.push_back({id, s});
  }
  return out;
}

std::vector<WindowRef> epoch_windows(const data::Dataset& dataset, const std::vector<std::string>& sequences,
                                     const LoaderOptions& options, int epoch, std::int64_t horizon) {
  std::vector<WindowRef> order = all_windows(dataset, sequences, options, horizon);
  if (order.empty()) {
    throw InputError(
        dataset.path(), "split '" + options.split + "'",
        "sequences longer than " + std::to_string(options.history + horizon) + " frames (history + horizon)",
        std::to_string(sequences.size()) + " sequences, none long enough");
  }
  std::mt19937_64 rng(options.seed * 1000003ULL + static_cast<std::uint64_t>(epoch));
  std::shuffle(order.begin(), order.end(), rng);
  if (options.windows_per_epoch > 0 && order.size() > static_cast<std::size_t>(options.windows_per_epoch))
    order.resize(static_cast<std::size_t>(options.windows_per_epoch));
  if (options.world > 1) {
    // Every rank runs the same number of equal batches (the gradients are
    // averaged over ranks); up to world - 1 windows are left for this epoch.
    const std::size_t world = static_cast<std::size_t>(options.world);
    std::vector<WindowRef> mine;
    for (std::size_t i = static_cast<std::size_t>(options.rank); i + (order.size() % world) < order.size(); i += world)
      mine.push_back(order[i]);
    if (mine.empty())
      throw InputError(dataset.path(), "split '" + options.split + "'",
                       "at least one window per rank (" + std::to_string(world) + " ranks)",
                       std::to_string(order.size()) + " windows");
    order = std::move(mine);
  }
  return order;
}

std::size_t WindowLoader::start_epoch(int epoch, std::int64_t horizon) {
  Impl& m = *impl_;
  m.halt();
  std::vector<WindowRef> order = epoch_windows(m.dataset, m.ids, m.options, epoch, horizon);
  const std::size_t bs = static_cast<std::size_t>(m.options.batch_size);
  m.queue.clear();
  m.error = nullptr;
  m.stop = m.producer_done = false;
  m.batches = (order.size() + bs - 1) / bs;
  m.delivered = 0;
  m.worker = std::thread([&m, order = std::move(order), horizon]() mutable { m.produce(std::move(order), horizon); });
  return m.batches;
}

std::optional<Batch> WindowLoader::next() {
  Impl& m = *impl_;
  std::unique_lock<std::mutex> lock(m.mutex);
  m.changed.wait(lock, [&] { return !m.queue.empty() || m.producer_done || m.error; });
  if (!m.queue.empty()) {
    Batch b = std::move(m.queue.front());
    m.queue.pop_front();
    ++m.delivered;
    m.changed.notify_all();
    return b;
  }
  if (m.error) std::rethrow_exception(m.error);
  return std::nullopt;
}

}  // namespace layers::train
