// Model base: validation, conversion and caching of per-sequence static
// data, and checks around step() (see model.h).
#include "layers/zoo/model.h"

#include <algorithm>
#include <sstream>

#include "layers/core/error.h"

namespace layers::zoo {
namespace {

constexpr std::int64_t kAny = -1;

// What a tensor must be: integer or floating, with these sizes (kAny: any).
struct Spec {
  bool integral;
  std::vector<std::int64_t> sizes;
};

std::string describe(const Spec& spec) {
  std::ostringstream out;
  out << (spec.integral ? "an integer" : "a floating-point") << " tensor [";
  for (std::size_t i = 0; i < spec.sizes.size(); ++i)
    out << (i ? ", " : "") << (spec.sizes[i] == kAny ? std::string("*") : std::to_string(spec.sizes[i]));
  out << "]";
  return out.str();
}

std::string describe(const at::Tensor& t) {
  if (!t.defined()) return "nothing (undefined tensor)";
  std::ostringstream out;
  out << t.scalar_type() << " tensor " << t.sizes() << " on " << t.device();
  return out.str();
}

bool matches(const at::Tensor& t, const Spec& spec) {
  if (!t.defined() || t.dim() != static_cast<std::int64_t>(spec.sizes.size())) return false;
  if (spec.integral ? !at::isIntegralType(t.scalar_type(), /*includeBool=*/false)
                    : !at::isFloatingType(t.scalar_type()))
    return false;
  for (std::size_t i = 0; i < spec.sizes.size(); ++i)
    if (spec.sizes[i] != kAny && t.size(static_cast<std::int64_t>(i)) != spec.sizes[i]) return false;
  return true;
}

// Static data checks: InputError naming the sequence and the field.
class StaticChecker {
 public:
  explicit StaticChecker(const std::string& id) : where_("sequence '" + id + "'") {}

  void tensor(const at::Tensor& t, const Spec& spec, const std::string& field) const {
    if (!matches(t, spec)) throw InputError(where_, field, describe(spec), describe(t));
  }
  void optional(const at::Tensor& t, const Spec& spec, const std::string& field) const {
    if (t.defined()) tensor(t, spec, field);
  }
  // Every index in [0, bound).
  void indices(const at::Tensor& t, std::int64_t bound, const std::string& field) const {
    if (t.numel() == 0) return;
    std::int64_t lo = t.min().item<std::int64_t>(), hi = t.max().item<std::int64_t>();
    if (lo < 0 || hi >= bound) {
      throw InputError(where_, field, "indices in [0, " + std::to_string(bound) + ")",
                       "values in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
  }
  void finite(const at::Tensor& t, const std::string& field) const {
    if (t.numel() > 0 && !at::isfinite(t).all().item<bool>())
      throw InputError(where_, field, "finite values", "NaN or infinity");
  }
  void fail(const std::string& field, const std::string& expected, const std::string& got) const {
    throw InputError(where_, field, expected, got);
  }

 private:
  std::string where_;
};

void validate(const SequenceStatic& s) {
  StaticChecker check(s.id);
  check.tensor(s.body_faces, {true, {kAny, 3}}, "body_faces");
  for (std::size_t k = 0; k < s.garments.size(); ++k) {
    const GarmentStatic& g = s.garments[k];
    const std::string at = "garments[" + std::to_string(k) + "] (" + g.name + ").";
    if (g.layer != 0 && g.layer != 1) check.fail(at + "layer", "0 (inner) or 1 (outer)", std::to_string(g.layer));
    check.tensor(g.rest, {false, {kAny, 3}}, at + "rest");
    check.tensor(g.faces, {true, {kAny, 3}}, at + "faces");
    check.tensor(g.uv, {false, {kAny, 2}}, at + "uv");
    const std::int64_t nf = g.faces.size(0);
    check.tensor(g.uv_faces, {true, {nf, 3}}, at + "uv_faces");
    check.tensor(g.panel, {true, {nf}}, at + "panel");
    check.tensor(g.attributes, {false, {kAny}}, at + "attributes");
    check.indices(g.faces, g.rest.size(0), at + "faces");
    check.indices(g.uv_faces, g.uv.size(0), at + "uv_faces");
    check.finite(g.rest, at + "rest");
    check.finite(g.uv, at + "uv");
    check.finite(g.attributes, at + "attributes");
  }
  check.optional(s.joint_parents, {true, {kAny}}, "joint_parents");
  check.optional(s.skin_index, {true, {kAny, 4}}, "skin_index");
  check.optional(s.tpose_joints, {false, {s.joint_parents.defined() ? s.joint_parents.size(0) : kAny, 3, 4}},
                 "tpose_joints");
  check.optional(s.skin_weight, {false, {kAny, 4}}, "skin_weight");
  if (s.skin_index.defined() != s.skin_weight.defined())
    check.fail("skin_weight", "skin_index and skin_weight given together", "only one of them");
  if (s.skin_index.defined()) {
    check.tensor(s.skin_weight, {false, {s.skin_index.size(0), 4}}, "skin_weight");
    check.indices(s.body_faces, s.skin_index.size(0), "body_faces");
    if (s.joint_parents.defined()) check.indices(s.skin_index, s.joint_parents.size(0), "skin_index");
  }
}

at::Tensor convert(const at::Tensor& t, at::Device device, at::ScalarType type) {
  return t.defined() ? t.to(device, type) : t;
}

SequenceStatic converted(const SequenceStatic& s, at::Device device) {
  SequenceStatic out = s;
  out.body_faces = convert(s.body_faces, device, at::kLong);
  out.joint_parents = convert(s.joint_parents, device, at::kLong);
  out.skin_index = convert(s.skin_index, device, at::kLong);
  out.skin_weight = convert(s.skin_weight, device, at::kFloat);
  out.tpose_joints = convert(s.tpose_joints, device, at::kFloat);
  for (GarmentStatic& g : out.garments) {
    g.faces = convert(g.faces, device, at::kLong);
    g.uv_faces = convert(g.uv_faces, device, at::kLong);
    g.panel = convert(g.panel, device, at::kLong);
    g.rest = convert(g.rest, device, at::kFloat);
    g.uv = convert(g.uv, device, at::kFloat);
    g.attributes = convert(g.attributes, device, at::kFloat);
  }
  return out;
}

// Step input/output checks: Error naming the model and the field.
class StepChecker {
 public:
  StepChecker(const std::string& model, at::Device device) : model_(model), device_(device) {}

  void tensor(const at::Tensor& t, const Spec& spec, const std::string& field) const {
    if (!matches(t, spec) || t.device() != device_) {
      std::ostringstream expected;
      expected << describe(spec) << " on " << device_;
      throw Error("model '" + model_ + "': " + field + ": expected " + expected.str() + ", got " + describe(t));
    }
  }
  void count(std::size_t got, std::size_t want, const std::string& field) const {
    if (got != want) {
      throw Error("model '" + model_ + "': " + field + ": expected " + std::to_string(want) +
                  " garments (as prepared), got " + std::to_string(got));
    }
  }

 private:
  std::string model_;
  at::Device device_;
};

}  // namespace

Model::Model(const std::string& name) : torch::nn::Module(name) {
  // An empty buffer every model has, so that device() follows to(device)
  // even for a model without parameters or buffers of its own.
  register_buffer("device_anchor", at::zeros({0}));
}
Model::~Model() = default;

ModelInfo Model::info() const {
  ModelInfo out;
  out.name = name();
  for (const at::Tensor& p : parameters(/*recurse=*/true)) {
    out.parameters += p.numel();
    if (p.requires_grad()) out.trainable += p.numel();
  }
  return out;
}

at::Device Model::device() const {
  for (const at::Tensor& p : parameters(true)) return p.device();
  for (const at::Tensor& b : buffers(true)) return b.device();
  return at::Device(at::kCPU);
}

void Model::prepare(const SequenceStatic& data) {
  at::Device dev = device();
  const std::string key = data.id + "@" + dev.str();
  for (auto it = cache_.begin(); it != cache_.end(); ++it) {
    if (it->key == key) {
      cache_.splice(cache_.begin(), cache_, it);
      current_ = &cache_.front();
      return;
    }
  }
  validate(data);
  Prepared entry{key, dev, converted(data, dev), nullptr};
  entry.derived = derive(entry.data);
  cache_.push_front(std::move(entry));
  current_ = &cache_.front();
  while (cache_.size() > capacity_) cache_.pop_back();
}

const SequenceStatic& Model::sequence() const {
  if (!current_) throw Error("model '" + name() + "': step or sequence() before prepare()");
  return current_->data;
}

std::shared_ptr<const Model::Derived> Model::derive(const SequenceStatic&) { return nullptr; }

std::shared_ptr<const Model::Derived> Model::bind(const SequenceStatic&, std::shared_ptr<const Derived> derived,
                                                  const StepInput&) {
  return derived;
}

const Model::Derived* Model::current_derived() const {
  const SequenceStatic& s = sequence();
  if (!current_->derived) throw Error("model '" + name() + "' derived no data for sequence '" + s.id + "'");
  return current_->derived.get();
}

void Model::set_normalization(const Normalization& norm) { norm_ = norm.to(device()); }

const Normalization& Model::normalization() const {
  const at::Device dev = device();
  if (norm_.garment_position.mean.device() != dev) norm_ = norm_.to(dev);
  return norm_;
}

std::vector<LossTerm> Model::auxiliary_losses(const TrainingContext&) { return {}; }

void Model::set_cache_capacity(std::size_t capacity) {
  capacity_ = std::max<std::size_t>(capacity, 1);
  // The current entry is the most recently used one, so it survives.
  while (cache_.size() > capacity_) cache_.pop_back();
}

StepOutput Model::step(const StepInput& in) {
  const SequenceStatic& s = sequence();
  const at::Device dev = device();
  if (current_->device != dev) {
    throw Error("model '" + name() + "' moved to " + dev.str() + " after prepare() on " + current_->device.str() +
                "; call prepare() again");
  }
  StepChecker check(name(), dev);
  check.count(in.garments.size(), s.garments.size(), "step input garments");
  for (std::size_t k = 0; k < s.garments.size(); ++k) {
    const Spec state{false, {s.garments[k].rest.size(0), 3}};
    const std::string at = "step input garments[" + std::to_string(k) + "].";
    check.tensor(in.garments[k].prev, state, at + "prev");
    check.tensor(in.garments[k].current, state, at + "current");
  }
  const std::int64_t nb = s.skin_index.defined() ? s.skin_index.size(0) : kAny;
  check.tensor(in.body, {false, {nb, 3}}, "step input body");
  check.tensor(in.body_next, {false, {in.body.size(0), 3}}, "step input body_next");
  check.tensor(in.root, {false, {3, 3}}, "step input root");
  check.tensor(in.root_rot, {false, {3, 4}}, "step input root_rot");
  check.tensor(in.wind_rotation, {false, {2, 4}}, "step input wind_rotation");
  check.tensor(in.wind_strength, {false, {2}}, "step input wind_strength");
  const std::int64_t nj = s.joint_parents.defined() ? s.joint_parents.size(0) : kAny;
  if (in.joints.defined()) check.tensor(in.joints, {false, {nj, 3, 4}}, "step input joints");
  if (in.joints_next.defined()) check.tensor(in.joints_next, {false, {nj, 3, 4}}, "step input joints_next");

  if (!current_->bound) {
    current_->derived = bind(s, current_->derived, in);
    current_->bound = true;
  }
  StepOutput out = predict(in);
  check.count(out.garments.size(), s.garments.size(), "step output garments");
  for (std::size_t k = 0; k < s.garments.size(); ++k) {
    check.tensor(out.garments[k], {false, {s.garments[k].rest.size(0), 3}},
                 "step output garments[" + std::to_string(k) + "]");
  }
  return out;
}

}  // namespace layers::zoo
