// The swaying plant of the realistic synthetic scene (CaptureRealism::background_sway): a
// pot in the back-left corner of the room, and a bush of leaves on a stem that sways on it
// like a plant in a draught, so that a little of the background moves a few centimetres.
#ifndef M4D_ENCODER_SYNTHETIC_SWAYING_PLANT_H_
#define M4D_ENCODER_SYNTHETIC_SWAYING_PLANT_H_

#include <glm/mat4x4.hpp>

#include "encoder/src/synthetic/triangle_mesh.h"

namespace m4d {

// The pot, in world coordinates.
TriangleMesh PlantPotMesh();

// The stem and leaves in their own frame, rooted at the origin (the pot's rim) and up +y.
TriangleMesh PlantFoliageMesh();

// The foliage's frame at `frame`: on the pot's rim, tilted so that its top moves `sway`
// metres at most from where it stands.
glm::mat4 PlantFoliagePose(float sway, int frame);

}  // namespace m4d

#endif  // M4D_ENCODER_SYNTHETIC_SWAYING_PLANT_H_
