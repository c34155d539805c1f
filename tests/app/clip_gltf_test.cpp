// What assimp is given of a glTF clip (app/clips/src/gltf_skeleton_only.cpp; docs/physics.md,
// "Animation"): the nodes and the keys of their rotations, translations and scales alone, what
// those keys are read from checked to lie within what holds them. The files are those a probe of
// assimp 5.2's reader found crashing it, each a change to one small clip.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "clip_refusal.h"
#include "clips/clip_file.h"
#include "physics/animation.h"

namespace {

using Json = nlohmann::json;
using testing_clips::refusal;

constexpr double kTolerance = 1e-6;  // assimp keeps its keys in float

// The hips' turn at frame 1: 0.3 rad about x; the knee rests (and is keyed) turned 0.5 rad about z.
const double kHipsTurn = 0.3, kKneeRest = 0.5;

std::string base64(const std::string& bytes) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = static_cast<std::uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

// The clip's keys: 3 times, the hips' turns (x, y, z, w), the hips' positions, the knee's turns.
std::string keyBytes() {
  const float h = static_cast<float>(std::sin(kHipsTurn / 2)),
              hw = static_cast<float>(std::cos(kHipsTurn / 2));
  const float k = static_cast<float>(std::sin(kKneeRest / 2)),
              kw = static_cast<float>(std::cos(kKneeRest / 2));
  const std::vector<float> floats{0.0F, 0.1F, 0.2F,                                      // times
                                  0,    0,    0,    1,    h, 0, 0,    hw, 0, 0, 0, 1,    // hips' turns
                                  0,    1,    0,    0.1F, 1, 0, 0.2F, 1,  0,             // hips' positions
                                  0,    0,    k,    kw,   0, 0, k,    kw, 0, 0, k, kw};  // knee's turns
  std::string bytes(floats.size() * sizeof(float), '\0');
  std::memcpy(bytes.data(), floats.data(), bytes.size());
  return bytes;
}

// A clip of hips and knee under an armature scaled by 2 and moved 5 m along z (a matrix), the knee
// at rest turned about z: 3 frames 0.1 s apart.
Json clipDocument() {
  const std::string bytes = keyBytes();
  Json doc = Json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "armature", "children": [1], "matrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,5,1]},
              {"name": "hips", "children": [2]},
              {"name": "knee", "translation": [0, -0.4, 0], "rotation": [0, 0, 0.247403959, 0.968912422]}],
    "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                                 {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                                 {"sampler": 2, "target": {"node": 2, "path": "rotation"}}],
                    "samplers": [{"input": 0, "output": 1, "interpolation": "LINEAR"},
                                 {"input": 0, "output": 2, "interpolation": "LINEAR"},
                                 {"input": 0, "output": 3}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR"},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC4"},
                  {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC4"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12}, {"buffer": 0, "byteOffset": 12, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 60, "byteLength": 36}, {"buffer": 0, "byteOffset": 96, "byteLength": 48}],
    "buffers": [{"byteLength": 144}]})");
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bytes);
  return doc;
}

// `doc` as a .glb: the buffer of the keys its BIN chunk.
std::string glbOf(Json doc) {
  for (Json& buffer : doc["buffers"]) {
    if (buffer["uri"].get<std::string>().starts_with("data:application/octet-stream")) buffer.erase("uri");
  }
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const std::string bin = keyBytes();
  const auto word = [](std::size_t n) {
    const auto w = static_cast<std::uint32_t>(n);
    return std::string(reinterpret_cast<const char*>(&w), sizeof w);
  };
  return "glTF" + word(2) + word(12 + 8 + json.size() + 8 + bin.size()) + word(json.size()) + "JSON" + json +
         word(bin.size()) + std::string("BIN\0", 4) + bin;
}

phys::Quat aboutX(double angle) {
  return {std::cos(angle / 2), std::sin(angle / 2), 0.0, 0.0};
}

// The clip clipDocument describes, read from `content`: the knee keyed at its rest is no turn, the
// hips' positions scaled and moved by the armature.
void expectTheClip(const std::string& content, const std::string& name) {
  const std::string ext = name.substr(name.rfind('.') + 1);
  const phys::Clip clip = clips::parseClip(content, name, ext);
  ASSERT_EQ(clip.bones, (std::vector<std::string>{"hips", "knee"}));
  EXPECT_EQ(clip.parents, (std::vector<int>{-1, 0}));
  EXPECT_NEAR(clip.frameTime, 0.1, kTolerance);
  ASSERT_EQ(clip.frames(), 3U);
  for (std::size_t f = 0; f < 3; ++f) {
    const phys::Vec3 root(0.2 * static_cast<double>(f), 2.0, 5.0);
    EXPECT_NEAR(glm::length(clip.root[f] - root), 0.0, kTolerance) << name << " frame " << f;
    const phys::Quat hips = f == 1 ? aboutX(kHipsTurn) : phys::Quat(1, 0, 0, 0);
    EXPECT_NEAR(std::abs(glm::dot(clip.turns[f * 2], hips)), 1.0, kTolerance) << name << " frame " << f;
    EXPECT_NEAR(std::abs(glm::dot(clip.turns[f * 2 + 1], phys::Quat(1, 0, 0, 0))), 1.0, kTolerance) << name;
  }
}

// parseClip's message for `doc` as a .gltf named `name`.
std::string refusalOf(const Json& doc, const std::string& name) {
  return refusal(doc.dump(), name);
}

TEST(ClipGltf, AccessorsReadPastTheirBufferViewAreRefused) {
  Json offset = clipDocument();  // 3 VEC3 of 12 bytes from byte 24 of 36: assimp checked 3 x 4 bytes
  offset["accessors"][2]["byteOffset"] = 24;
  EXPECT_EQ(
      refusalOf(offset, "offset.gltf"),
      "offset.gltf: accessor 2: its 3 elements of 12 bytes, 12 apart from byte 24, end at byte 60, past the "
      "36 bytes of bufferView 2");
  Json stride = clipDocument();  // a stride smaller than an element read 12 bytes 4 apart
  stride["bufferViews"][2] = {{"buffer", 0}, {"byteOffset", 132}, {"byteLength", 12}, {"byteStride", 4}};
  EXPECT_EQ(refusalOf(stride, "stride.gltf"),
            "stride.gltf: bufferView 2: byteStride 4 is less than the 12 bytes of an element of accessor 2");
  Json wide = clipDocument();  // a stride that takes the last element past the view
  wide["bufferViews"][2]["byteStride"] = 16;
  EXPECT_EQ(
      refusalOf(wide, "wide.gltf"),
      "wide.gltf: accessor 2: its 3 elements of 12 bytes, 16 apart from byte 0, end at byte 44, past the 36 "
      "bytes of bufferView 2");
  Json view = clipDocument();
  view["bufferViews"][3]["byteLength"] = 60;
  EXPECT_EQ(refusalOf(view, "view.gltf"),
            "view.gltf: bufferView 3: bytes 96 to 156 are past the 144 bytes of buffer 0");
  Json none = clipDocument();
  none["accessors"][1].erase("bufferView");
  EXPECT_EQ(refusalOf(none, "none.gltf"),
            "none.gltf: accessor 1 has no bufferView: a clip's keys are read from a buffer");
}

TEST(ClipGltf, SparseAccessorsAreRefused) {
  // Values past their view; indices with no view; no indices; no values: all read out of bounds or
  // through a null pointer by assimp.
  for (const char* sparse : {R"({"count": 1, "indices": {"bufferView": 0, "componentType": 5125},
                                 "values": {"bufferView": 2, "byteOffset": 24}})",
                             R"({"count": 1, "indices": {}, "values": {"bufferView": 1}})",
                             R"({"count": 1, "values": {"bufferView": 1}})",
                             R"({"count": 1, "indices": {"bufferView": 0, "componentType": 5125}})"}) {
    Json doc = clipDocument();
    doc["accessors"][1]["sparse"] = Json::parse(sparse);
    EXPECT_EQ(refusalOf(doc, "sparse.gltf"),
              "sparse.gltf: accessor 1: a sparse accessor: a clip's keys are stored whole")
        << sparse;
  }
}

TEST(ClipGltf, SamplersHoldAKeyForEachTimeOrThreeForACubicSpline) {
  Json cubic = clipDocument();  // assimp read values[3i + 1] past the last of 3
  cubic["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";
  EXPECT_EQ(refusalOf(cubic, "cubic.gltf"),
            "cubic.gltf: animation 0, sampler 0: its output, accessor 1, holds 3 keys for 3 times, where "
            "CUBICSPLINE "
            "needs 9 (an in-tangent, a value and an out-tangent each)");
  Json more = clipDocument();
  more["accessors"][2]["count"] = 2;
  EXPECT_EQ(refusalOf(more, "more.gltf"),
            "more.gltf: animation 0, sampler 1: its output, accessor 2, holds 2 keys for 3 times, where "
            "LINEAR needs 3");
  Json none = clipDocument();
  none["accessors"][0]["count"] = 0;
  EXPECT_EQ(refusalOf(none, "none.gltf"),
            "none.gltf: animation 0, sampler 0: its input, accessor 0, holds no times");
  Json bytes = clipDocument();  // assimp copied one byte into each float time, the rest unset
  bytes["accessors"][0]["componentType"] = 5121;
  EXPECT_EQ(refusalOf(bytes, "bytes.gltf"),
            "bytes.gltf: animation 0, sampler 0: its input, accessor 0, holds \"SCALAR\" of componentType "
            "5121, where "
            "times are SCALAR of floats (5126)");
  Json type = clipDocument();
  type["accessors"][3]["type"] = "VEC5";
  EXPECT_EQ(refusalOf(type, "type.gltf"),
            "type.gltf: animation 0, sampler 2: its output, accessor 3, holds \"VEC5\" of componentType "
            "5126, where "
            "keys are VEC4 of floats (5126)");
}

TEST(ClipGltf, IndicesPastWhatTheyIndexAreRefused) {
  Json sampler = clipDocument();  // assimp skipped the channel, and the clip lost a bone's keys
  sampler["animations"][0]["channels"][2]["sampler"] = 7;
  EXPECT_EQ(refusalOf(sampler, "sampler.gltf"),
            "sampler.gltf: animation 0, channel 2: sampler 7 is past the animation's 3 samplers");
  Json accessor = clipDocument();
  accessor["animations"][0]["samplers"][1]["output"] = 4;
  EXPECT_EQ(refusalOf(accessor, "accessor.gltf"),
            "accessor.gltf: animation 0, sampler 1: accessor 4 is past the file's 4 accessors");
  Json node = clipDocument();  // assimp took such a channel to move its first node
  node["animations"][0]["channels"][0]["target"].erase("node");
  EXPECT_EQ(refusalOf(node, "node.gltf"), "node.gltf: animation 0, channel 0: its target names no node");
  Json negative = clipDocument();
  negative["accessors"][1]["byteOffset"] = -4;
  EXPECT_EQ(refusalOf(negative, "negative.gltf"),
            "negative.gltf: accessor 1: \"byteOffset\" is -4, not a whole number from 0 to 4294967295");
}

TEST(ClipGltf, MeshesSkinsCamerasAndWeightsAreLeftOut) {
  expectTheClip(clipDocument().dump(), "clip.gltf");
  // What the probe found: a skin with no inverse bind matrices, WEIGHTS_1 with no JOINTS_1, line
  // loops, strips and fans of too few vertices or indices past them; and a weights channel of no
  // times (a division by zero) or a cubic spline of one key a time (a stride that wrapped, 17 GB).
  Json doc = clipDocument();
  doc["nodes"][2].update(Json::parse(R"({"mesh": 0, "skin": 0, "camera": 0, "weights": [1],
                                         "extensions": {"KHR_lights_punctual": {"light": 0}}, "extras": {"a": 1}})"));
  doc["accessors"].push_back(
      Json::parse(R"({"bufferView": 0, "componentType": 5121, "count": 0, "type": "SCALAR"})"));
  // A compressed mesh's accessor (KHR_draco_mesh_compression) counts elements no buffer view holds:
  // never read, so never refused for it.
  doc["accessors"].push_back(Json::parse(R"({"componentType": 5126, "count": 4000000000, "type": "VEC3"})"));
  doc["meshes"] = Json::parse(R"([{"primitives": [
      {"attributes": {"POSITION": 2, "WEIGHTS_0": 1, "WEIGHTS_1": 1, "JOINTS_0": 0}},
      {"attributes": {"POSITION": 2}, "indices": 4, "mode": 2},
      {"attributes": {"POSITION": 4}, "mode": 3},
      {"attributes": {"POSITION": 2}, "indices": 4, "mode": 5},
      {"attributes": {"POSITION": 2}, "indices": 4, "mode": 6},
      {"attributes": {"POSITION": 99}},
      {"attributes": {"POSITION": 5}, "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0,
                                                                                  "attributes": {"POSITION": 0}}}}]}])");
  doc["skins"] = Json::parse(R"([{"joints": [1, 2]}])");
  doc["cameras"] = Json::parse(R"([{"type": "perspective", "perspective": {"yfov": -1, "znear": 0}}])");
  doc["animations"][0]["channels"].push_back(
      Json::parse(R"({"sampler": 3, "target": {"node": 2, "path": "weights"}})"));
  doc["animations"][0]["channels"].push_back(
      Json::parse(R"({"sampler": 4, "target": {"node": 2, "path": "weights"}})"));
  doc["animations"][0]["samplers"].push_back(Json::parse(R"({"input": 4, "output": 0})"));
  doc["animations"][0]["samplers"].push_back(
      Json::parse(R"({"input": 0, "output": 0, "interpolation": "CUBICSPLINE"})"));
  expectTheClip(doc.dump(), "everything.gltf");
  expectTheClip(glbOf(doc), "everything.glb");
}

TEST(ClipGltf, AGlbKeepsItsBinaryChunk) {
  expectTheClip(glbOf(clipDocument()), "clip.glb");
  Json doc = clipDocument();
  doc["buffers"][0]["byteLength"] = 148;
  EXPECT_EQ(refusal(glbOf(doc), "long.glb"),
            "long.glb: buffer 0 says it holds 148 bytes, but the BIN chunk holds 144");
  // The BIN chunk's buffer after another: assimp takes buffer 0 of a .glb to be the chunk.
  Json second = clipDocument();
  second["buffers"].insert(second["buffers"].begin(),
                           Json::parse(R"({"byteLength": 4, "uri": "data:,abcd"})"));
  for (Json& view : second["bufferViews"]) view["buffer"] = 1;
  expectTheClip(glbOf(second), "second.glb");
}

TEST(ClipGltf, JsonThatIsNotWellFormedIsRefusedWithItsLine) {
  EXPECT_EQ(refusal("{\"asset\": {\"version\": \"2.0\"},\n\"nodes\": [}", "bad.gltf"),
            "bad.gltf:2: not JSON: column 11: syntax error while parsing value - unexpected '}'; expected "
            "'[', '{', "
            "or a literal");
  std::string glb = glbOf(clipDocument());
  const std::size_t comma = glb.find(',');
  glb[comma] = ';';
  const std::string e = refusal(glb, "bad.glb");
  EXPECT_EQ(e.rfind("bad.glb: its JSON chunk, line 1: not JSON: column ", 0), 0U) << e;
}

}  // namespace
