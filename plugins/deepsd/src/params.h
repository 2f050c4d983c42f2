// plugins/deepsd/src/params.h -- the parameters of the DeePSD model (the
// `model.params` section of an experiment config), with the defaults of the
// public DeePSD code (docs/deepsd.md). Torch-free.
#pragma once

#include <cstdint>
#include <vector>

#include "layers/core/config.h"

namespace layers::deepsd {

struct DeepsdParams {
  int joints = 31;                                   // skeleton joints J (cmu_mb rig: 31)
  std::vector<int> graph_widths{32, 64, 128, 256};   // graph layers after the 6 inputs
  std::vector<int> weight_head{128, 64, 32};         // hidden widths of the blend-weight head
  std::vector<int> deformation_head{256, 256, 256};  // hidden widths of the deformation head
  std::vector<int> pose_head{256, 256, 256};         // hidden widths of the pose embedding
  int basis = 128;                                   // K deformation basis vectors per vertex
  bool wind = true;                                  // wind at t+1 as an extra pose input
  // First-epoch priors (auxiliary losses, added by the trainer).
  int prior_epochs = 1;             // epochs 0 .. prior_epochs-1 get them
  double weight_prior = 10.0;       // x mean_v sum_j (w_vj - w*_vj)^2, w* the nearest body vertex's weights
  double deformation_prior = 0.01;  // x mean_v |d_v|^2 in cm^2 (the trainer's position unit)

  template <class V>
  void visit(V& v) {
    v("joints", joints, cfg::opt().range(1, 1000).help("skeleton joints J (must match the data)"));
    v("graph_widths", graph_widths,
      cfg::opt().range(1, 100000).help("widths of the graph layers (mean over mesh neighbours)"));
    v("weight_head", weight_head, cfg::opt().range(1, 100000).help("hidden widths of the blend-weight head"));
    v("deformation_head", deformation_head, cfg::opt().range(1, 100000).help("hidden widths of the deformation head"));
    v("pose_head", pose_head, cfg::opt().range(1, 100000).help("hidden widths of the pose embedding"));
    v("basis", basis, cfg::opt().range(1, 100000).help("deformation basis vectors per vertex (K)"));
    v("wind", wind, cfg::opt().help("feed wind (strength/400, direction) at t+1 to the pose embedding"));
    v("prior_epochs", prior_epochs, cfg::opt().range(0, 100000).help("epochs with the weight and deformation priors"));
    v("weight_prior", weight_prior, cfg::opt().min(0).help("weight of the skinning-weight prior"));
    v("deformation_prior", deformation_prior, cfg::opt().min(0).help("weight of the deformation size prior (cm^2)"));
  }
};

// Reads and checks the parameters (an absent/null node gives the
// defaults). Errors are layers::InputError naming the key relative to
// `params` (zoo::create_model prefixes model.params).
DeepsdParams read_params(const cfg::Node& params);

}  // namespace layers::deepsd
