// SceneContent: everything the synthetic scene is made of: its textures and its objects, each
// a mesh in its own frame with a texture and a kind of motion. The room and its furniture
// are static (meshes in world coordinates); the figure's parts, the rotating cube and the
// emergent ball move or appear (see scene_animation.h).
#ifndef M4D_ENCODER_SYNTHETIC_SCENE_CONTENT_H_
#define M4D_ENCODER_SYNTHETIC_SCENE_CONTENT_H_

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/src/synthetic/scene_texture.h"
#include "encoder/src/synthetic/triangle_mesh.h"

namespace m4d {

enum class ObjectMotion {
  kStatic,      // part of the room; mesh in world coordinates
  kFigurePart,  // a part of the articulated figure; figure_part says which
  kRotating,    // the cube spinning on the table
  kEmergent,    // the ball that appears at the emergent frame and then stays put
  kSwaying,     // the plant's leaves, swaying slightly (realistic scene only)
};

struct SceneObject {
  std::string name;
  TriangleMesh mesh;
  int texture = 0;        // index into SceneContent::textures
  float emissive = 0.0f;  // 0: lit; towards 1: glows with the lamp's colour (the shade)
  ObjectMotion motion = ObjectMotion::kStatic;
  int figure_part = -1;
};

struct SceneContent {
  std::vector<SceneTexture> textures;
  std::vector<SceneObject> objects;
};

// The room (floor, ceiling, back and side walls, a poster, a rug), its furniture (table,
// bookshelf with books, cabinet, floor lamp), the figure, the cube and the ball, and with
// `swaying_plant` a potted plant at the back (after them all, so the others keep their
// indices). The seed varies the textures' noise and the books' sizes and colours.
SceneContent BuildSceneContent(uint32_t seed, bool swaying_plant);

const char* ObjectMotionName(ObjectMotion motion);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SCENE_CONTENT_H_
