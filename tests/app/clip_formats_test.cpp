// Clips from formats whose rest pose turns the bones (docs/physics.md, "Animation"): glTF, FBX,
// Collada and the seed's .x hold each key as the bone's whole local rotation, rest included, where
// a clip holds the turn from rest. The check is what any animation means whatever its format: each
// bone's turn in the world, rest to keyed, is the same read from the clip (its turns composed down
// its bones) as worked out from the file's own nodes and keys; and a frame keyed at the rest pose
// is no turn at all.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "clips/clip_file.h"
#include "physics/animation.h"
#include "temp_folder.h"

namespace {

using phys::Quat;
using phys::Vec3;

constexpr unsigned kFrames = 3;
constexpr double kFrameTime = 1.0 / 30.0;  // unit: s
// In seconds: assimp 5.2's FBX and Collada writers write a key's time in ticks as if in seconds.
constexpr double kTicksPerSecond = 1.0;
// assimp keeps its keys in float: turns agree to about 1e-7 rad, taken through a few products.
constexpr double kTurnTolerance = 1e-5;  // unit: rad

Quat toQuat(const aiQuaternion& q) {
  return Quat(q.w, q.x, q.y, q.z);
}

Quat rotationOf(const aiMatrix4x4& m) {
  aiVector3D scaling, position;
  aiQuaternion rotation;
  m.Decompose(scaling, rotation, position);
  return glm::normalize(toQuat(rotation));
}

double angleBetween(const Quat& a, const Quat& b) {
  return 2.0 * std::acos(std::min(1.0, std::abs(static_cast<double>(glm::dot(a, b)))));
}

const aiNodeAnim* channelOf(const aiAnimation& a, const aiString& node) {
  for (unsigned c = 0; c < a.mNumChannels; ++c) {
    if (a.mChannels[c]->mNodeName == node) return a.mChannels[c];
  }
  return nullptr;
}

// What the file says each animated bone does at `frame`: its orientation in the file's frame, keyed,
// times the inverse of its orientation at rest, from the nodes' rotations down from the root (every
// node at rest but the animated ones at their keys). Independent of the loader: assimp's scene only.
void worldTurns(const aiNode& node, const aiAnimation& a, unsigned frame, const Quat& keyedParent,
                const Quat& restParent, std::map<std::string, Quat>& out) {
  const Quat rest = restParent * rotationOf(node.mTransformation);
  Quat keyed = keyedParent * rotationOf(node.mTransformation);
  if (const aiNodeAnim* channel = channelOf(a, node.mName)) {
    keyed = keyedParent * glm::normalize(toQuat(channel->mRotationKeys[frame].mValue));
    out[node.mName.C_Str()] = keyed * glm::conjugate(rest);
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) worldTurns(*node.mChildren[i], a, frame, keyed, rest, out);
}

// The same from the clip: its turns composed from the root down, as a character composes them.
std::map<std::string, Quat> clipWorldTurns(const phys::Clip& clip, unsigned frame) {
  std::vector<Quat> world(clip.bones.size());
  std::map<std::string, Quat> out;
  for (std::size_t b = 0; b < clip.bones.size(); ++b) {
    const Quat turn = clip.turns[frame * clip.bones.size() + b];
    world[b] = clip.parents[b] < 0 ? turn : world[static_cast<std::size_t>(clip.parents[b])] * turn;
    out[clip.bones[b]] = world[b];
  }
  return out;
}

// Checks `clip` against the animation of `scene` frame by frame; the rest frame, if any, is no turn.
void expectSameMotion(const phys::Clip& clip, const aiScene& scene, int restFrame, const std::string& what) {
  ASSERT_EQ(clip.frames(), kFrames) << what;
  for (unsigned f = 0; f < kFrames; ++f) {
    std::map<std::string, Quat> expected;
    worldTurns(*scene.mRootNode, *scene.mAnimations[0], f, Quat(1.0, 0.0, 0.0, 0.0), Quat(1.0, 0.0, 0.0, 0.0),
               expected);
    const std::map<std::string, Quat> read = clipWorldTurns(clip, f);
    ASSERT_EQ(read.size(), expected.size()) << what;
    for (const auto& [bone, turn] : expected) {
      ASSERT_TRUE(read.contains(bone)) << what << ": bone " << bone;
      EXPECT_LT(angleBetween(read.at(bone), turn), kTurnTolerance)
          << what << ": frame " << f << ", bone " << bone;
      if (static_cast<int>(f) == restFrame) {
        EXPECT_LT(angleBetween(read.at(bone), Quat(1.0, 0.0, 0.0, 0.0)), kTurnTolerance)
            << what << ": bone " << bone << " is turned in the frame keyed at rest";
      }
    }
  }
}

aiMatrix4x4 transform(const Vec3& at, const Quat& turn, double scale = 1.0) {
  const aiQuaternion q(static_cast<float>(turn.w), static_cast<float>(turn.x), static_cast<float>(turn.y),
                       static_cast<float>(turn.z));
  const auto s = static_cast<float>(scale);
  return aiMatrix4x4(
      aiVector3D(s, s, s), q,
      aiVector3D(static_cast<float>(at.x), static_cast<float>(at.y), static_cast<float>(at.z)));
}

Quat turnAbout(double degrees, const Vec3& axis) {
  return glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
}

// A leg under an armature the way exporters leave one: the armature moved, turned a quarter about x
// (z-up to y-up) and scaled to centimetres, the hips turned at rest, a twist node that is not
// animated between the hips and the thigh, and each animated bone keyed at rest in frame 1 (not the
// first, so that a loader taking its rest from the first key fails) and turned either way of it in
// frames 0 and 2. A triangle, since some exporters want a mesh.
std::unique_ptr<aiScene> legScene() {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("scene");
  auto* armature = new aiNode("armature");
  auto* hips = new aiNode("hips");
  auto* twist = new aiNode("twist");
  auto* thigh = new aiNode("thigh");
  auto* shin = new aiNode("shin");
  scene->mRootNode->addChildren(1, &armature);
  armature->addChildren(1, &hips);
  hips->addChildren(1, &twist);
  twist->addChildren(1, &thigh);
  thigh->addChildren(1, &shin);
  armature->mTransformation = transform(Vec3(0.5, 0.0, -0.2), turnAbout(-90.0, Vec3(1, 0, 0)), 0.01);
  const std::map<std::string, std::pair<Vec3, Quat>> rest{
      {"hips", {Vec3(0.0, 0.0, 95.0), turnAbout(30.0, Vec3(0, 1, 1))}},
      {"thigh", {Vec3(10.0, 0.0, 0.0), turnAbout(-50.0, Vec3(1, 0, 0.3))}},
      {"shin", {Vec3(0.0, -45.0, 0.0), turnAbout(20.0, Vec3(0, 0, 1))}}};
  twist->mTransformation = transform(Vec3(0.0), turnAbout(70.0, Vec3(0, 1, 0)));
  for (aiNode* node : {hips, thigh, shin}) {
    const auto& [at, turn] = rest.at(node->mName.C_Str());
    node->mTransformation = transform(at, turn);
  }

  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { new aiMesh };
  aiMesh& mesh = *scene->mMeshes[0];
  mesh.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh.mNumVertices = 3;
  mesh.mVertices = new aiVector3D[3]{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.mNumFaces = 1;
  mesh.mFaces = new aiFace[1];
  mesh.mFaces[0].mNumIndices = 3;
  mesh.mFaces[0].mIndices = new unsigned[3]{0, 1, 2};
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial };

  scene->mNumAnimations = 1;
  scene->mAnimations = new aiAnimation* [1] { new aiAnimation };
  aiAnimation& anim = *scene->mAnimations[0];
  anim.mTicksPerSecond = kTicksPerSecond;
  anim.mDuration = (kFrames - 1) * kFrameTime * kTicksPerSecond;
  anim.mNumChannels = 3;
  anim.mChannels = new aiNodeAnim*[3];
  const char* bones[] = {"hips", "thigh", "shin"};
  for (unsigned c = 0; c < 3; ++c) {
    auto* channel = new aiNodeAnim;
    anim.mChannels[c] = channel;
    channel->mNodeName = bones[c];
    channel->mNumRotationKeys = channel->mNumPositionKeys = channel->mNumScalingKeys = kFrames;
    channel->mRotationKeys = new aiQuatKey[kFrames];
    channel->mPositionKeys = new aiVectorKey[kFrames];
    channel->mScalingKeys = new aiVectorKey[kFrames];
    const auto& [at, restTurn] = rest.at(bones[c]);
    for (unsigned f = 0; f < kFrames; ++f) {
      const double degrees = 25.0 * (static_cast<double>(f) - 1.0) * (c + 1);
      const Quat turn = turnAbout(degrees, Vec3(1.0, 0.5 * c, 0.2 * f)) * restTurn;
      const aiMatrix4x4 key = transform(at + Vec3(f * 3.0, 0.0, 0.0), turn);
      aiVector3D scaling, position;
      aiQuaternion rotation;
      key.Decompose(scaling, rotation, position);
      const double tick = f * kFrameTime * kTicksPerSecond;
      channel->mRotationKeys[f] = aiQuatKey(tick, rotation);
      channel->mPositionKeys[f] = aiVectorKey(tick, position);
      channel->mScalingKeys[f] = aiVectorKey(tick, aiVector3D(1, 1, 1));
    }
  }
  return scene;
}

TEST(ClipFormats, KeysOfTurnedRestPosesAreReadAsTurnsFromRest) {
  const std::unique_ptr<aiScene> scene = legScene();
  const testing_app::TempFolder dir;
  Assimp::Exporter exporter;
  // assimp 5.2 writes animations in these (its .x writer leaves them out: the next test writes one).
  for (const auto& [format, extension] : {std::pair{"glb2", "glb"}, {"fbxa", "fbx"}, {"collada", "dae"}}) {
    const std::filesystem::path file = dir.path / (std::string("leg.") + extension);
    ASSERT_EQ(exporter.Export(scene.get(), format, file.string()), aiReturn_SUCCESS)
        << format << ": " << exporter.GetErrorString();
    const phys::Clip clip = clips::loadClip(file);
    EXPECT_EQ(clip.bones, (std::vector<std::string>{"hips", "thigh", "shin"})) << format;
    EXPECT_EQ(clip.parents, (std::vector<int>{-1, 0, 1})) << format;
    EXPECT_NEAR(clip.frameTime, kFrameTime, 1e-6) << format;
    expectSameMotion(clip, *scene, 1, format);
    // The hips' position in the file's frame: the armature moves, turns z up to y up and scales to
    // metres.
    EXPECT_NEAR(glm::length(clip.root[0] - Vec3(0.5, 0.95, -0.2)), 0.0, 1e-5) << format;
    EXPECT_NEAR(glm::length(clip.root[2] - Vec3(0.56, 0.95, -0.2)), 0.0, 1e-5) << format;
  }
}

// A .x file as the seed's engine read them: frames with their rest matrices (row vectors, the
// translation in the last row), an animation of matrix keys, frame 1 at rest.
std::string xFile() {
  const auto matrix = [](const Vec3& at, const Quat& turn) {
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), at) * glm::mat4_cast(turn);
    std::ostringstream s;
    s.setf(std::ios::fixed);  // assimp's .x reader takes no exponents
    s.precision(12);
    // glm stores columns one after another, which is the row-vector matrix row by row.
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) s << (c + r > 0 ? "," : "") << m[c][r];
    return s.str();
  };
  const Quat hipsRest = turnAbout(40.0, Vec3(0, 1, 1)), kneeRest = turnAbout(-35.0, Vec3(1, 0.2, 0));
  const Vec3 hipsAt(0.0, 0.9, 0.0), kneeAt(0.0, -0.45, 0.05);
  std::ostringstream x;
  x << "xof 0303txt 0032\n"
    << "AnimTicksPerSecond { " << 1.0 / kFrameTime << "; }\n"
    << "Frame root {\n FrameTransformMatrix { " << matrix(Vec3(1.0, 0.0, 2.0), turnAbout(15.0, Vec3(0, 1, 0)))
    << ";; }\n"
    << " Frame hips {\n  FrameTransformMatrix { " << matrix(hipsAt, hipsRest) << ";; }\n"
    << "  Frame knee {\n   FrameTransformMatrix { " << matrix(kneeAt, kneeRest) << ";; }\n  }\n }\n}\n"
    << "AnimationSet walk {\n";
  for (const auto& [name, at, rest, axis] : {std::tuple{"hips", hipsAt, hipsRest, Vec3(0, 0, 1)},
                                             std::tuple{"knee", kneeAt, kneeRest, Vec3(1, 0, 0)}}) {
    x << " Animation {\n  {" << name << "}\n  AnimationKey { 4; " << kFrames << ";\n";
    for (unsigned f = 0; f < kFrames; ++f)
      x << "   " << f << "; 16; " << matrix(at, turnAbout(30.0 * (static_cast<double>(f) - 1.0), axis) * rest)
        << ";;" << (f + 1 < kFrames ? ",\n" : ";\n");
    x << "  }\n }\n";
  }
  x << "}\n";
  return x.str();
}

TEST(ClipFormats, TheSeedsXFilesAreReadAsTurnsFromRest) {
  const testing_app::TempFolder dir;
  const std::filesystem::path file = dir.path / "walk.x";
  std::ofstream(file) << xFile();
  const phys::Clip clip = clips::loadClip(file);
  EXPECT_EQ(clip.bones, (std::vector<std::string>{"hips", "knee"}));
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  expectSameMotion(clip, *scene, 1, "walk.x");
  // Frame 2 turns the knee 30 degrees from rest (about the hips' x, as the key is the turn times the
  // rest), whatever the file's rest pose.
  const Quat knee = clip.turns[2 * clip.bones.size() + 1];
  EXPECT_NEAR(2.0 * std::acos(std::min(1.0, std::abs(knee.w))), glm::radians(30.0), 1e-5);
  // The hips at (0, 0.9, 0) in the root frame, which is turned about the up axis and moved to
  // (1, 0, 2); .x is left-handed, and assimp makes it right-handed by turning z round.
  EXPECT_NEAR(glm::length(clip.root[1] - Vec3(1.0, 0.9, -2.0)), 0.0, 1e-5)
      << clip.root[1].x << " " << clip.root[1].y << " " << clip.root[1].z;
}

}  // namespace
