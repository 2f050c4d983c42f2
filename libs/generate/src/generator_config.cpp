// Cross-field checks of the generator config (see generator_config.h).
#include "layers/generate/generator_config.h"

#include <algorithm>

#include "layers/core/error.h"
#include "layers/data/format.h"

namespace layers::generate {
namespace {

template <class T>
void check_pair(const std::vector<T>& range, const std::string& file, const std::string& path) {
  if (range.size() != 2 || range[0] > range[1])
    throw InputError(file, path, "a range [lo, hi] with lo <= hi", std::to_string(range.size()) + " values" +
                                                                      (range.size() == 2 ? " with lo > hi" : ""));
}

bool is_outer(const std::string& type) { return type == "jacket" || type == "jacket_hood"; }

}  // namespace

void check(const GeneratorConfig& c, const std::string& file) {
  const auto& shape = c.body.shape;
  check_pair(shape.gender, file, "body.shape.gender");
  check_pair(shape.muscle, file, "body.shape.muscle");
  check_pair(shape.weight, file, "body.shape.weight");
  check_pair(shape.height, file, "body.shape.height");
  if (c.body.motions.empty()) throw InputError(file, "body.motions", "at least one motion", "an empty list");
  const auto& a = c.garments.attributes;
  check_pair(a.mass, file, "garments.attributes.mass");
  check_pair(a.stiffness, file, "garments.attributes.stiffness");
  check_pair(a.bending, file, "garments.attributes.bending");
  check_pair(a.friction, file, "garments.attributes.friction");
  check_pair(c.wind.calm, file, "wind.calm");
  check_pair(c.wind.strong, file, "wind.strong");
  check_pair(c.wind.mixed, file, "wind.mixed");
  check_pair(c.wind.span_frames, file, "wind.span_frames");
  if (c.wind.calm_weight + c.wind.strong_weight + c.wind.mixed_weight <= 0)
    throw InputError(file, "wind", "at least one positive regime weight", "all zero");
  if (c.splits.val + c.splits.test >= 1.0)
    throw InputError(file, "splits", "val + test < 1 (the rest is train)",
                     std::to_string(c.splits.val + c.splits.test));
  if (c.garments.outfits.empty()) throw InputError(file, "garments.outfits", "at least one outfit", "an empty list");
  double total = 0;
  const auto& types = data::garment_types();
  for (std::size_t i = 0; i < c.garments.outfits.size(); ++i) {
    const auto& o = c.garments.outfits[i];
    const std::string path = "garments.outfits[" + std::to_string(i) + "]";
    total += o.weight;
    if (o.inner.empty()) throw InputError(file, path + ".inner", "at least one inner garment type", "an empty list");
    for (const auto& t : o.inner) {
      if (std::find(types.begin(), types.end(), t) == types.end() || is_outer(t))
        throw InputError(file, path + ".inner", "inner garment types (dress, dress_belt, jumpsuit, tshirt, pants, skirt)",
                         "'" + t + "'");
    }
  }
  if (total <= 0) throw InputError(file, "garments.outfits", "at least one outfit with a positive weight", "all zero");
  scene::validate(c.garments.fit);
  sim::check(c.sim, "sim");
}

}  // namespace layers::generate
