// Clips from formats whose rest pose turns the bones (docs/physics.md, "Animation"): glTF, FBX,
// Collada and the seed's .x hold each key as the bone's whole local rotation, rest included, where
// a clip holds the turn from rest. The check is what any animation means whatever its format: each
// bone's turn in the world, rest to keyed, is the same read from the clip (its turns composed down
// its bones) as worked out from the file's own nodes and keys; and a frame keyed at the rest pose
// is no turn at all.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
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

#include "clip_refusal.h"
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

using testing_clips::refusal;

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

// assimp allocates what a .glb's header and chunks say they hold before it reads them: a JSON chunk
// said to be 1.7 GB long was allocated whole (found by the clip fuzzer). A length past the file's end
// is refused, saying which.
TEST(ClipFormats, AGlbLengthPastTheFilesEndIsRefused) {
  const testing_app::TempFolder dir;
  const std::string glb = legFile(dir, "glb2", "glb");
  ASSERT_EQ(glb.substr(16, 4), "JSON");
  const auto with = [&](std::size_t at, std::uint32_t value) {
    std::string changed = glb;
    std::memcpy(changed.data() + at, &value, sizeof value);
    return changed;
  };
  const auto size = static_cast<std::uint32_t>(glb.size());
  const std::string holds = " bytes, but it has " + std::to_string(size);
  const std::string past = " bytes, past the file's end (" + std::to_string(size) + " bytes)";
  EXPECT_EQ(refusal(with(8, size + 1), "long.glb"),
            "long.glb: its header says the file has " + std::to_string(size + 1) + holds);
  EXPECT_EQ(refusal(with(12, 0x670003b8), "json.glb"),
            "json.glb: the chunk at byte 12 says it has 1728054200" + past);
  std::uint32_t json = 0;
  std::memcpy(&json, glb.data() + 12, sizeof json);
  const std::uint32_t bin = (20 + json + 3) / 4 * 4;
  ASSERT_EQ(glb.substr(bin + 4, 4), std::string("BIN\0", 4));
  // One byte more than the file holds after the chunk's own eight.
  const std::uint32_t over = size - bin - 7;
  EXPECT_EQ(refusal(with(bin, over), "bin.glb"), "bin.glb: the chunk at byte " + std::to_string(bin) +
                                                     " says it has " + std::to_string(over) + past);
  // glTF 1.0 is not read at all: its reader overflowed the stack on a binary file's deep JSON.
  EXPECT_EQ(refusal(with(4, 1), "one.glb"), "one.glb: a glTF 1.0 file: clips are read from glTF 2.0");
  const std::string one =
      refusal(R"({"asset": {"version": "1.0"}, "scene": "s", "scenes": {"s": {"nodes": []}}})", "one.gltf");
  EXPECT_TRUE(has(one, "one.gltf: not a clip assimp can read: ") && has(one, "1.0")) << one;
}

// assimp imports a glTF node under each node that lists it as a child, as often as it does: 25
// nodes each listing the next twice unfolded to 2^25 (2 GB), and a chain whose nodes the root lists
// too nests as deep as the chain, though each node is one level below the root.
TEST(ClipFormats, GltfNodesThatUnfoldTooFarAreRefused) {
  const auto gltf = [](const std::vector<std::string>& children) {
    std::string nodes;
    for (const std::string& list : children)
      nodes += std::string(nodes.empty() ? "" : ", ") + "{\"children\": [" + list + "]}";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" + nodes +
           "]}";
  };
  std::vector<std::string> doubling;
  doubling.reserve(26);
  for (int i = 0; i < 25; ++i) doubling.push_back(std::to_string(i + 1) + ", " + std::to_string(i + 1));
  doubling.emplace_back("");
  // Node k unfolds to 2^(26 - k) - 1 nodes: node 9 is the first past 100,000.
  EXPECT_EQ(refusal(gltf(doubling), "dag.gltf"),
            "dag.gltf: node 9 unfolds, a copy under each node that lists it as a child, to more than 100000 "
            "nodes (a skeleton has tens)");
  constexpr int kChain = 400;
  std::vector<std::string> chain{""};
  for (int i = 1; i <= kChain; ++i) {
    chain[0] += (i > 1 ? ", " : "") + std::to_string(i);
    chain.push_back(i < kChain ? std::to_string(i + 1) : "");
  }
  // Node k has kChain - k levels below it: node 143 is the first with more than 256.
  EXPECT_EQ(refusal(gltf(chain), "chain.gltf"),
            "chain.gltf: node 143: nodes below it nested more than 256 deep (a skeleton's are tens deep)");
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
  // assimp ends a key at its colon: "KeyTime:*N" is the key and the count, as with a space.
  const std::string tight = refusal(replaced(fbx, keyTimes + " {", "KeyTime:*4000000000 {"), "tight.fbx");
  EXPECT_TRUE(has(tight, ": KeyTime: *4000000000 holds ")) << tight;

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

  // An array without a count holds no values for assimp, whatever its text (the clip fuzzer's
  // finding: a misspelt count aborted it on the first key time read).
  const std::size_t array = dae.find("<float_array");
  const std::size_t count = dae.find("count=\"", array);
  const std::string uncounted = dae.substr(0, count) + "c0unt" + dae.substr(count + 5);
  const std::string u = refusal(uncounted, "uncounted.dae");
  EXPECT_TRUE(has(u, "values of '")) << u;
  EXPECT_TRUE(has(u, "', which holds 0")) << u;
  // ... and one without an id is the one an accessor's source="#" reads.
  const std::size_t idAt = dae.find("id=\"", array);
  const std::string id = dae.substr(idAt + 4, dae.find('"', idAt + 4) - idAt - 4);
  const std::string unnamed =
      replaced(replaced(uncounted, "id=\"" + id + "\"", ""), "source=\"#" + id + "\"", "source=\"#\"");
  const std::string n = refusal(unnamed, "unnamed.dae");
  EXPECT_TRUE(has(n, "values of '', which holds 0")) << n;
}

// A sampler's key times and values are numbers: assimp asserted (aborting) when one's accessor
// read a <Name_array>, which it keeps as names (the clip fuzzer's finding), and a key of more than
// 16 numbers overran the buffer it reads a key into.
TEST(ClipFormats, ColladaKeysAreReadFromNumbersAndFitAMatrix) {
  const testing_app::TempFolder dir;
  const std::string dae = legFile(dir, "collada", "dae");
  // An output's array made a <Name_array>: its words are the same, but assimp keeps them as names.
  const std::size_t output = dae.find("-output-array");
  ASSERT_NE(output, std::string::npos);
  const std::size_t open = dae.rfind("<float_array", output);
  const std::size_t close = dae.find("</float_array>", output);
  const std::string named = dae.substr(0, open) + "<Name_array" + dae.substr(open + 12, close - open - 12) +
                            "</Name_array>" + dae.substr(close + 14);
  const std::string e = refusal(named, "named.dae");
  EXPECT_TRUE(has(e, "<input semantic=\"OUTPUT\"> reads numbers from '")) << e;
  EXPECT_TRUE(has(e, "', which holds names")) << e;

  // One key of 17 numbers, all within its array.
  std::string params;
  for (int i = 0; i < 17; ++i) params += "<param type=\"float\"/>";
  const std::string wide =
      "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><library_animations><animation>\n"
      "<source id=\"t\"><float_array id=\"ta\" count=\"1\">0</float_array><technique_common>"
      "<accessor source=\"#ta\" count=\"1\"><param type=\"float\"/></accessor></technique_common>"
      "</source>\n<source id=\"v\"><float_array id=\"va\" count=\"17\">" +
      repeated("1 ", 17) +
      "</float_array><technique_common>\n<accessor source=\"#va\" count=\"1\" stride=\"17\">" + params +
      "</accessor></technique_common></source>\n"
      "<sampler id=\"s\"><input semantic=\"INPUT\" source=\"#t\"/>"
      "<input semantic=\"OUTPUT\" source=\"#v\"/></sampler>\n"
      "</animation></library_animations></COLLADA>\n";
  EXPECT_EQ(refusal(wide, "wide.dae"),
            "wide.dae:5: <accessor> of a key of 17 numbers, more than a 4x4 matrix's 16");
}

// assimp sizes a COLLADA mesh's indices and a skin's weights by their counts before it reads them:
// 1,000,000,000 triangles asked for 24 GB, an <input offset="100000000"> for 2.4 GB. What they need
// must be there first, refused with the element's line.
TEST(ClipFormats, ColladaIndicesAndWeightsAreThereBeforeTheyAreSized) {
  const auto refusalOf = [](const std::string& element) {
    return refusal("<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><library_geometries>" + element +
                       "</library_geometries></COLLADA>\n",
                   "mesh.dae");
  };
  EXPECT_EQ(refusalOf(R"(<triangles count="1000000000"><input offset="0"/><p>0 1 2</p></triangles>)"),
            R"(mesh.dae:2: <triangles> of count="1000000000" needs 3000000000 indices, but holds 3)");
  EXPECT_EQ(refusalOf(R"(<lines count="2"><input offset="0"/><p>0 1 2</p></lines>)"),
            R"(mesh.dae:2: <lines> of count="2" needs 4 indices, but holds 3)");
  EXPECT_EQ(
      refusalOf(
          R"(<polylist count="1"><input offset="0"/><vcount>3000000000</vcount><p>0 1 2</p></polylist>)"),
      R"(mesh.dae:2: <polylist> of count="1" needs 3000000000 indices, but holds 3)");
  EXPECT_EQ(refusalOf(R"(<triangles count="1"><input offset="100000000"/><p>0 1 2</p></triangles>)"),
            R"(mesh.dae:2: <triangles> of count="1" needs 300000003 indices, but holds 3)");
  // assimp reads an index where the last stopped: at a word that is none it read zeros for good.
  EXPECT_EQ(refusalOf(R"(<polylist count="1"><input offset="0"/><vcount>1</vcount><p>0 1 Z</p></polylist>)"),
            R"(mesh.dae:2: <polylist> <p> holds 'Z', which is not an index)");
  EXPECT_EQ(
      refusalOf(R"(<polygons count="1"><input offset="0"/><ph><p>0 1 2</p><h>3 1.5 5</h></ph></polygons>)"),
      R"(mesh.dae:2: <polygons> <h> holds '1.5', which is not an index)");
  EXPECT_EQ(
      refusalOf(R"(<triangles count="1"><input offset="0"/><p> -1 +1 2 </p></triangles>)").find("index"),
      std::string::npos);
  EXPECT_EQ(
      refusalOf(R"(<polygons count="2"><input offset="0"/><ph><p>0 1 2</p><h>3 4 5</h></ph></polygons>)")
          .find("needs"),
      std::string::npos);
  EXPECT_EQ(
      refusalOf(R"(<polygons count="7"><input offset="0"/><ph><p>0 1 2</p><h>3 4 5</h></ph></polygons>)"),
      R"(mesh.dae:2: <polygons> of count="7" needs 7 indices, but holds 6)");
  EXPECT_EQ(
      refusalOf(
          R"(<triangles count="1"><input offset="0"/><input offset="1"/><p>0 0 1 1 2 2</p></triangles>)")
          .find("needs"),
      std::string::npos);
  EXPECT_EQ(refusalOf(R"(<vertex_weights count="1000000000"><input offset="0"/><input offset="1"/>)"
                      R"(<vcount>1</vcount><v>0 0</v></vertex_weights>)"),
            R"(mesh.dae:2: <vertex_weights> of count="1000000000" needs 1000000000 counts and 2 indices, )"
            R"(but holds 1 and 2)");
  EXPECT_EQ(
      refusalOf(R"(<vertex_weights count="1"><input offset="0"/><input offset="1"/>)"
                R"(<vcount>2000000000</vcount><v>0 0</v></vertex_weights>)"),
      R"(mesh.dae:2: <vertex_weights> of count="1" needs 1 counts and 4000000000 indices, but holds 1 and 2)");
}

// assimp copies the node an <instance_node> names into the node it is in, recursing once a level: a
// node instancing itself or a node it is in overflowed the stack, and nodes instancing each other
// twice over unfold to billions.
TEST(ClipFormats, ColladaNodeInstancesAreRefusedWhereTheyNeverEnd) {
  const auto refusalOf = [](const std::string& library, const std::string& scene) {
    return refusal("<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\">\n<library_nodes>" + library +
                       "</library_nodes>\n<library_visual_scenes><visual_scene id=\"s\">\n" + scene +
                       "</visual_scene></library_visual_scenes></COLLADA>\n",
                   "nodes.dae");
  };
  EXPECT_EQ(
      refusalOf("", "<node id=\"hips\"><node id=\"knee\">\n<instance_node url=\"#hips\"/></node></node>"),
      R"(nodes.dae:6: <instance_node url="#hips"> instances a node it is within)");
  EXPECT_EQ(refusalOf("", "<node id=\"hips\">\n<instance_node url=\"#hips\"/></node>"),
            R"(nodes.dae:6: <instance_node url="#hips"> instances a node it is within)");
  EXPECT_EQ(refusalOf(R"(<node id="a"><instance_node url="#b"/></node><node id="b">)"
                      "\n"
                      R"(<instance_node url="#a"/></node>)",
                      R"(<node id="hips"><instance_node url="#a"/></node>)"),
            R"(nodes.dae:4: <instance_node url="#a"> instances a node it is within)");
  std::string doubling;
  for (int i = 0; i < 20; ++i) {
    const std::string next = "#n" + std::to_string(i + 1);
    doubling += "<node id=\"n" + std::to_string(i) + "\"><instance_node url=\"" + next +
                "\"/><instance_node url=\"" + next + "\"/></node>";
  }
  doubling += "<node id=\"n20\"/>";
  EXPECT_EQ(refusalOf(doubling, ""),
            "nodes.dae:3: <node> unfolds through its <instance_node>s to more than 100000 nodes (a skeleton "
            "has tens)");
  // A chain of 300 library nodes each instancing the next nests 300 deep: n43 is the first with more
  // than 256 levels below it.
  std::string chain;
  for (int i = 0; i < 300; ++i)
    chain += "<node id=\"n" + std::to_string(i) + "\"><instance_node url=\"#n" + std::to_string(i + 1) +
             "\"/></node>";
  chain += "<node id=\"n300\"/>";
  EXPECT_EQ(
      refusalOf(chain, ""),
      "nodes.dae:3: <node> unfolds through its <instance_node>s to nodes below it nested more than 256 deep "
      "(a skeleton's are tens deep)");
  // A node instanced twice, from the library, is no cycle.
  const std::string twice = refusalOf(
      R"(<node id="leg"><node id="foot"/></node>)",
      R"(<node id="hips"><instance_node url="#leg"/><node id="other"><instance_node url="#leg"/></node></node>)");
  EXPECT_EQ(twice.find("instance"), std::string::npos) << twice;
}

void expectSameClip(const phys::Clip& a, const phys::Clip& b, const std::string& what) {
  EXPECT_EQ(a.bones, b.bones) << what;
  EXPECT_EQ(a.parents, b.parents) << what;
  EXPECT_EQ(a.frameTime, b.frameTime) << what;
  EXPECT_EQ(a.root, b.root) << what;
  EXPECT_EQ(a.turns, b.turns) << what;
}

// A clip reads nodes and their keys; assimp's readers take a mesh's and a skin's counts and indices
// on trust (a COLLADA skin's joint index of 50,000,000 was written unchecked, a .x skin weight's
// vertex index too, a .x face's material read from an empty list, an FBX mesh's layer past its
// table). What a clip does not read is
// taken out before assimp reads the file, so broken meshes and skins change nothing.
TEST(ClipFormats, MeshesAndSkinsAreNotRead) {
  const std::string x = xFile();
  const std::string frame = " Frame hips {\n";
  const std::string brokenMesh =
      "Mesh m { 3; 0.0;0.0;0.0;, 1.0;0.0;0.0;, 0.0;1.0;0.0;; 1; 3; 0,1,2;;\n"
      " SkinWeights { \"hips\"; 1; 90000000; 1.0; 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1;; }\n"
      " MeshMaterialList { 0; 1; 0;; } // a material for a face, and no material\n"
      " # a comment holding a brace }\n"
      "}\n";
  const phys::Clip plain = clips::parseClip(x, "walk.x", "x");
  expectSameClip(clips::parseClip(replaced(x, frame, frame + brokenMesh), "mesh.x", "x"), plain, "mesh.x");
  // "template Mesh" declares the type: kept, and no mesh.
  const std::string declared = replaced(x, "AnimTicksPerSecond",
                                        "template Mesh {\n <3D82AB44-62DA-11cf-AB39-0020AF71E433>\n DWORD "
                                        "nVertices;\n [...]\n}\nAnimTicksPerSecond");
  expectSameClip(clips::parseClip(declared, "template.x", "x"), plain, "template.x");
  // assimp reads a quote as a character like any other: a Mesh after one is a Mesh.
  const std::string quoted =
      replaced(x, frame, frame + "Foo { \" }\nMesh m {\n 400000000;\n 0.0;0.0;0.0;;\n}\n\" }\n");
  EXPECT_TRUE(has(refusal(quoted, "quoted.x"), "Mesh of 400000000, more than the "))
      << refusal(quoted, "quoted.x");
  // assimp takes "#" as a comment, as the checks now do: the count after it is the mesh's.
  const std::string hashed = replaced(x, frame, frame + "Mesh m { # 9\n4000000000; 0.0;0.0;0.0;; 0;; }\n");
  EXPECT_TRUE(has(refusal(hashed, "hashed.x"), "Mesh of 4000000000, more than the "))
      << refusal(hashed, "hashed.x");

  // An FBX mesh's texture coordinates indexed per control point, with more indices (the polygon
  // vertices') than control points: assimp read its table past its end.
  const testing_app::TempFolder dir;
  const std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::size_t polygons = fbx.find("PolygonVertexIndex: *");
  ASSERT_NE(polygons, std::string::npos);
  const std::size_t polygonsEnd = fbx.find('}', polygons) + 1;
  const std::string uv =
      "PolygonVertexIndex: *6 {\n a: 0,1,-3,0,1,-3\n}\n"
      "LayerElementUV: 0 {\n Version: 101\n Name: \"uv\"\n MappingInformationType: \"ByVertice\"\n"
      " ReferenceInformationType: \"IndexToDirect\"\n UV: *2 {\n a: 0,0\n }\n UVIndex: *6 {\n a: "
      "0,0,0,0,0,0\n }\n}";
  const std::string layered = fbx.substr(0, polygons) + uv + fbx.substr(polygonsEnd);
  const phys::Clip leg = clips::parseClip(fbx, "leg.fbx", "fbx");
  expectSameClip(clips::parseClip(layered, "layered.fbx", "fbx"), leg, "layered.fbx");
  // assimp ends a key at its colon: "Geometry:1," is a Geometry as "Geometry: 1," is.
  ASSERT_TRUE(has(layered, "\tGeometry: "));
  expectSameClip(clips::parseClip(replaced(layered, "\tGeometry: ", "\tGeometry:"), "tight.fbx", "fbx"), leg,
                 "tight.fbx");

  const std::string dae = legFile(dir, "collada", "dae");
  const std::string instance = "<instance_geometry url=\"#";
  ASSERT_TRUE(has(dae, instance) && has(dae, "</instance_geometry>"));
  const std::string skin =
      R"(<library_controllers><controller id="skin"><skin source="#mesh_0">)"
      R"(<source id="j"><Name_array id="j-a" count="1">hips</Name_array><technique_common>)"
      R"(<accessor source="#j-a" count="1"><param name="JOINT" type="name"/></accessor></technique_common></source>)"
      R"(<source id="w"><float_array id="w-a" count="1">1</float_array><technique_common>)"
      R"(<accessor source="#w-a" count="1"><param name="WEIGHT" type="float"/></accessor></technique_common></source>)"
      R"(<joints><input semantic="JOINT" source="#j"/></joints><vertex_weights count="3">)"
      R"(<input semantic="JOINT" source="#j" offset="0"/><input semantic="WEIGHT" source="#w" offset="1"/>)"
      R"(<vcount>1 1 1</vcount><v>50000000 0 0 0 0 0</v></vertex_weights></skin></controller>)"
      R"(</library_controllers>)";
  std::string skinned = replaced(dae, "<library_visual_scenes>", skin + "<library_visual_scenes>");
  skinned =
      replaced(skinned, instance,
               "<instance_controller "
               "url=\"#skin\"><skeleton>#hips</skeleton></instance_controller><instance_geometry url=\"#");
  expectSameClip(clips::parseClip(skinned, "skinned.dae", "dae"), clips::parseClip(dae, "leg.dae", "dae"),
                 "skinned.dae");
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
// truncated file, and COLLADA keys that are not finite, out of time order or at one time.
TEST(ClipFormats, WhatAssimpRefusesOrReadsIsRefusedWithTheReason) {
  const testing_app::TempFolder dir;
  for (const auto& [format, extension] : {std::pair{"fbxa", "fbx"}, {"collada", "dae"}, {"glb2", "glb"}}) {
    const std::string whole = legFile(dir, format, extension);
    EXPECT_EQ(refusal(whole, std::string("leg.") + extension), "loaded") << format;
    const std::string cut = refusal(whole.substr(0, whole.size() / 2), std::string("cut.") + extension);
    // A .glb says its length in its header, which is checked before assimp reads it.
    const std::string why =
        format == std::string("glb2") ? "its header says the file has " : "not a clip assimp can read: ";
    EXPECT_TRUE(has(cut, why)) << cut;
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
}

// A .x that gives no AnimTicksPerSecond runs at DirectX's 4800 ticks a second, as D3DX and the
// exporters take it; assimp gives 0, and the clip played at 25 (keys a tick apart at 0.04 s).
TEST(ClipFormats, AnXFileOfNoTickRateRunsAtDirectXsDefault) {
  const std::string x = xFile();
  ASSERT_TRUE(has(x, "\nAnimTicksPerSecond { 30; }\n"));
  const testing_app::TempFolder dir;
  std::ofstream(dir.path / "default.x") << replaced(x, "AnimTicksPerSecond { 30; }\n", "");
  const phys::Clip clip = clips::loadClip(dir.path / "default.x");
  EXPECT_DOUBLE_EQ(clip.frameTime, 1.0 / 4800.0);
  std::ofstream(dir.path / "stated.x") << x;
  EXPECT_DOUBLE_EQ(clips::loadClip(dir.path / "stated.x").frameTime, 1.0 / 30.0);
}

// assimp reads a .x file's AnimTicksPerSecond of 0 as no rate given (the clip then plays at
// DirectX's 4800 ticks a second), and wraps a negative one to more than 4 billion.
TEST(ClipFormats, AnXTickRateThatIsNotAWholeNumberAboveZeroIsRefusedWithTheLine) {
  const std::string x = xFile();
  ASSERT_TRUE(has(x, "\nAnimTicksPerSecond { 30; }\n"));
  for (const std::string rate : {"0", "-30", "4294967296", "2.5"}) {
    const std::string ticks =
        replaced(x, "AnimTicksPerSecond { 30; }", "AnimTicksPerSecond {\n " + rate + "; }");
    EXPECT_EQ(refusal(ticks, "ticks.x"),
              "ticks.x:3: AnimTicksPerSecond " + rate +
                  ": the ticks a second are not a whole number from 1 to 4294967295");
  }
  const std::string named = replaced(x, "AnimTicksPerSecond { 30; }", "AnimTicksPerSecond rate { 0; }");
  EXPECT_TRUE(has(refusal(named, "named.x"), "named.x:2: AnimTicksPerSecond 0: "))
      << refusal(named, "named.x");
  EXPECT_EQ(refusal(replaced(x, "AnimTicksPerSecond { 30; }", "AnimTicksPerSecond { 4800; }"), "fast.x"),
            "loaded");
}

// assimp's binary .x reader takes counts on trust as its text reader does, and a compressed .x is
// inflated before anything could check it: only .x as text is read.
TEST(ClipFormats, BinaryAndCompressedXFilesAreRefused) {
  const std::string body = xFile().substr(16);
  EXPECT_EQ(refusal("xof 0303bin 0032" + body, "bin.x"),
            "bin.x:1: a binary .x file ('xof 0303bin '): clips are read from .x files as text "
            "('xof 0303txt 0032') alone");
  EXPECT_TRUE(has(refusal("xof 0303bzip0032" + body, "bzip.x"), "bzip.x:1: a compressed binary .x file"));
  EXPECT_TRUE(has(refusal("xof 0303tzip0032" + body, "tzip.x"), "tzip.x:1: a compressed .x file"));
}

// assimp 5.2 drops an FBX curve whose key times do not rise, with a warning no caller sees: a file
// of such curves read as one that "holds no animation". Refused naming the curve, its property and
// its node.
TEST(ClipFormats, FbxKeysOutOfTimeOrderAreRefusedNamingTheCurve) {
  const testing_app::TempFolder dir;
  const std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::size_t array = fbx.find("a: ", fbx.find("KeyTime: *3"));
  const std::size_t end = fbx.find('\n', array);
  const std::string times = fbx.substr(array, end - array);  // a: t0,t1,t2
  const std::size_t comma = times.find(',');
  const std::size_t second = times.find(',', comma + 1);
  const std::string t0 = times.substr(3, comma - 3), t1 = times.substr(comma + 1, second - comma - 1);
  const std::string swapped = "a: " + t1 + "," + t0 + times.substr(second);
  const std::string e = refusal(replaced(fbx, times, swapped), "order.fbx");
  const std::size_t line = 1 + std::count(fbx.begin(), fbx.begin() + fbx.find("KeyTime: *3"), '\n');
  EXPECT_TRUE(has(e, "order.fbx:" + std::to_string(line) + ": KeyTime: key 1 at " + t0 +
                         " is not after key 0 at " + t1 + ": the keys of the curve d|"))
      << e;
  EXPECT_TRUE(has(e, " of node 'hips' are out of time order")) << e;
  // Two keys at one time are out of order too (assimp drops the curve as well).
  EXPECT_TRUE(has(refusal(replaced(fbx, times, "a: " + t0 + "," + t0 + times.substr(second)), "same.fbx"),
                  ": KeyTime: key 1 at " + t0 + " is not after key 0 at " + t0));
}

// ---- binary FBX, written byte by byte ----

std::string littleEndian(std::uint64_t value, int bytes) {
  std::string out;
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xff);
  return out;
}

// Properties: a 64-bit integer, a string, an array of 64-bit integers (as they are, or as a zlib
// stream of one stored deflate block), an array of any type with what its header says.
std::string longProperty(std::int64_t value) {
  return "L" + littleEndian(static_cast<std::uint64_t>(value), 8);
}
std::string stringProperty(const std::string& text) {
  return "S" + littleEndian(text.size(), 4) + text;
}
std::string arrayProperty(char type, std::uint64_t count, std::uint64_t encoding, const std::string& stored) {
  return type + littleEndian(count, 4) + littleEndian(encoding, 4) + littleEndian(stored.size(), 4) + stored;
}
std::string longsProperty(const std::vector<std::int64_t>& values, bool compressed) {
  std::string plain;
  for (const std::int64_t v : values) plain += littleEndian(static_cast<std::uint64_t>(v), 8);
  if (!compressed) return arrayProperty('l', values.size(), 0, plain);
  std::uint32_t a = 1, b = 0;  // Adler-32 (RFC 1950)
  for (const char c : plain) {
    a = (a + static_cast<unsigned char>(c)) % 65521;
    b = (b + a) % 65521;
  }
  const std::uint32_t adler = b << 16 | a;
  std::string stream =
      "\x78\x01\x01" + littleEndian(plain.size(), 2) + littleEndian(~plain.size() & 0xffff, 2) + plain;
  for (int i = 3; i >= 0; --i) stream += static_cast<char>((adler >> (8 * i)) & 0xff);
  return arrayProperty('l', values.size(), 1, stream);
}

// A node record of version 7500 (8-byte words): its properties already written, `count` of them.
struct FbxRecord {
  std::string name;
  std::string properties;
  std::uint64_t count = 0;
  std::vector<FbxRecord> children;
};

std::string recordAt(const FbxRecord& r, std::uint64_t at) {
  const std::uint64_t headerSize = 25 + r.name.size();
  std::string children;
  for (const FbxRecord& child : r.children)
    children += recordAt(child, at + headerSize + r.properties.size() + children.size());
  if (!r.children.empty()) children += std::string(25, '\0');
  const std::uint64_t end = at + headerSize + r.properties.size() + children.size();
  return littleEndian(end, 8) + littleEndian(r.count, 8) + littleEndian(r.properties.size(), 8) +
         static_cast<char>(r.name.size()) + r.name + r.properties + children;
}

std::string binaryFbx(const std::vector<FbxRecord>& records) {
  std::string out = std::string("Kaydara FBX Binary  ") + '\0' + '\x1a' + '\0' + littleEndian(7500, 4);
  for (const FbxRecord& r : records) out += recordAt(r, out.size());
  return out + std::string(25, '\0');
}

// A curve of `times` under Objects, moving "d|X" of "Lcl Rotation" of the model 'knee'.
std::string binaryFbxCurve(const std::vector<std::int64_t>& times, bool compressed) {
  const FbxRecord model{
      "Model",
      longProperty(10) + stringProperty(std::string("knee\0\1Model", 11)) + stringProperty("LimbNode"),
      3,
      {}};
  const FbxRecord curveNode{
      "AnimationCurveNode",
      longProperty(20) + stringProperty(std::string("R\0\1AnimCurveNode", 16)) + stringProperty(""),
      3,
      {}};
  const FbxRecord keyTime{"KeyTime", longsProperty(times, compressed), 1, {}};
  const FbxRecord curve{
      "AnimationCurve",
      longProperty(30) + stringProperty(std::string("\0\1AnimCurve", 11)) + stringProperty(""),
      3,
      {keyTime}};
  const auto link = [](std::int64_t from, std::int64_t to, const std::string& property) {
    return FbxRecord{
        "C", stringProperty("OP") + longProperty(from) + longProperty(to) + stringProperty(property), 4, {}};
  };
  return binaryFbx({{"Objects", "", 0, {model, curveNode, curve}},
                    {"Connections", "", 0, {link(30, 20, "d|X"), link(20, 10, "Lcl Rotation")}}});
}

TEST(ClipFormats, BinaryFbxKeysOutOfTimeOrderAreRefusedNamingTheCurve) {
  for (const bool compressed : {false, true}) {
    const std::string inOrder = refusal(binaryFbxCurve({0, 100, 200}, compressed), "order.fbx");
    EXPECT_FALSE(has(inOrder, "KeyTime")) << inOrder;
    const std::string e = refusal(binaryFbxCurve({0, 200, 100}, compressed), "order.fbx");
    EXPECT_TRUE(has(e, "order.fbx: node record 'KeyTime' at byte ")) << e;
    EXPECT_TRUE(has(e,
                    ": KeyTime: key 2 at 100 is not after key 1 at 200: the keys of the curve d|X of Lcl "
                    "Rotation of node 'knee' are out of time order"))
        << e;
  }
}

// assimp 5.2 copies each model property it does not read into the node's metadata and aborts the
// program (an assert) on one of a type it has no metadata for, KTime or ColorAndAlpha: the fuzzer
// found it. Refused naming the property, at its line in text and its byte in binary; the same
// properties elsewhere (the global settings' KTime) still load.
TEST(ClipFormats, AnFbxModelPropertyAssimpCannotKeepIsRefused) {
  const testing_app::TempFolder dir;
  const std::string fbx = legFile(dir, "fbxa", "fbx");
  const std::size_t model = fbx.find("\"Model::");
  ASSERT_NE(model, std::string::npos);
  const std::size_t table = fbx.find("Properties70:  {\n", model);
  ASSERT_NE(table, std::string::npos);
  const std::size_t at = table + std::string("Properties70:  {\n").size();
  const std::size_t line = static_cast<std::size_t>(std::count(fbx.begin(), fbx.begin() + at, '\n')) + 1;
  for (const std::string type : {"KTime", "ColorAndAlpha"}) {
    std::string bad = fbx;
    bad.insert(at, "\t\t\tP: \"Odd\", \"" + type + "\", \"\", \"\", 0, 0, 0, 0\n");
    const std::string e = refusal(bad, "odd.fbx");
    EXPECT_TRUE(has(e, "odd.fbx:" + std::to_string(line) + ": the model property \"Odd\" of type " + type +
                           ": assimp 5.2 stops the program"))
        << e;
  }
  EXPECT_TRUE(has(fbx, "\"KTime\"")) << "the file has KTime properties outside its models";
  EXPECT_EQ(refusal(fbx, "leg.fbx"), "loaded");

  const FbxRecord property{"P",
                           stringProperty("Odd") + stringProperty("KTime") + stringProperty("Time") +
                               stringProperty("") + longProperty(0),
                           5,
                           {}};
  const FbxRecord binaryModel{
      "Model",
      longProperty(10) + stringProperty(std::string("knee\0\1Model", 11)) + stringProperty("LimbNode"),
      3,
      {{"Properties70", "", 0, {property}}}};
  const std::string e = refusal(binaryFbx({{"Objects", "", 0, {binaryModel}}}), "odd.fbx");
  EXPECT_TRUE(has(e, "odd.fbx: node record 'P' at byte ")) << e;
  EXPECT_TRUE(has(e, ": the model property \"Odd\" of type KTime")) << e;
}

// assimp converts an FBX model under each model it is linked to, recursing once a level: a model
// linked under a model below it overflowed the stack, and models each linked twice under the next
// unfold to millions. Refused at the link, with its line in text and its byte in binary.
TEST(ClipFormats, FbxModelsThatNestWithoutEndAreRefusedAtTheLink) {
  const auto textFbx = [](const std::vector<std::string>& models, const std::string& links) {
    std::string fbx = "Objects:  {\n";
    for (std::size_t i = 0; i < models.size(); ++i)
      fbx += "\tModel: " + std::to_string(i + 1) + ", \"Model::" + models[i] + "\", \"Null\" {\n\t}\n";
    return fbx + "}\nConnections:  {\n" + links + "}\n";
  };
  // Lines 1 to 6 are the objects, 7 opens the connections.
  EXPECT_EQ(refusal(textFbx({"hips", "knee"}, "\tC: \"OO\", 1, 0\n\tC: \"OO\", 2, 1\n\tC: \"OO\", 1, 2\n"),
                    "cycle.fbx"),
            "cycle.fbx:10: model 1 'hips' is linked under model 2 'knee', which is under it: the models "
            "would nest without end");
  std::vector<std::string> names;
  std::string doubled = "\tC: \"OO\", 1, 0\n";
  for (int i = 1; i <= 20; ++i) {
    names.push_back("m" + std::to_string(i));
    if (i < 20)
      doubled += repeated("\tC: \"OO\", " + std::to_string(i + 1) + ", " + std::to_string(i) + "\n", 2);
  }
  // Model k unfolds to 2^(21 - k) - 1 nodes: model 4 is the first past 100,000, linked under 3 on
  // line 49, after 2 x 20 lines of objects, 3 of braces, 1 of model 1's link, 4 of models 2 and 3's.
  EXPECT_EQ(
      refusal(textFbx(names, doubled), "twice.fbx"),
      "twice.fbx:49: model 4 'm4' unfolds, a copy under each model it is linked to, to more than 100000 "
      "nodes (a skeleton has tens)");
  // A chain of 300 models nests 300 deep, which assimp and the clip's bones recurse through: model
  // 300 - 257 = 43 is the first with more than 256 below it, linked on line 2 x 300 + 3 + 43.
  std::vector<std::string> chainNames;
  std::string chain = "\tC: \"OO\", 1, 0\n";
  for (int i = 1; i <= 300; ++i) {
    chainNames.push_back("c" + std::to_string(i));
    if (i < 300) chain += "\tC: \"OO\", " + std::to_string(i + 1) + ", " + std::to_string(i) + "\n";
  }
  EXPECT_EQ(refusal(textFbx(chainNames, chain), "chain.fbx"),
            "chain.fbx:646: model 43 'c43' has models linked 257 deep under it: more than 256 (a skeleton's "
            "are tens deep)");
  // A model linked under two others is a copy under each, no cycle.
  EXPECT_FALSE(has(refusal(textFbx({"hips", "knee", "foot"},
                                   "\tC: \"OO\", 1, 0\n\tC: \"OO\", 2, 1\n"
                                   "\tC: \"OO\", 3, 1\n\tC: \"OO\", 3, 2\n"),
                           "shared.fbx"),
                   "linked under"));

  const auto model = [](std::int64_t id, const std::string& name) {
    return FbxRecord{
        "Model",
        longProperty(id) + stringProperty(name + std::string("\0\1Model", 7)) + stringProperty("Null"),
        3,
        {}};
  };
  const auto link = [](std::int64_t from, std::int64_t to) {
    return FbxRecord{"C", stringProperty("OO") + longProperty(from) + longProperty(to), 3, {}};
  };
  const std::string binary = binaryFbx({{"Objects", "", 0, {model(1, "hips"), model(2, "knee")}},
                                        {"Connections", "", 0, {link(1, 0), link(2, 1), link(1, 2)}}});
  const std::string e = refusal(binary, "cycle.fbx");
  EXPECT_TRUE(has(e, "cycle.fbx: node record 'C' at byte ")) << e;
  EXPECT_TRUE(has(e, ": model 1 'hips' is linked under model 2 'knee', which is under it")) << e;
}

// assimp's binary FBX reader recurses once a level of node records, computes an array's size in 32
// bits and reads its count of values out of what that size allocated, and takes a count of
// properties on trust: each refused, naming the record and its byte, before assimp reads the file.
TEST(ClipFormats, BinaryFbxRecordsAreCheckedBeforeAssimpReadsThem) {
  FbxRecord deep{"Deep", "", 0, {}};
  for (int level = 0; level < 300; ++level) deep = FbxRecord{"Deep", "", 0, {deep}};
  const std::string nested = refusal(binaryFbx({deep}), "deep.fbx");
  EXPECT_TRUE(has(nested, "deep.fbx: node record 'Deep' at byte ")) << nested;
  EXPECT_TRUE(has(nested, ": node records nested more than 256 deep")) << nested;
  FbxRecord shallow{"Deep", "", 0, {}};
  for (int level = 0; level < 200; ++level) shallow = FbxRecord{"Deep", "", 0, {shallow}};
  EXPECT_FALSE(has(refusal(binaryFbx({shallow}), "shallow.fbx"), "node record")) << "200 deep is a file";

  const std::string one = binaryFbx({{"Objects", "", 0, {}}});
  std::string past = one;
  past.replace(27, 8, littleEndian(one.size() + 100, 8));
  EXPECT_EQ(refusal(past, "past.fbx"), "past.fbx: node record 'Objects' at byte 27: it ends at byte " +
                                           std::to_string(one.size() + 100) +
                                           ", outside the file (bytes 59 to " + std::to_string(one.size()) +
                                           ")");

  const auto withProperty = [](const std::string& property, std::uint64_t count = 1) {
    return binaryFbx({{"Objects", "", 0, {{"Data", property, count, {}}}}});
  };
  std::string longList = withProperty(longProperty(1));
  longList.replace(59 + 16, 8, littleEndian(1000, 8));  // Data's property list length
  EXPECT_TRUE(has(refusal(longList, "list.fbx"),
                  "list.fbx: node record 'Data' at byte 59: its properties' 1000 "
                  "bytes run past its end at byte "));
  EXPECT_EQ(refusal(withProperty(longProperty(1), 1000), "count.fbx"),
            "count.fbx: node record 'Data' at byte 59: 1000 properties in 9 bytes");
  const std::string wraps =
      refusal(withProperty(arrayProperty('l', 0x20000001, 0, std::string(8, '\0'))), "wraps.fbx");
  EXPECT_TRUE(has(wraps,
                  "node record 'Data' at byte 59: an array of 536870913 values of 8 bytes in 8 bytes: 1 GB "
                  "or more"))
      << wraps;
  EXPECT_TRUE(has(refusal(withProperty(arrayProperty('d', 1000, 0, std::string(8, '\0'))), "short.fbx"),
                  "an array of 1000 values of 8 bytes in 8 bytes, stored as they are"));
  EXPECT_TRUE(has(refusal(withProperty(arrayProperty('f', 10000000, 1, std::string(8, '\0'))), "bomb.fbx"),
                  "an array of 10000000 values of 4 bytes in 8 bytes, more than they inflate to"));
  EXPECT_FALSE(
      has(refusal(withProperty(arrayProperty('f', 2, 0, std::string(8, '\0'))), "fine.fbx"), "node record"));
  // Arrays each within bounds that come to more than 256 MB together: assimp inflates and keeps them
  // all. Three of 96 MB (in 93,100 bytes each, within deflate's 1032 to 1).
  const std::string big = arrayProperty('d', 12'000'000, 1, std::string(93'100, '\0'));
  const std::string many = refusal(withProperty(big + big + big, 3), "many.fbx");
  EXPECT_TRUE(has(many,
                  "many.fbx: node record 'Data' at byte 59: an array of 12000000 values of 8 bytes in 93100 "
                  "bytes: the file's arrays come to 288000000 bytes, more than 256 MB"))
      << many;
  EXPECT_FALSE(has(refusal(withProperty(big + big, 2), "two.fbx"), "node record")) << "192 MB is a file";
}

// Nodes looked up among all the channels, once a node, took seconds for 20,000: a clip of 20,000
// bones, each keyed at two frames, loads with every bone under its parent.
TEST(ClipFormats, AClipOfTwentyThousandChannelsLoads) {
  constexpr int kBones = 20000;
  const std::string identity = "1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0";
  std::string x = "xof 0303txt 0032\nAnimTicksPerSecond { 30; }\nFrame root {\n FrameTransformMatrix { " +
                  identity + ";; }\n";
  for (int b = 1; b < kBones; ++b)
    x += " Frame b" + std::to_string(b) + " { FrameTransformMatrix { " + identity + ";; } }\n";
  x += "}\nAnimationSet all {\n";
  for (int b = 0; b < kBones; ++b) {
    x += " Animation { {" + (b == 0 ? std::string("root") : "b" + std::to_string(b)) +
         "} AnimationKey { 4; 2; 0; 16; " + identity + ";;, 1; 16; " + identity + ";;; } }\n";
  }
  x += "}\n";
  const phys::Clip clip = clips::parseClip(x, "many.x", "x");
  ASSERT_EQ(clip.bones.size(), static_cast<std::size_t>(kBones));
  EXPECT_EQ(clip.bones[0], "root");
  EXPECT_EQ(clip.bones[kBones - 1], "b" + std::to_string(kBones - 1));
  EXPECT_EQ(std::count(clip.parents.begin(), clip.parents.end(), 0), kBones - 1);
  EXPECT_EQ(clip.frames(), 2u);
}

}  // namespace
