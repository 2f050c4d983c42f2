// layers_clip_convert -- a motion clip (.bvh, or .amc with its .asf) made
// into the BVH the project ships (assets/motions/): resampled, some joints
// (and those below them) dropped.
//   layers_clip_convert IN OUT.bvh [fps] [joint,joint,...]
// e.g. layers_clip_convert 02/02_01.amc cmu/02_01.bvh 30 lhand,rhand,lthumb,rthumb
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <set>
#include <sstream>
#include <string>

#include "layers/motion/asf_amc.h"
#include "layers/motion/bvh_write.h"

int main(int argc, char** argv) {
  if (argc < 3 || argc > 5) {
    std::fprintf(stderr, "usage: layers_clip_convert IN OUT.bvh [fps] [joint,joint,...]\n");
    return 2;
  }
  try {
    using namespace layers::motion;
    BvhClip clip = read_clip(argv[1]);
    if (argc >= 4) clip = resample(clip, std::atof(argv[3]));
    std::set<std::string> drop;
    if (argc == 5) {
      std::istringstream names(argv[4]);
      for (std::string n; std::getline(names, n, ',');)
        if (!n.empty()) drop.insert(n);
    }
    write_bvh(without_joints(clip, drop), argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "layers_clip_convert: %s\n", e.what());
    return 1;
  }
  return 0;
}
