// The rotations that turn a stream's world so that its up axis (M4dUpAxis, spec 4.1) is where
// another format wants it: -y for 3DGS PLY (the reference tools read PLY with y down) and +y
// for glTF. They are signed permutations: exact in float, handedness kept.
#ifndef M4D_ENCODER_EXPORT_AXIS_ROTATION_H_
#define M4D_ENCODER_EXPORT_AXIS_ROTATION_H_

namespace m4d {

// A rotation as a row-major 3x3 matrix: world' = m * world.
struct AxisRotation {
  float m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  bool is_identity() const;
};

// The unit vector of an up_axis code 1..6 (+x, -x, +y, -y, +z, -z).
void UpAxisVector(int up_axis, float v[3]);

// The rotation taking axis `from` to axis `to` (codes 1..6): the identity when they are equal,
// 90 degrees about from x to when perpendicular, and when opposite 180 degrees about the next
// axis in x, y, z order (for y: about z, the turn PlayCanvas's splat-transform gives PLY).
AxisRotation RotationBetweenAxes(int from, int to);

// The stream's world as 3DGS PLY holds it: up_axis made -y. Up not stated (0) is taken as -y,
// the OpenCV convention most captures keep, so nothing turns.
AxisRotation PlyFrame(int up_axis);

// The stream's world as glTF holds it: up_axis made +y. This is PlyFrame followed by the
// 180 degrees about z with which splat-transform turns a PLY into glTF, so that our PLY
// converted by that tool and our GLB agree.
AxisRotation GltfFrame(int up_axis);

// r * s.
AxisRotation Compose(const AxisRotation& r, const AxisRotation& s);

}  // namespace m4d

#endif  // M4D_ENCODER_EXPORT_AXIS_ROTATION_H_
