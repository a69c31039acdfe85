#include "encoder/src/synthetic/scene_content.h"

#include <glm/gtc/matrix_transform.hpp>

#include "encoder/src/synthetic/articulated_figure.h"
#include "encoder/src/synthetic/mesh_shapes.h"
#include "encoder/src/synthetic/procedural_textures.h"
#include "encoder/src/synthetic/scene_random.h"
#include "encoder/src/synthetic/swaying_plant.h"

namespace m4d {
namespace {

// Texture indices, in the order BuildTextures makes them.
enum TextureId {
  kFloorTiles,
  kWallpaper,
  kBrick,
  kCeiling,
  kWood,
  kPlaid,
  kDenim,
  kMetal,
  kPoster,
  kSecondPoster,
  kRug,
  kBookSpines,
  kSkin,
  kCube,
  kBeachBall,
  kLampShade,
  kLeaves,  // made only for the swaying plant
};

std::vector<SceneTexture> BuildTextures(uint64_t seed) {
  // Each texture gets its own noise stream.
  auto s = [seed](uint64_t k) { return MixBits(seed * 131 + k); };
  return {FloorTilesTexture(s(1)), WallpaperTexture(s(2)),      BrickTexture(s(3)),
          CeilingTexture(s(4)),    WoodTexture(s(5)),           PlaidTexture(s(6)),
          DenimTexture(s(7)),      MetalTexture(s(8)),          PosterTexture(s(9)),
          PosterTexture(s(10)),    RugTexture(s(11)),           BookSpinesTexture(s(12)),
          SkinTexture(s(13)),      PatternedCubeTexture(s(14)), BeachBallTexture(s(15)),
          LampShadeTexture(s(16))};
}

UvMapping Metric(float metres_per_repeat) {
  UvMapping uv;
  uv.metres_per_repeat = metres_per_repeat;
  return uv;
}

glm::mat4 At(float x, float y, float z) {
  return glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z));
}

void AddStatic(const std::string& name, TriangleMesh mesh, int texture,
               std::vector<SceneObject>* objects) {
  SceneObject object;
  object.name = name;
  object.mesh = std::move(mesh);
  object.texture = texture;
  objects->push_back(std::move(object));
}

// The room spans x in [-2.5, 2.5], y in [0, 2.7], z in [-4, 2]; the cameras stand near
// z = 1.6 looking towards -z.
void AddRoom(std::vector<SceneObject>* objects) {
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  AddStatic("floor", QuadMesh({-2.5f, 0, 2}, 5.0f * x, -6.0f * z, Metric(1)), kFloorTiles, objects);
  AddStatic("ceiling", QuadMesh({-2.5f, 2.7f, -4}, 5.0f * x, 6.0f * z, Metric(1)), kCeiling,
            objects);
  AddStatic("back_wall", QuadMesh({-2.5f, 0, -4}, 5.0f * x, 2.7f * y, Metric(1)), kWallpaper,
            objects);
  AddStatic("left_wall", QuadMesh({-2.5f, 0, 2}, -6.0f * z, 2.7f * y, Metric(1)), kBrick, objects);
  AddStatic("right_wall", QuadMesh({2.5f, 0, -4}, 6.0f * z, 2.7f * y, Metric(1)), kBrick, objects);
  AddStatic("poster", QuadMesh({-1.7f, 1.15f, -3.99f}, 1.3f * x, 1.0f * y, UvMapping()), kPoster,
            objects);
  AddStatic("side_poster", QuadMesh({2.49f, 1.0f, -2.4f}, 1.2f * z, 0.9f * y, UvMapping()),
            kSecondPoster, objects);
  AddStatic("rug", QuadMesh({-1.4f, 0.004f, -1.0f}, 2.2f * x, -1.6f * z, UvMapping()), kRug,
            objects);
}

TriangleMesh Table() {
  TriangleMesh mesh;
  AppendMesh(BoxMesh({1.1f, 0.05f, 0.65f}, Metric(0.5f)), At(0.55f, 0.75f, -1.9f), &mesh);
  for (int i = 0; i < 4; ++i) {
    const float lx = 0.55f + ((i & 1) ? 0.5f : -0.5f), lz = -1.9f + ((i & 2) ? 0.27f : -0.27f);
    AppendMesh(BoxMesh({0.05f, 0.725f, 0.05f}, Metric(0.5f)), At(lx, 0.3625f, lz), &mesh);
  }
  return mesh;
}

// The shelf unit stands against the back wall, x in [0.5, 1.5], 1.9 m high.
TriangleMesh Bookshelf() {
  TriangleMesh mesh;
  const float depth = 0.32f, zc = -4.0f + 0.5f * depth;
  for (float side : {0.515f, 1.485f}) {
    AppendMesh(BoxMesh({0.03f, 1.9f, depth}, Metric(0.5f)), At(side, 0.95f, zc), &mesh);
  }
  AppendMesh(BoxMesh({1.0f, 1.9f, 0.02f}, Metric(0.5f)), At(1.0f, 0.95f, -3.99f), &mesh);
  for (int shelf = 0; shelf < 5; ++shelf) {
    AppendMesh(BoxMesh({0.94f, 0.03f, depth - 0.02f}, Metric(0.5f)),
               At(1.0f, 0.015f + 0.4675f * shelf, zc + 0.01f), &mesh);
  }
  return mesh;
}

// Books of random widths and heights fill the four lower shelves, with the odd gap.
TriangleMesh Books(uint64_t seed) {
  SceneRandom random(seed);
  TriangleMesh mesh;
  for (int shelf = 0; shelf < 4; ++shelf) {
    const float base = 0.03f + 0.4675f * shelf;
    for (float x = 0.54f; x < 1.42f;) {
      const float width = random.Uniform(0.025f, 0.06f);
      if (random.Uniform() < 0.08f) {
        x += width;
        continue;
      }
      const float height = random.Uniform(0.22f, 0.36f), depth = random.Uniform(0.2f, 0.26f);
      UvMapping uv;
      uv.uv_origin = glm::vec2(static_cast<float>(random.Next() % 16) / 16.0f, 0.0f);
      uv.uv_size = glm::vec2(1.0f / 16.0f, 1.0f);
      AppendMesh(BoxMesh({width, height, depth}, uv),
                 At(x + 0.5f * width, base + 0.5f * height, -3.97f + 0.5f * depth), &mesh);
      x += width + 0.003f;
    }
  }
  return mesh;
}

TriangleMesh Cabinet() {
  TriangleMesh mesh;
  AppendMesh(BoxMesh({0.45f, 0.85f, 1.3f}, Metric(0.5f)), At(-2.27f, 0.425f, -2.6f), &mesh);
  return mesh;
}

// Drawer handles on the cabinet, the lamp's base and pole, and the cube's pedestal.
TriangleMesh MetalParts() {
  TriangleMesh mesh;
  for (int drawer = 0; drawer < 3; ++drawer) {
    AppendMesh(BoxMesh({0.02f, 0.03f, 0.3f}, Metric(0.2f)),
               At(-2.035f, 0.18f + 0.26f * drawer, -2.6f), &mesh);
  }
  AppendMesh(CylinderMesh(0.16f, 0.14f, 0.03f, 24), At(1.9f, 0, -2.6f), &mesh);
  AppendMesh(CylinderMesh(0.015f, 0.015f, 1.45f, 12), At(1.9f, 0.03f, -2.6f), &mesh);
  AppendMesh(CylinderMesh(0.05f, 0.04f, 0.1f, 16), At(0.75f, 0.775f, -1.9f), &mesh);
  return mesh;
}

void AddFurniture(uint64_t seed, std::vector<SceneObject>* objects) {
  AddStatic("table", Table(), kWood, objects);
  AddStatic("bookshelf", Bookshelf(), kWood, objects);
  AddStatic("books", Books(seed), kBookSpines, objects);
  AddStatic("cabinet", Cabinet(), kWood, objects);
  AddStatic("metal_parts", MetalParts(), kMetal, objects);
  TriangleMesh shade;
  AppendMesh(CylinderMesh(0.22f, 0.14f, 0.28f, 32), At(1.9f, 1.45f, -2.6f), &shade);
  AddStatic("lamp_shade", std::move(shade), kLampShade, objects);
  objects->back().emissive = 0.85f;
}

void AddMovingObjects(std::vector<SceneObject>* objects) {
  for (int part = 0; part < kFigurePartCount; ++part) {
    SceneObject object;
    object.name = FigurePartName(part);
    object.mesh = FigurePartMesh(part);
    const FigureMaterial material = FigurePartMaterial(part);
    object.texture = material == FigureMaterial::kSkin    ? kSkin
                     : material == FigureMaterial::kShirt ? kPlaid
                                                          : kDenim;
    object.motion = ObjectMotion::kFigurePart;
    object.figure_part = part;
    objects->push_back(std::move(object));
  }
  SceneObject cube;
  cube.name = "rotating_cube";
  cube.mesh = BoxMesh(glm::vec3(0.24f), UvMapping());
  cube.texture = kCube;
  cube.motion = ObjectMotion::kRotating;
  objects->push_back(std::move(cube));
  SceneObject ball;
  ball.name = "emergent_ball";
  ball.mesh = SphereMesh(0.16f, 32, 20);
  ball.texture = kBeachBall;
  ball.motion = ObjectMotion::kEmergent;
  objects->push_back(std::move(ball));
}

void AddPlant(uint64_t seed, SceneContent* content) {
  content->textures.push_back(LeavesTexture(MixBits(seed * 131 + 17)));
  AddStatic("plant_pot", PlantPotMesh(), kWood, &content->objects);
  SceneObject foliage;
  foliage.name = "plant_foliage";
  foliage.mesh = PlantFoliageMesh();
  foliage.texture = kLeaves;
  foliage.motion = ObjectMotion::kSwaying;
  content->objects.push_back(std::move(foliage));
}

}  // namespace

SceneContent BuildSceneContent(uint32_t seed, bool swaying_plant) {
  SceneContent content;
  content.textures = BuildTextures(seed);
  AddRoom(&content.objects);
  AddFurniture(MixBits(seed * 977 + 3), &content.objects);
  AddMovingObjects(&content.objects);
  if (swaying_plant) AddPlant(seed, &content);
  return content;
}

const char* ObjectMotionName(ObjectMotion motion) {
  switch (motion) {
    case ObjectMotion::kStatic:
      return "static";
    case ObjectMotion::kFigurePart:
      return "articulated";
    case ObjectMotion::kRotating:
      return "rotating";
    case ObjectMotion::kEmergent:
      return "emergent";
    case ObjectMotion::kSwaying:
      return "swaying";
  }
  return "unknown";
}

}  // namespace m4d
