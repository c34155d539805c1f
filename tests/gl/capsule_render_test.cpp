// Capsules drawn by the sandbox's scene view, in this process, to a framebuffer of the test's
// own: one capsule lying on the ground, seen from a known camera. Its colour is at its centre and
// along its length, and where the box it is inscribed in would have its top corners there is
// ground (the same world with the body made a box puts the box's colour there): the caps are
// round. Also in the overlay's tints, in wireframe, held by a joint, and the mesh cache's bounds.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "body_colors.h"
#include "draw_options.h"
#include "engine/camera.h"
#include "engine/capsule_mesh_cache.h"
#include "engine/error.h"
#include "engine/image.h"
#include "engine/renderer.h"
#include "fileio/files.h"
#include "gl_context.h"
#include "sandbox_run.h"
#include "scene_view.h"

namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 640, kHeight = 480;
constexpr double kRadius = 0.25, kHalfSegment = 0.5;  // unit: m; 1.5 m from cap to cap

// A colour and depth target of the test's own, so the hidden window's size does not matter.
class Target {
 public:
  Target() {
    glGenTextures(1, &color_);
    glBindTexture(GL_TEXTURE_2D, color_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kWidth, kHeight, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  }
  ~Target() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteTextures(1, &color_);
  }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;
  bool complete() const { return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE; }

 private:
  unsigned fbo_ = 0, color_ = 0, depth_ = 0;
};

// The body lies along x, resting on the ground at the origin: its core from (-h, r, 0) to (h, r, 0).
phys::BodyDesc lyingBody(phys::Shape shape) {
  phys::BodyDesc d;
  d.shape = shape;
  d.size = phys::Vec3(2.0 * kRadius, 2.0 * (kHalfSegment + kRadius), 2.0 * kRadius);
  d.center = phys::Vec3(0.0, kRadius, 0.0);
  // A quarter turn about z takes the body's y axis to world x.
  d.orientation = glm::angleAxis(-glm::half_pi<double>(), phys::Vec3(0.0, 0.0, 1.0));
  return d;
}

// Above and in front, looking down at the body: every part of it is in view.
const engine::FirstPersonCamera kCamera =
    engine::FirstPersonCamera::lookingAt({0.0f, 2.2f, 1.4f}, {0.0f, static_cast<float>(kRadius), 0.0f});

// The shaders' folder, once the shared GL context exists.
fs::path shaderDir() {
  testing_gl::context();
  return fs::path(DATA_DIR) / "shaders";
}

class CapsuleRender : public testing::Test {
 protected:
  CapsuleRender() : renderer_(shaderDir()), view_(renderer_, fs::path(DATA_DIR) / "assets" / "models") {}

  // One frame as the sandbox draws it (ground, bodies, lines), read back and kept as a PNG.
  engine::Image render(const phys::World& world, const std::string& png,
                       const sandbox::DrawOptions& options = {},
                       const std::optional<sandbox::Tint>& tint = std::nullopt) {
    Target target;
    EXPECT_TRUE(target.complete());
    const glm::mat4 viewProjection = kCamera.projection(float(kWidth) / float(kHeight)) * kCamera.view();
    renderer_.beginFrame({kWidth, kHeight});
    renderer_.drawGround(viewProjection, kCamera.position, {0.0f, 1.0f, 0.0f}, 0.0f);
    view_.draw(world, viewProjection, options, tint);
    glDisable(GL_DEPTH_TEST);
    renderer_.endFrame(viewProjection);
    engine::Image image = engine::readFramebuffer({kWidth, kHeight});
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    fs::create_directories(OUTPUT_DIR);
    fileio::writeAtomically(fs::path(OUTPUT_DIR) / png, engine::encodePng(image));
    return image;
  }

  glm::u8vec4 at(const engine::Image& image, const glm::vec3& world) const {
    const glm::ivec2 px = testing_gl::toPixel(image, kCamera, world);
    EXPECT_TRUE(px.x >= 0 && px.x < image.width && px.y >= 0 && px.y < image.height) << px.x << ", " << px.y;
    return image.pixel(std::clamp(px.x, 0, image.width - 1), std::clamp(px.y, 0, image.height - 1));
  }

  engine::Renderer renderer_;
  sandbox::SceneView view_;
};

bool bodyColoured(const glm::u8vec4& p) {
  return sandbox::looksLike(sandbox::kBoxColor, p.r, p.g, p.b);
}

bool isGround(const glm::u8vec4& p) {
  const engine::RenderStyle style;
  const glm::ivec3 want(glm::round(engine::shade(style.groundColor, {0, 1, 0}, style.light) * 255.0f));
  return std::abs(p.r - want.r) <= 3 && std::abs(p.g - want.g) <= 3 && std::abs(p.b - want.b) <= 3;
}

std::string describe(const glm::u8vec4& p) {
  return std::to_string(int(p.r)) + " " + std::to_string(int(p.g)) + " " + std::to_string(int(p.b));
}

// The top corners of the box the capsule is inscribed in, drawn in 5% so that a box would
// surely cover them: outside the capsule by 0.07 m (at the caps, 0.32 m from the core's ends).
std::vector<glm::vec3> boxTopCorners() {
  const float x = 0.95f * float(kHalfSegment + kRadius), y = float(kRadius) * 1.95f,
              z = 0.95f * float(kRadius);
  return {{-x, y, -z}, {x, y, -z}, {-x, y, z}, {x, y, z}};
}

// Points inside the capsule's silhouette: its centre, near both tips, the top of the cylinder.
std::vector<glm::vec3> capsulePoints() {
  const float r = float(kRadius), tip = float(kHalfSegment + kRadius);
  return {{0.0f, r, 0.0f}, {0.85f * tip, r, 0.0f}, {-0.85f * tip, r, 0.0f}, {0.4f, 1.9f * r, 0.0f}};
}

TEST_F(CapsuleRender, ACapsuleIsRoundWhereItsBoxHasCorners) {
  phys::World capsuleWorld, boxWorld;
  capsuleWorld.addBody(lyingBody(phys::Shape::Capsule));
  boxWorld.addBody(lyingBody(phys::Shape::Box));
  ASSERT_EQ(capsuleWorld.bodies()[0].shape, phys::Shape::Capsule);
  const engine::Image capsule = render(capsuleWorld, "capsule-lying.png");
  const engine::Image box = render(boxWorld, "capsule-as-box.png");

  // Not empty, not NaN (which would come out black or not at all): the body's colour fills a
  // patch of the size a 1.5 m by 0.5 m capsule has at this distance, smaller than the box's.
  const int capsulePixels = testing_gl::countPixels(capsule, 0, 0, kWidth, kHeight, [](int r, int g, int b) {
    return sandbox::looksLike(sandbox::kBoxColor, std::uint8_t(r), std::uint8_t(g), std::uint8_t(b));
  });
  const int boxPixels = testing_gl::countPixels(box, 0, 0, kWidth, kHeight, [](int r, int g, int b) {
    return sandbox::looksLike(sandbox::kBoxColor, std::uint8_t(r), std::uint8_t(g), std::uint8_t(b));
  });
  EXPECT_GT(capsulePixels, 10000);
  EXPECT_LT(capsulePixels, boxPixels);
  EXPECT_EQ(testing_gl::countPixels(capsule, 0, 0, kWidth, kHeight,
                                    [](int r, int g, int b) { return r + g + b == 0; }),
            0);

  for (const glm::vec3& p : capsulePoints()) {
    EXPECT_TRUE(bodyColoured(at(capsule, p)))
        << "capsule at " << p.x << " " << p.y << " " << p.z << ": " << describe(at(capsule, p));
  }
  for (const glm::vec3& p : boxTopCorners()) {
    EXPECT_TRUE(bodyColoured(at(box, p)))
        << "box corner " << p.x << " " << p.y << " " << p.z << ": " << describe(at(box, p));
    EXPECT_TRUE(isGround(at(capsule, p)))
        << "beside the capsule at " << p.x << " " << p.y << " " << p.z << ": " << describe(at(capsule, p));
  }
}

TEST_F(CapsuleRender, AJointedCapsuleIsStillACapsule) {
  // Ragdoll parts (bodies held by a joint) are drawn with the limb model, unless they are capsules.
  phys::World world;
  const phys::BodyId capsule = world.addBody(lyingBody(phys::Shape::Capsule));
  phys::BodyDesc other = lyingBody(phys::Shape::Capsule);
  other.center = phys::Vec3(0.0, kRadius, -3.0);
  const phys::BodyId far = world.addBody(other);
  world.addLink(world.anchor(capsule, phys::Vec3(0.0, kRadius, -1.5)),
                world.anchor(far, phys::Vec3(0.0, kRadius, -1.5)));
  const engine::Image image = render(world, "capsule-jointed.png");
  for (const glm::vec3& p : capsulePoints())
    EXPECT_TRUE(bodyColoured(at(image, p))) << describe(at(image, p));
  for (const glm::vec3& p : boxTopCorners()) EXPECT_TRUE(isGround(at(image, p))) << describe(at(image, p));
}

TEST_F(CapsuleRender, TheOverlayTintsCapsulesAndWireframeDrawsTheirEdges) {
  phys::World world;
  world.addBody(lyingBody(phys::Shape::Capsule));
  const glm::vec3 centre(0.0f, float(kRadius), 0.0f);
  // The overlay's run colours, translucent over the ground: orange shows red over blue, blue the
  // other way round, and the ground beside the capsule stays ground.
  const engine::Image orange =
      render(world, "capsule-tint-orange.png", {}, sandbox::Tint{{0.95f, 0.45f, 0.10f}});
  const engine::Image blue = render(world, "capsule-tint-blue.png", {}, sandbox::Tint{{0.15f, 0.45f, 0.95f}});
  auto redOverBlue = [](const glm::u8vec4& p) { return int(p.r) - int(p.b); };
  EXPECT_GT(redOverBlue(at(orange, centre)), 40) << describe(at(orange, centre));
  EXPECT_LT(redOverBlue(at(blue, centre)), -40) << describe(at(blue, centre));
  for (const glm::vec3& p : boxTopCorners()) {
    EXPECT_TRUE(isGround(at(orange, p))) << describe(at(orange, p));
    EXPECT_TRUE(isGround(at(blue, p))) << describe(at(blue, p));
  }

  sandbox::DrawOptions wireframe;
  wireframe.mode = sandbox::DrawMode::Wireframe;
  const engine::Image filled = render(world, "capsule-filled.png");
  const engine::Image edges = render(world, "capsule-wireframe.png", wireframe);
  auto coloured = [](const engine::Image& image) {
    return testing_gl::countPixels(image, 0, 0, kWidth, kHeight, [](int r, int g, int b) {
      return sandbox::looksLike(sandbox::kBoxColor, std::uint8_t(r), std::uint8_t(g), std::uint8_t(b));
    });
  };
  // The edges are drawn, the faces between them are not, and nothing lands beyond the caps.
  EXPECT_GT(coloured(edges), 1000);
  EXPECT_LT(coloured(edges), coloured(filled) * 3 / 4);
  for (const glm::vec3& p : boxTopCorners()) EXPECT_TRUE(isGround(at(edges, p))) << describe(at(edges, p));
}

TEST_F(CapsuleRender, OneMeshPerSizeAndTheCacheStaysBounded) {
  const std::size_t capacity = view_.capsuleMeshes().capacity();
  // Two sizes among three capsules: two meshes.
  {
    phys::World world;
    world.addBody(lyingBody(phys::Shape::Capsule));
    phys::BodyDesc d = lyingBody(phys::Shape::Capsule);
    d.center.z = -2.0;
    world.addBody(d);
    d.size = phys::Vec3(0.3, 1.0, 0.3);
    d.center.z = 2.0;
    world.addBody(d);
    world.addBody(lyingBody(phys::Shape::Box));
    render(world, "capsule-cache.png");
    EXPECT_EQ(view_.capsuleMeshes().size(), 2u);
  }
  // Scene after scene, each with capsules of new sizes: the cache never holds more than its
  // capacity, however many sizes went before.
  const glm::mat4 viewProjection = kCamera.projection(float(kWidth) / float(kHeight)) * kCamera.view();
  for (int scene = 0; scene < 3 * int(capacity); ++scene) {
    phys::World world;
    phys::BodyDesc d = lyingBody(phys::Shape::Capsule);
    d.size = phys::Vec3(0.2, 0.5 + 0.01 * scene, 0.2);
    world.addBody(d);
    view_.draw(world, viewProjection, {});
    ASSERT_LE(view_.capsuleMeshes().size(), capacity) << "scene " << scene;
  }
  // One world with more sizes than the capacity keeps them all while it is drawn.
  phys::World many;
  const int sizes = int(capacity) + 16;
  for (int i = 0; i < sizes; ++i) {
    phys::BodyDesc d = lyingBody(phys::Shape::Capsule);
    d.size = phys::Vec3(0.1 + 0.001 * i, 0.6, 0.1 + 0.001 * i);
    d.center = phys::Vec3(0.0, 0.1, -2.0 * i);
    many.addBody(d);
  }
  view_.draw(many, viewProjection, {});
  view_.draw(many, viewProjection, {});
  EXPECT_EQ(view_.capsuleMeshes().size(), std::size_t(sizes));
  // And when it is gone, the next scene's drawing frees them down to the capacity.
  phys::World one;
  one.addBody(lyingBody(phys::Shape::Capsule));
  view_.draw(one, viewProjection, {});
  EXPECT_EQ(view_.capsuleMeshes().size(), capacity);
  renderer_.lines().flush(viewProjection);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A missing model was only a line on stderr, which a user who started the sandbox from a desktop
// never sees; the view now says why, for the status line.
TEST(SceneViewModels, AMissingModelIsDrawnAsTheCubeAndSaysWhy) {
  engine::Renderer renderer(shaderDir());
  const sandbox::SceneView view(renderer, fs::path(DATA_DIR) / "no-such-models");
  EXPECT_NE(view.modelWarnings().find("box.obj"), std::string::npos) << view.modelWarnings();
  EXPECT_NE(view.modelWarnings().find("limb.obj"), std::string::npos) << view.modelWarnings();
  const sandbox::SceneView found(renderer, fs::path(DATA_DIR) / "assets" / "models");
  EXPECT_EQ(found.modelWarnings(), "");
}

TEST(CapsuleMeshCache, SharesAMeshBetweenEqualSizesAndRefusesBadOnes) {
  testing_gl::context();
  engine::CapsuleMeshCache cache(2);
  const engine::GpuMesh* a = &cache.get(0.25f, 0.5f);
  EXPECT_EQ(&cache.get(0.25f, 0.5f), a);
  EXPECT_EQ(&cache.get(0.25f + 1e-7f, 0.5f - 1e-7f), a);  // below the resolution: the same mesh
  EXPECT_NE(&cache.get(0.25f, 0.6f), a);
  EXPECT_EQ(cache.size(), 2u);
  // The same size cut more coarsely (for wireframe) is a mesh of its own.
  EXPECT_NE(&cache.get(0.25f, 0.5f, engine::CapsuleMeshCache::kCoarse), a);
  EXPECT_EQ(cache.size(), 3u);
  cache.trim();  // all three used in this round: all stay
  EXPECT_EQ(cache.size(), 3u);
  cache.get(0.25f, 0.5f);
  cache.get(0.25f, 0.6f);
  cache.trim();  // the coarse one was not: it goes
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_THROW(cache.get(0.0f, 0.5f), engine::Error);
  EXPECT_THROW(cache.get(std::nanf(""), 0.5f), engine::Error);
  EXPECT_THROW(cache.get(0.25f, -1.0f), engine::Error);
  EXPECT_EQ(cache.size(), 2u);
  // Three sizes in one round stay; after it, the one not used in the next round goes.
  cache.get(0.25f, 0.5f);
  cache.get(0.25f, 0.6f);
  cache.get(0.3f, 0.5f);
  EXPECT_EQ(cache.size(), 3u);
  cache.trim();
  EXPECT_EQ(cache.size(), 3u);
  cache.get(0.25f, 0.5f);
  cache.get(0.3f, 0.5f);
  cache.trim();
  EXPECT_EQ(cache.size(), 2u);
  cache.clear();
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
