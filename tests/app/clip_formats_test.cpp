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
#include <iterator>
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

// The message parseClip refuses `content` with, or "loaded".
std::string refusal(const std::string& content, const std::string& name) {
  try {
    clips::parseClip(content, name, std::filesystem::path(name).extension().string().substr(1));
  } catch (const clips::ClipError& e) {
    return e.what();
  }
  return "loaded";
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The leg written by assimp as `format`, as text.
std::string legFile(const testing_app::TempFolder& dir, const char* format, const char* extension) {
  const std::unique_ptr<aiScene> scene = legScene();
  const std::filesystem::path file = dir.path / (std::string("leg.") + extension);
  Assimp::Exporter exporter;
  EXPECT_EQ(exporter.Export(scene.get(), format, file.string()), aiReturn_SUCCESS)
      << exporter.GetErrorString();
  return readText(file);
}

// `text` with its first `from` made `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string repeated(const std::string& s, int times) {
  std::string out;
  for (int i = 0; i < times; ++i) out += s;
  return out;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// assimp reads forty formats, most of them meshes; a clip is read from five, each through its own
// reader alone.
TEST(ClipFormats, OnlyTheClipFormatsAreRead) {
  const std::string obj = refusal("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "mesh.obj");
  EXPECT_TRUE(has(obj, "mesh.obj: not a clip file: clips are read from BVH (.bvh), FBX (.fbx), glTF")) << obj;
  const std::string none = refusal("#!/bin/sh\n", "script.sh");
  EXPECT_TRUE(has(none, "script.sh: not a clip file")) << none;
}

// A glTF names its buffers by path, which assimp opened from the working folder, and any path at all
// (a pipe there held the reader for good): a clip is read from its own bytes alone.
TEST(ClipFormats, AGltfReadsNoFileButItself) {
  const testing_app::TempFolder dir;
  std::string gltf = legFile(dir, "gltf2", "gltf");
  const std::string bin = (dir.path / "leg.bin").string();
  ASSERT_TRUE(std::filesystem::exists(bin));
  gltf = replaced(gltf, "\"uri\": \"leg.bin\"", "\"uri\": \"" + bin + "\"");
  const std::string e = refusal(gltf, "leg.gltf");
  EXPECT_TRUE(has(e, "leg.gltf: not a clip assimp can read: GLTF: could not open referenced file \"" + bin))
      << e;
}

// assimp's readers recurse once a level of JSON, XML, braces or nodes: 50,000 levels overflowed the
// stack in each. Refused past 256, with the line (or the node).
TEST(ClipFormats, NestingTooDeepIsRefusedWithTheLine) {
  constexpr int kLevels = 50000;
  const std::string deepJson = "{\"asset\": {\"version\": \"2.0\"},\n\"extras\": " + repeated("[", kLevels) +
                               repeated("]", kLevels) + "}";
  EXPECT_EQ(refusal(deepJson, "deep.gltf"),
            "deep.gltf:2: objects and arrays nested more than 256 deep (a skeleton's are tens deep)");
  std::string chain =
      "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [";
  for (int i = 0; i < kLevels; ++i) chain += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
  chain += "{}]}";
  EXPECT_EQ(refusal(chain, "chain.gltf"),
            "chain.gltf: node 257: nodes nested more than 256 deep (a skeleton's are tens deep)");

  const testing_app::TempFolder dir;
  const std::string dae = legFile(dir, "collada", "dae");
  const std::string deepDae =
      replaced(dae, "<node id=\"shin\"",
               repeated("<node>", kLevels) + repeated("</node>", kLevels) + "<node id=\"shin\"");
  const std::size_t line = 1 + std::count(dae.begin(), dae.begin() + dae.find("<node id=\"shin\""), '\n');
  const std::string e = refusal(deepDae, "deep.dae");
  EXPECT_TRUE(has(e, "deep.dae:" + std::to_string(line) + ": elements nested more than 256 deep")) << e;

  const std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::string deepFbx =
      replaced(fbx, "Objects:  {", "Deep: " + repeated("{ A: ", kLevels) + "\nObjects:  {");
  const std::size_t fbxLine = 1 + std::count(fbx.begin(), fbx.begin() + fbx.find("Objects:  {"), '\n');
  const std::string f = refusal(deepFbx, "deep.fbx");
  EXPECT_EQ(f, "deep.fbx:" + std::to_string(fbxLine) +
                   ": braces nested more than 256 deep (a skeleton's are tens deep)");

  const std::string deepX =
      replaced(xFile(), " Frame hips {", repeated(" Frame f {\n", kLevels) + " Frame hips {");
  const std::string x = refusal(deepX, "deep.x");
  EXPECT_TRUE(has(x, "deep.x:") && has(x, ": braces nested more than 256 deep")) << x;
}

// assimp allocates what a count says before it reads the values: a COLLADA array, an FBX array and
// a .x mesh of 4,000,000,000 each asked for 16 GB or more.
TEST(ClipFormats, CountsTheFileDoesNotHoldAreRefusedWithTheLine) {
  const testing_app::TempFolder dir;
  const std::string dae = legFile(dir, "collada", "dae");
  const std::size_t array = dae.find("<float_array");
  const std::size_t count = dae.find("count=\"", array) + 7;
  const std::string bigDae = dae.substr(0, count) + "4000000000" + dae.substr(dae.find('"', count));
  const std::string d = refusal(bigDae, "big.dae");
  EXPECT_TRUE(has(d, "big.dae:" + std::to_string(1 + std::count(dae.begin(), dae.begin() + array, '\n')) +
                         ": <float_array> says count=\"4000000000\" but holds "))
      << d;
  const std::string negative = dae.substr(0, count) + "-1" + dae.substr(dae.find('"', count));
  EXPECT_TRUE(has(refusal(negative, "neg.dae"), "<float_array> count=\"-1\" is not a whole number"));

  const std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::string keyTimes =
      fbx.substr(fbx.find("KeyTime: *"), fbx.find(" {", fbx.find("KeyTime: *")) - fbx.find("KeyTime: *"));
  const std::string bigFbx = replaced(fbx, keyTimes + " {", "KeyTime: *4000000000 {");
  const std::string f = refusal(bigFbx, "big.fbx");
  EXPECT_TRUE(has(f, ": KeyTime: *4000000000 holds ")) << f;

  const std::string bigX =
      replaced(xFile(), "Frame root {", "Mesh m { 4000000000; 0.0;0.0;0.0;; }\nFrame root {");
  const std::string x = refusal(bigX, "big.x");
  EXPECT_TRUE(has(x, "big.x:3: Mesh of 4000000000, more than the ")) << x;
}

// assimp 5.2 asserts that each index of a COLLADA accessor is within its array, and aborted on a
// stride that reads past it.
TEST(ClipFormats, ColladaAccessorsStayWithinTheirArrays) {
  const testing_app::TempFolder dir;
  const std::string dae = legFile(dir, "collada", "dae");
  const std::string strided = replaced(dae, "stride=\"16\"", "stride=\"4000000000\"");
  const std::string e = refusal(strided, "stride.dae");
  EXPECT_TRUE(has(e, "<accessor> of count=\"3\" reads ")) << e;
}

// An FBX curve of no times and no values made assimp 5.2 read through a null pointer.
TEST(ClipFormats, AnFbxCurveOfNoKeysIsRefused) {
  const testing_app::TempFolder dir;
  std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::size_t times = fbx.find("KeyTime: *");
  const std::size_t end = fbx.find("KeyAttrFlags", times);
  fbx.replace(times, end - times, "KeyTime: *0 {\n a: \n}\nKeyValueFloat: *0 {\n a: \n}\n");
  const std::string e = refusal(fbx, "empty.fbx");
  EXPECT_TRUE(has(e, ": KeyTime: *0: an animation curve of no keys")) << e;
}

// What assimp reads or refuses itself, and what the clip's own checks then refuse: every format's
// truncated file, and keys that are not finite, out of time order or at one time.
TEST(ClipFormats, WhatAssimpRefusesOrReadsIsRefusedWithTheReason) {
  const testing_app::TempFolder dir;
  for (const auto& [format, extension] : {std::pair{"fbxa", "fbx"}, {"collada", "dae"}, {"glb2", "glb"}}) {
    const std::string whole = legFile(dir, format, extension);
    EXPECT_EQ(refusal(whole, std::string("leg.") + extension), "loaded") << format;
    const std::string cut = refusal(whole.substr(0, whole.size() / 2), std::string("cut.") + extension);
    EXPECT_TRUE(has(cut, "not a clip assimp can read: ")) << cut;
  }
  EXPECT_TRUE(has(refusal(xFile().substr(0, 300), "cut.x"), "cut.x: not a clip assimp can read: "));

  const std::string dae = legFile(dir, "collada", "dae");
  const std::size_t times = dae.find("<float_array", dae.find("<library_animations"));
  const std::size_t from = dae.find('>', times) + 1;
  const std::string keys = dae.substr(from, dae.find('<', from) - from);
  const std::string nan = refusal(replaced(dae, keys, " 0 nan 0.0666 "), "nan.dae");
  EXPECT_TRUE(nan != "loaded" && has(nan, "nan.dae: ")) << nan;
  EXPECT_NE(refusal(replaced(dae, keys, " 0 0.0666 0.0333 "), "order.dae"), "loaded");
  EXPECT_NE(refusal(replaced(dae, keys, " 0 0 0 "), "same.dae"), "loaded");
  const std::string x = xFile();
  const std::string turned = replaced(x, "AnimTicksPerSecond { 30; }", "AnimTicksPerSecond { -30; }");
  EXPECT_EQ(refusal(turned, "ticks.x"), "ticks.x: its frame time is not finite and >= 1e-6 s");
}

}  // namespace
