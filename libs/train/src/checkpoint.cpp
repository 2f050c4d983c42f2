// Checkpoint files (see checkpoint.h).
#include "layers/train/checkpoint.h"

#include <torch/optim/adam.h>
#include <torch/optim/optimizer.h>
#include <torch/serialize/input-archive.h>
#include <torch/serialize/output-archive.h>

#include <c10/util/Exception.h>
#include <c10/util/string_utils.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"

namespace layers::train {
namespace {

// Archive key of a statistic: "garment/position" -> "garment_position".
std::string norm_key(const char* quantity) {
  std::string key = quantity;
  std::replace(key.begin(), key.end(), '/', '_');
  return key;
}

// The file: a header line "layers-checkpoint 1 fnv1a64 <16 hex> <n>\n",
// then the n bytes of the torch archive the hash covers. A bare torch
// archive (no header, as written before checksums) is refused: its damage
// could not be told from its content.
constexpr const char* kMagic = "layers-checkpoint 1 fnv1a64 ";

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// The message of a LibTorch error without its backtrace, on one line.
std::string torch_message(const std::exception& e) {
  if (const auto* c10 = dynamic_cast<const c10::Error*>(&e)) return first_line(c10->what_without_backtrace());
  return first_line(e.what());
}

// What a header line may echo: printable ASCII as it is, other bytes as
// \xNN (a damaged or foreign file prints no raw bytes).
std::string printable(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out;
}

// The verified torch archive bytes of a checkpoint file; `checksum` gets
// the verified hash.
std::string checked_payload(const std::string& path, std::string& checksum) {
  // A regular file no larger than kMaxCheckpointBytes, checked before a
  // byte is read (a folder, a device such as /dev/zero or a huge file is
  // one line, not a read until memory runs out).
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw InputError(path, "checkpoint", "a checkpoint file (checkpoint-best.pt or checkpoint-last.pt)", "a folder");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, "checkpoint", "a regular file", "a device, pipe or other special file");
  const auto size_on_disk = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, "checkpoint", "a readable file", "cannot read its size: " + ec.message());
  if (size_on_disk > kMaxCheckpointBytes)
    throw InputError(path, "checkpoint", "at most " + std::to_string(kMaxCheckpointBytes >> 20) + " MiB",
                     std::to_string(size_on_disk >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "checkpoint", "a readable file", "cannot open it");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.rfind("PK\x03\x04", 0) == 0)
    throw InputError(path, "checkpoint", "a layers checkpoint (header '" + std::string(kMagic) + "...')",
                     "a bare torch archive without a checksum (damage to it could not be detected; retrain, or "
                     "resave it with a build from before this check)");
  const std::string magic = kMagic;
  const std::size_t eol = bytes.find('\n');
  if (bytes.rfind(magic, 0) != 0 || eol == std::string::npos || eol > 128)
    throw InputError(path, "checkpoint", "a layers checkpoint (header '" + magic + "...')",
                     bytes.empty() ? "an empty file" : "another file");
  char hex[17] = {};
  unsigned long long size = 0;
  if (std::sscanf(bytes.c_str() + magic.size(), "%16[0-9a-f] %llu", hex, &size) != 2)
    throw InputError(path, "checkpoint", "'" + magic + "<16 hex digits> <size>'",
                     "'" + printable(bytes.substr(0, eol)) + "'");
  const std::string payload = bytes.substr(eol + 1);
  if (payload.size() != size)
    throw InputError(path, "checkpoint", std::to_string(size) + " bytes after the header",
                     std::to_string(payload.size()) + " (truncated or damaged)");
  const std::string actual = content_hash(payload);
  if (actual != hex)
    throw InputError(path, "checksum", std::string("fnv1a64 ") + hex, actual + " (the file is damaged)");
  checksum = actual;
  return payload;
}

// Text as a tensor of its bytes (archives hold tensors).
void write_text(torch::serialize::OutputArchive& out, const std::string& key, const std::string& text) {
  std::vector<std::int64_t> bytes(text.begin(), text.end());
  out.write(key, at::tensor(bytes, at::kLong));
}

std::string text_of(const at::Tensor& bytes) {
  std::string text;
  for (std::int64_t i = 0; i < bytes.numel(); ++i) text.push_back(static_cast<char>(bytes[i].item<std::int64_t>()));
  return text;
}

at::Tensor read_tensor(torch::serialize::InputArchive& in, const std::string& key, const std::string& path) {
  at::Tensor t;
  if (!in.try_read(key, t)) throw InputError(path, key, "a tensor", "nothing (not a layers checkpoint?)");
  return t;
}

// Adam's state by parameter position ("<i>.step", "<i>.exp_avg", ...) and
// each group's learning rate: LibTorch's own optimizer archive keys the
// state by the parameters' memory addresses, so the same training wrote
// different bytes in every process.
void save_adam(torch::serialize::OutputArchive& out, const torch::optim::Adam& adam) {
  torch::serialize::OutputArchive a;
  std::int64_t i = 0;
  for (std::size_t g = 0; g < adam.param_groups().size(); ++g) {
    const auto& group = adam.param_groups()[g];
    a.write("group" + std::to_string(g) + ".lr",
            at::scalar_tensor(static_cast<const torch::optim::AdamOptions&>(group.options()).lr(), at::kDouble));
    for (const at::Tensor& p : group.params()) {
      const std::string key = std::to_string(i++);
      const auto it = adam.state().find(c10::guts::to_string(p.unsafeGetTensorImpl()));
      if (it == adam.state().end()) continue;
      const auto& s = static_cast<const torch::optim::AdamParamState&>(*it->second);
      a.write(key + ".step", at::scalar_tensor(s.step(), at::kLong));
      a.write(key + ".exp_avg", s.exp_avg());
      a.write(key + ".exp_avg_sq", s.exp_avg_sq());
      if (s.max_exp_avg_sq().defined()) a.write(key + ".max_exp_avg_sq", s.max_exp_avg_sq());
    }
  }
  a.write("params", at::scalar_tensor(i, at::kLong));
  out.write("adam", a);
}

void load_adam(torch::serialize::InputArchive& a, torch::optim::Adam& adam, const std::string& path) {
  std::int64_t count = 0;
  for (const auto& group : adam.param_groups()) count += static_cast<std::int64_t>(group.params().size());
  const std::int64_t saved = read_tensor(a, "params", path).item<std::int64_t>();
  if (saved != count)
    throw InputError(path, "adam.params", std::to_string(count) + " parameters (this model's)", std::to_string(saved));
  std::int64_t i = 0;
  for (std::size_t g = 0; g < adam.param_groups().size(); ++g) {
    auto& group = adam.param_groups()[g];
    static_cast<torch::optim::AdamOptions&>(group.options())
        .lr(read_tensor(a, "group" + std::to_string(g) + ".lr", path).item<double>());
    for (const at::Tensor& p : group.params()) {
      const std::string key = std::to_string(i++);
      at::Tensor step;
      if (!a.try_read(key + ".step", step)) continue;  // no state yet for this parameter
      // Each moment has its parameter's shape, device and type.
      const auto moment = [&](const std::string& name, at::Tensor t) {
        if (!t.sizes().equals(p.sizes()))
          throw InputError(path, "adam." + key + "." + name, "the shape of parameter " + key,
                           "another shape (a checkpoint of another model)");
        return t.to(p.device(), p.scalar_type());
      };
      auto s = std::make_unique<torch::optim::AdamParamState>();
      s->step(step.item<std::int64_t>());
      s->exp_avg(moment("exp_avg", read_tensor(a, key + ".exp_avg", path)));
      s->exp_avg_sq(moment("exp_avg_sq", read_tensor(a, key + ".exp_avg_sq", path)));
      at::Tensor max;
      if (a.try_read(key + ".max_exp_avg_sq", max)) s->max_exp_avg_sq(moment("max_exp_avg_sq", max));
      adam.state()[c10::guts::to_string(p.unsafeGetTensorImpl())] = std::move(s);
    }
  }
}

}  // namespace

void save_checkpoint(const std::string& path, zoo::Model& model, const torch::optim::Optimizer* optimizer,
                     const CheckpointState& state) {
  torch::serialize::OutputArchive out, model_archive, norm_archive;
  model.save(model_archive);
  out.write("model", model_archive);
  data::for_each_quantity(model.normalization(), [&](const char* quantity, const zoo::NormPair& p) {
    norm_archive.write(norm_key(quantity) + ".mean", p.mean.cpu());
    norm_archive.write(norm_key(quantity) + ".std", p.std.cpu());
  });
  out.write("normalization", norm_archive);
  if (const auto* adam = dynamic_cast<const torch::optim::Adam*>(optimizer)) {
    save_adam(out, *adam);
  } else if (optimizer) {
    torch::serialize::OutputArchive opt_archive;
    optimizer->save(opt_archive);
    out.write("optimizer", opt_archive);
  }
  out.write("epochs_done", at::scalar_tensor(static_cast<std::int64_t>(state.epochs_done), at::kLong));
  out.write("steps", at::scalar_tensor(state.steps, at::kLong));
  out.write("best_val_mm", at::scalar_tensor(state.best_val_mm, at::kDouble));
  write_text(out, "model_name", state.model_name);
  write_text(out, "selection_kind", state.kind);
  write_text(out, "selection_split", state.chosen_on);
  write_text(out, "selection_metric", state.metric);
  out.write("selection_epoch", at::scalar_tensor(static_cast<std::int64_t>(state.chosen_epoch), at::kLong));
  out.write("selection_epochs", at::scalar_tensor(static_cast<std::int64_t>(state.epochs), at::kLong));
  out.write("loss_by_epoch", at::tensor(state.loss_by_epoch, at::kDouble));
  out.write("windows_by_epoch", at::tensor(state.windows_by_epoch, at::kDouble));
  out.write("val_mm_by_epoch", at::tensor(state.val_mm_by_epoch, at::kDouble));
  std::filesystem::create_directories(std::filesystem::path(path).parent_path().empty()
                                          ? std::filesystem::path(".")
                                          : std::filesystem::path(path).parent_path());
  std::ostringstream archive;
  out.save_to(archive);
  const std::string payload = archive.str();
  AtomicPath target(path);
  {
    std::ofstream file(target.temp(), std::ios::binary);
    file << kMagic << content_hash(payload) << ' ' << payload.size() << '\n' << payload;
    file.flush();
    if (!file) throw Error(target.temp() + ": cannot write the checkpoint");
  }
  target.commit();
}

CheckpointState load_checkpoint(const std::string& path, zoo::Model& model, torch::optim::Optimizer* optimizer) {
  if (!std::filesystem::exists(path)) throw InputError(path, "checkpoint", "an existing file", "no such file");
  torch::serialize::InputArchive in;
  std::string checksum;
  std::istringstream payload(checked_payload(path, checksum));
  try {
    in.load_from(payload);
  } catch (const std::exception& e) {
    throw InputError(path, "checkpoint", "a layers checkpoint (torch archive)", "unreadable: " + torch_message(e));
  }
  CheckpointState state;
  state.checksum = checksum;
  state.model_name = text_of(read_tensor(in, "model_name", path));
  if (state.model_name != model.name())
    throw InputError(path, "model_name", "a checkpoint of model '" + model.name() + "'",
                     "one of model '" + state.model_name + "'");
  state.epochs_done = static_cast<int>(read_tensor(in, "epochs_done", path).item<std::int64_t>());
  state.steps = read_tensor(in, "steps", path).item<std::int64_t>();
  state.best_val_mm = read_tensor(in, "best_val_mm", path).item<double>();
  // The selection record; a checkpoint saved before it has none.
  at::Tensor kind, split, metric, epoch, epochs;
  if (in.try_read("selection_kind", kind) && in.try_read("selection_split", split) &&
      in.try_read("selection_metric", metric) && in.try_read("selection_epoch", epoch) &&
      in.try_read("selection_epochs", epochs)) {
    state.recorded = true;
    state.kind = text_of(kind);
    state.chosen_on = text_of(split);
    state.metric = text_of(metric);
    state.chosen_epoch = static_cast<int>(epoch.item<std::int64_t>());
    state.epochs = static_cast<int>(epochs.item<std::int64_t>());
  }
  at::Tensor losses, vals;
  if (in.try_read("loss_by_epoch", losses) && in.try_read("val_mm_by_epoch", vals) && losses.numel() == vals.numel()) {
    losses = losses.to(at::kDouble).contiguous();
    vals = vals.to(at::kDouble).contiguous();
    state.loss_by_epoch.assign(losses.data_ptr<double>(), losses.data_ptr<double>() + losses.numel());
    state.val_mm_by_epoch.assign(vals.data_ptr<double>(), vals.data_ptr<double>() + vals.numel());
  }
  at::Tensor windows;
  if (in.try_read("windows_by_epoch", windows)) {
    windows = windows.to(at::kDouble).contiguous();
    state.windows_by_epoch.assign(windows.data_ptr<double>(), windows.data_ptr<double>() + windows.numel());
  }
  torch::serialize::InputArchive model_archive, norm_archive;
  if (!in.try_read("model", model_archive)) throw InputError(path, "model", "the model's parameters", "nothing");
  // LibTorch's load replaces a tensor whatever its shape: the shapes the
  // configured model has are compared afterwards, one line for the first
  // that differs (a model of another width, say).
  // Every parameter and buffer with its kind and shape, in one order.
  struct Shape {
    std::string what;
    std::vector<std::int64_t> sizes;
  };
  const auto shapes_of = [&] {
    std::vector<Shape> out;
    for (const auto& p : model.named_parameters(true)) out.push_back({"parameter " + p.key(), p.value().sizes().vec()});
    for (const auto& b : model.named_buffers(true)) out.push_back({"buffer " + b.key(), b.value().sizes().vec()});
    return out;
  };
  const std::vector<Shape> configured = shapes_of();
  try {
    model.load(model_archive);
  } catch (const std::exception& e) {
    throw InputError(path, "model", "parameters matching the configured model '" + model.name() + "'",
                     "a mismatch: " + torch_message(e));
  }
  const auto text = [](const std::vector<std::int64_t>& shape) {
    std::string t = "[";
    for (std::size_t i = 0; i < shape.size(); ++i) t += (i ? ", " : "") + std::to_string(shape[i]);
    return t + "]";
  };
  const std::vector<Shape> loaded = shapes_of();
  for (std::size_t k = 0; k < configured.size() && k < loaded.size(); ++k)
    if (loaded[k].sizes != configured[k].sizes)
      throw InputError(path, "model " + configured[k].what,
                       "shape " + text(configured[k].sizes) + " (the model '" + model.name() + "' as configured)",
                       text(loaded[k].sizes) + " in the checkpoint (trained with other model.params)");
  if (!in.try_read("normalization", norm_archive))
    throw InputError(path, "normalization", "the training statistics", "nothing");
  zoo::Normalization norm;
  data::for_each_quantity(norm, [&](const char* quantity, zoo::NormPair& p) {
    p.mean = read_tensor(norm_archive, norm_key(quantity) + ".mean", path);
    p.std = read_tensor(norm_archive, norm_key(quantity) + ".std", path);
  });
  model.set_normalization(norm);
  if (optimizer) {
    torch::serialize::InputArchive opt_archive;
    auto* adam = dynamic_cast<torch::optim::Adam*>(optimizer);
    if (adam && in.try_read("adam", opt_archive))
      load_adam(opt_archive, *adam, path);
    else if (in.try_read("optimizer", opt_archive))  // checkpoints written before the "adam" record
      optimizer->load(opt_archive);
  }
  return state;
}

}  // namespace layers::train
