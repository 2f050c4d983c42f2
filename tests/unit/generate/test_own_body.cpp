// A user's own body in the generator (generate/own_body.h): the tiny rig
// (tests/support/tiny_rig.h) and its frames as a mesh sequence become the
// body sequence frame for frame after the transition from the garments'
// pose; the config checks refuse templates, procedural motions and BVH
// clips on a mesh sequence with one line; and the scene's own body written
// as a rig by `layers tpose` (tpose_meshes) and read back as body.own, with
// its garments as files, is the native scene's body and moves the garments
// as the native scene does, within the spread one float ulp of body motion
// makes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "error_of.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/obj.h"
#include "layers/data/skinned_glb.h"
#include "layers/garment/garment_body.h"
#include "layers/generate/own_body.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/tpose.h"
#include "temp_dir.h"
#include "tiny_rig.h"
#include "tiny_scene.h"

namespace layers::generate {
namespace {

std::string write_rig(const test::TempDir& dir, const std::string& name, const data::SkinnedBody& rig) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << data::skinned_glb_bytes(rig, 30.0);
  return path;
}

GeneratorConfig own_config(const std::string& file, int frames, int transition, const std::string& pose = "bind") {
  GeneratorConfig c;
  c.frames = frames;
  c.body.transition_frames = transition;
  c.body.motions = {kOwnAnimation};
  c.body.own = OwnBodyConfig{};
  c.body.own->file = file;
  c.body.own->garment_pose = pose;
  return c;
}

// `rig` as a Mixamo-style file names it ("mixamorig:<joint>"), with
// `extra` more leaf joints under the left hand that carry no skin (the
// finger joints such a rig has beyond ours), moving with the hand.
data::SkinnedBody mixamo_style(const data::SkinnedBody& rig, int extra) {
  data::SkinnedBody out = rig;
  const std::size_t nj = rig.joint_names.size(), frames = rig.joints.size() / (nj * 12);
  const auto hand = static_cast<std::size_t>(std::find(rig.joint_names.begin(), rig.joint_names.end(), "LeftHand") -
                                             rig.joint_names.begin());
  for (std::string& name : out.joint_names) name = "mixamorig:" + name;
  out.joints.clear();
  for (int k = 0; k < extra; ++k) {
    out.joint_names.push_back("mixamorig:LeftHandExtra" + std::to_string(k));
    out.joint_parents.push_back(static_cast<std::int32_t>(hand));
    for (int a = 0; a < 3; ++a) out.rest_joints.push_back(rig.rest_joints[hand * 3 + a] + (a == 2 ? 0.002f * k : 0.0f));
  }
  for (std::size_t f = 0; f < frames; ++f) {
    const float* m = rig.joints.data() + f * nj * 12;
    out.joints.insert(out.joints.end(), m, m + nj * 12);
    const float* h = m + hand * 12;
    for (int k = 0; k < extra; ++k)  // p = p_hand + R_hand (0, 0, 0.002 k)
      for (int row = 0; row < 3; ++row) {
        out.joints.insert(out.joints.end(), h + row * 4, h + row * 4 + 3);
        out.joints.push_back(h[row * 4 + 3] + h[row * 4 + 2] * 0.002f * k);
      }
  }
  return out;
}

double frame_error(const motion::BodySequence& s, int frame, const std::vector<double>& want) {
  double worst = 0;
  const std::size_t n = want.size();
  for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(s.positions[frame * n + i] - want[i]));
  return worst;
}

TEST(OwnBody, TheRigsAnimationIsTheBodySequenceAfterTheTransition) {
  test::TempDir dir("own_body");
  const test::TinyRig rig(6);
  const std::string path = write_rig(dir, "rig.glb", rig.body);
  SceneSpec spec;
  spec.motion = kOwnAnimation;
  // Bind pose: 2 transition frames from it, then frames 0..3 of the animation.
  motion::GeneratedBody g = own_body(own_config(path, 4, 2), spec);
  EXPECT_EQ(g.body.file, path);
  EXPECT_EQ(g.body.skeleton.names, (std::vector<std::string>{"Hips", "Spine", "Head"}));
  ASSERT_EQ(g.sequence.num_frames, 6);
  EXPECT_EQ(g.sequence.motion, "animation:rig.glb#motion");
  for (int f = 0; f < 4; ++f) EXPECT_LT(frame_error(g.sequence, 2 + f, rig.posed(f)), 1e-5) << f;
  std::vector<double> rest(rig.body.rest.begin(), rig.body.rest.end());
  EXPECT_LT(frame_error(g.sequence, 0, rest), 1e-5) << "the transition starts in the bind pose";
  // The garments' pose is the bind pose: the T-pose body is the rest mesh.
  const garment::TPoseBody t = garment::t_pose_body(g.body);
  EXPECT_NEAR(t.mesh.vertices(29, 1), 1.7, 1e-6);
  // first_frame: frame 0 is the garments' pose, the motion plays from frame 1.
  g = own_body(own_config(path, 4, 2, "first_frame"), spec);
  for (int f = 0; f < 4; ++f) EXPECT_LT(frame_error(g.sequence, 2 + f, rig.posed(f + 1)), 1e-5) << f;
  const garment::TPoseBody first = garment::t_pose_body(g.body);
  const std::vector<double> pose0 = rig.posed(0);
  for (int i = 0; i < 90; ++i) EXPECT_NEAR(first.mesh.vertices.data()[i], pose0[i], 1e-5);
  // An animation shorter than the frames asked for.
  const std::string e = test::error_of<InputError>([&] { own_body(own_config(path, 6, 2, "first_frame"), spec); });
  EXPECT_NE(e.find("expected at least 6 frames at 30 fps (the config's frames, after the garments' pose), got 5"),
            std::string::npos)
      << e;
}

TEST(OwnBody, AMeshSequencePlaysItsFramesAfterBlendingInFromItsRestPose) {
  test::TempDir dir("own_body");
  const test::TinyRig rig(4);
  std::filesystem::create_directories(dir.file("frames"));
  for (int f = 0; f < 4; ++f) {
    data::ObjMesh m;
    for (double x : rig.posed(f)) m.positions.push_back(static_cast<float>(x));
    m.faces = rig.body.faces;
    data::write_obj(dir.file("frames/" + std::to_string(f) + ".obj"), m);
  }
  SceneSpec spec;
  spec.motion = kOwnAnimation;
  const motion::GeneratedBody g = own_body(own_config(dir.file("frames"), 3, 2), spec);
  ASSERT_EQ(g.sequence.num_frames, 5);
  EXPECT_EQ(g.sequence.num_joints, 1);
  for (int f = 0; f < 3; ++f) EXPECT_LT(frame_error(g.sequence, 2 + f, rig.posed(f)), 1e-6) << f;
  EXPECT_LT(frame_error(g.sequence, 0, rig.posed(0)), 1e-6) << "the first frame is the rest pose";
  // The root follows the frames' rigid motion; the joints array is [R|p].
  EXPECT_NEAR(g.sequence.joints[4 * 12 + 3], g.sequence.root[4 * 3], 1e-6);
}

TEST(OwnBody, TemplatesProceduralMotionsAndClipsOnASequenceAreRefused) {
  test::TempDir dir("own_body");
  const std::string path = write_rig(dir, "rig.glb", test::TinyRig(3).body);
  std::filesystem::create_directories(dir.file("frames"));
  GeneratorConfig c = own_config(path, 2, 1);
  c.garments.outfits = {OutfitConfig{{"dress"}, "jacket", 1.0}};
  std::string e = test::error_of<InputError>([&] { check_own_body(c, "c.yaml"); });
  EXPECT_NE(e.find("c.yaml: garments.outfits[0]: expected garment files (file:<mesh>) with body.own"),
            std::string::npos)
      << e;
  c.garments.outfits = {OutfitConfig{{"file:" + path}, "none", 1.0}};
  c.body.motions = {"procedural:walk"};
  e = test::error_of<InputError>([&] { check_own_body(c, "c.yaml"); });
  EXPECT_NE(e.find("body.motions[0]: expected animation (the file's own) or a BVH clip"), std::string::npos) << e;
  c.body.motions = {"bvh:cmu/01_01.bvh"};
  EXPECT_NO_THROW(check_own_body(c, "c.yaml"));
  c.body.own->file = dir.file("frames");
  e = test::error_of<InputError>([&] { check_own_body(c, "c.yaml"); });
  EXPECT_NE(e.find("expected animation (a mesh sequence plays its own frames)"), std::string::npos) << e;
  // Settings that would be ignored.
  c.body.motions = {kOwnAnimation};
  c.body.own->garment_pose = "first_frame";
  e = test::error_of<InputError>([&] { check_own_body(c, "c.yaml"); });
  EXPECT_NE(e.find("c.yaml: body.own.garment_pose: expected bind for a mesh sequence"), std::string::npos) << e;
  c.body.own->garment_pose = "bind";
  c.body.variation = MotionVariation{};
  e = test::error_of<InputError>([&] { check_own_body(c, "c.yaml"); });
  EXPECT_NE(e.find("c.yaml: body.variation: expected nothing with body.own"), std::string::npos) << e;
  c.body.variation.reset();
  c.body.motions = {"bvh:cmu/01_01.bvh"};
  // A clip on a rig without the joints retargeting needs.
  c.body.own->file = path;
  SceneSpec spec;
  spec.motion = "bvh:cmu/01_01.bvh";
  e = test::error_of<InputError>([&] { own_body(c, spec); });
  EXPECT_NE(e.find("rig.glb: skeleton: expected the joints a BVH clip is retargeted onto"), std::string::npos) << e;
  EXPECT_NE(e.find("got no LeftUpLeg"), std::string::npos) << e;
}

// The simulator is chaotic at the level of one float ulp of body motion
// (a rig whose joints are nudged by one ulp moves the body by 2.4e-7 m and
// the garments of this coarse scene by 2-4 mm on average, their mean speed
// by up to 8%; docs/log/2026-12-06-own-body.md), and a rig stored as
// float32 reproduces our body only to that level. So the body is compared
// with the native scene's in every frame (1e-5 m), and the garments by how
// far they are from the native scene's against how far one ulp of body
// motion takes them.
TEST(OwnBody, TheTposeRigReadBackSimulatesAsTheNativeScene) {
  test::TempDir dir("own_body");
  const GeneratorConfig native = cfg::read<GeneratorConfig>(tiny_tree());
  const TPoseMeshes t = tpose_meshes(native, 0);
  ASSERT_TRUE(t.problem.empty()) << t.problem;
  for (const auto& [name, mesh] : t.garments) data::write_obj(dir.file(name + ".obj"), mesh);
  dir.write("jacket.yaml", "self_contact: false\n");
  data::SkinnedBody nudged = t.rig;
  for (std::size_t i = 12 * nudged.joint_names.size(); i < nudged.joints.size(); ++i)
    nudged.joints[i] = std::nextafter(nudged.joints[i], 10.0f);
  const std::string files =
      "[{inner: ['file:" + dir.file("dress.obj") + "'], outer: 'file:" + dir.file("jacket.obj") + "'}]";
  // The garment files on our body, and on the rig read back (as written, and nudged).
  cfg::Node ours_tree = tiny_tree();
  set_outfits(ours_tree, files);
  const GeneratorConfig ours = cfg::read<GeneratorConfig>(ours_tree);
  std::vector<data::SequenceData> own;
  for (const data::SkinnedBody* rig : {&t.rig, static_cast<const data::SkinnedBody*>(&nudged)}) {
    const std::string path = write_rig(dir, "body" + std::to_string(own.size()) + ".glb", *rig);
    cfg::Node own_tree = tiny_tree({"body.motions=[animation]"});
    set_outfits(own_tree, files);
    cfg::apply_set(own_tree, "body.own={file: '" + path + "', garment_pose: first_frame}");
    GeneratorConfig c = cfg::read<GeneratorConfig>(own_tree);
    check(c, "test");
    resolve_own_body(c);
    EXPECT_EQ(c.body.own->hash.size(), 16u);
    own.push_back(generate_one(c, dir.file("own" + std::to_string(own.size()))));
  }
  const data::SequenceData a = generate_one(ours, dir.file("ours"));
  const data::SequenceData& b = own[0];
  EXPECT_TRUE(b.shape.empty()) << "no shape parameters of ours for a user's body";
  EXPECT_EQ(b.motion, "animation:body0.glb#motion");
  ASSERT_EQ(b.body.positions.size(), a.body.positions.size());
  double body = 0;
  for (std::size_t i = 0; i < a.body.positions.size(); ++i)
    body = std::max<double>(body, std::abs(b.body.positions[i] - a.body.positions[i]));
  EXPECT_LT(body, 1e-5) << "the body in every recorded frame";
  ASSERT_EQ(b.garments.size(), 2u);
  for (std::size_t g = 0; g < 2; ++g) {
    const data::GarmentData &x = a.garments[g], &y = b.garments[g];
    double rest = 0;
    for (std::size_t i = 0; i < x.rest.size(); ++i) rest = std::max<double>(rest, std::abs(y.rest[i] - x.rest[i]));
    EXPECT_LT(rest, 1e-5) << x.name << ": placed where the native scene places it";
    const double apart = mean_distance_mm(x.positions, y.positions);
    const double ulp = mean_distance_mm(y.positions, own[1].garments[g].positions);
    EXPECT_LE(apart, 3.0 * ulp + 0.5) << x.name << ": " << apart << " mm from the native scene, " << ulp
                                      << " mm from the run one ulp of body motion away";
    std::printf(
        "%s: body within %.2g m, garments %.3g mm from the native scene's on average (one ulp of body "
        "motion: %.3g mm), speed %.3f / %.3f mm per frame\n",
        x.name.c_str(), body, apart, ulp, garment_speed_mm(x, a.n_frames), garment_speed_mm(y, b.n_frames));
  }
}

// A BVH clip retargeted onto a Mixamo-style rig with our joint names
// (our body's rig, its joints named "mixamorig:<joint>" and 30 more under
// the left hand, as a rig with fingers has): the clip's frames after the
// transition, the feet on the ground. (Not our body's frames: a user's motion is not repaired
// where the body passes through itself, and a file's rig has no bone
// tails for its leaves, so the toes and thumbs aim where the rig
// suggests; docs/own-data.md.)
TEST(OwnBody, ABvhClipIsRetargetedOntoARigWithOurJointNames) {
  test::TempDir dir("own_body");
  const std::vector<std::string> clip = {"body.motions=[bvh:cmu/131_01_start_walk_stop.bvh]", "frames=20"};
  const TPoseMeshes t = tpose_meshes(cfg::read<GeneratorConfig>(tiny_tree(clip)), 0);
  cfg::Node tree = tiny_tree(clip);
  cfg::apply_set(tree, "body.own={file: '" + write_rig(dir, "body.glb", mixamo_style(t.rig, 30)) +
                           "', garment_pose: first_frame}");
  const GeneratorConfig own = cfg::read<GeneratorConfig>(tree);
  SceneSpec spec;
  spec.motion = "bvh:cmu/131_01_start_walk_stop.bvh";
  const motion::GeneratedBody g = own_body(own, spec);
  ASSERT_EQ(g.sequence.num_frames, 22);
  EXPECT_EQ(g.sequence.num_joints, 61);
  EXPECT_EQ(g.body.skeleton.names[0], "Hips");
  EXPECT_EQ(g.sequence.motion, "bvh:cmu/131_01_start_walk_stop.bvh");
  const std::size_t nv = static_cast<std::size_t>(g.sequence.num_vertices);
  for (int f = 2; f < 22; ++f) {
    float lowest = 1e9f;
    for (std::size_t v = 0; v < nv; ++v) lowest = std::min(lowest, g.sequence.positions[(f * nv + v) * 3 + 1]);
    EXPECT_NEAR(lowest, 0.0, 0.02) << "frame " << f << ": a foot on the ground";
  }
}

}  // namespace
}  // namespace layers::generate
