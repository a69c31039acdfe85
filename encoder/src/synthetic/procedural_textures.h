// The synthetic scene's procedural textures. They carry fine detail on purpose (tile grout,
// pin stripes, glyph rows, brick mortar, wood grain, speckle noise) so that a Gaussian model
// of the scene needs many small Gaussians, as real captures do. Each is a pure function of
// the seed; sizes are powers of two so GL can build mipmaps.
#ifndef M4D_ENCODER_SYNTHETIC_PROCEDURAL_TEXTURES_H_
#define M4D_ENCODER_SYNTHETIC_PROCEDURAL_TEXTURES_H_

#include <cstdint>

#include "encoder/src/synthetic/scene_texture.h"

namespace m4d {

// Repeating, one period per metre where the meshes use metric texture coordinates.
SceneTexture FloorTilesTexture(uint64_t seed);  // 4 x 4 ceramic tiles with grout
SceneTexture WallpaperTexture(uint64_t seed);   // fine vertical stripes over a mottled base
SceneTexture BrickTexture(uint64_t seed);       // offset bricks with mortar lines
SceneTexture CeilingTexture(uint64_t seed);     // plaster with panel joints
SceneTexture WoodTexture(uint64_t seed);        // grain along u
SceneTexture PlaidTexture(uint64_t seed);       // the figure's shirt
SceneTexture DenimTexture(uint64_t seed);       // the figure's trousers: diagonal twill
SceneTexture MetalTexture(uint64_t seed);       // brushed metal for the lamp

// Mapped once over a surface ([0, 1] texture coordinates).
SceneTexture PosterTexture(uint64_t seed);         // text-like glyph rows under a title
SceneTexture RugTexture(uint64_t seed);            // border bands and a diamond lattice
SceneTexture BookSpinesTexture(uint64_t seed);     // 16 spine columns; a book maps one column
SceneTexture SkinTexture(uint64_t seed);           // the figure's head: skin, hair, eyes
SceneTexture PatternedCubeTexture(uint64_t seed);  // the rotating cube's faces
SceneTexture BeachBallTexture(uint64_t seed);      // the emergent ball: coloured gores
SceneTexture LampShadeTexture(uint64_t seed);      // fine vertical ribs
SceneTexture LeavesTexture(uint64_t seed);         // the swaying plant: overlapping leaves

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_PROCEDURAL_TEXTURES_H_
