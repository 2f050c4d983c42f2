// layers/mgnet/params.h -- MGNet's parameters (the `model.params` section
// of a config): UV image resolution, encoder channels per stride-2 stage,
// latent size, and what the decoded displacement is added to. Torch-free.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/core/config.h"

namespace layers::mgnet {

// The prediction the decoded displacement is added to (input_maps.h).
enum class Base { constant_velocity, body_seeds };
inline const cfg::EnumNames<Base>& enum_names(Base) {
  static const cfg::EnumNames<Base> names{{Base::body_seeds, "body_seeds"},
                                          {Base::constant_velocity, "constant_velocity"}};
  return names;
}

struct Params {
  // The UV image is resolution x resolution pixels; it must be divisible by
  // 2^channels.size() (each encoder stage halves it).
  std::int64_t resolution = 64;
  // Output channels of each stride-2 convolution of the encoders (the
  // decoder mirrors them with transposed convolutions).
  std::vector<std::int64_t> channels = {32, 64, 128};
  // Size of each encoder's latent code (state and dynamic encoder).
  std::int64_t latent = 64;
  // The prediction the displacement is added to (input_maps.h):
  // "body_seeds" (each vertex moves with its body seed point, as MGNet's
  // output is carried by the body) or "constant_velocity" (root-relative).
  Base base = Base::body_seeds;

  template <class V>
  void visit(V& v) {
    v("resolution", resolution, cfg::opt().range(4, 1024).help("UV image side in pixels"));
    v("channels", channels, cfg::opt().range(1, 4096).help("channels of each stride-2 encoder stage"));
    v("latent", latent, cfg::opt().range(1, 65536).help("latent size of each encoder"));
    v("base", base, cfg::opt().help("prediction the displacement is added to: body_seeds or constant_velocity"));
  }
};

// cfg::read<Params> plus the checks that involve several fields (channels
// not empty, resolution divisible by 2^stages); InputError naming the key.
Params read_params(const cfg::Node& params);

}  // namespace layers::mgnet
