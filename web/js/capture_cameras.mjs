// Capture cameras of a transforms.json, for the web player and the viewer adapters.

/**
 * The capture cameras of a transforms.json (nerfstudio's format, which `m4d scene` writes):
 * one per distinct camera, camera-to-world OpenGL axes turned into world-to-camera OpenCV
 * axes as the encoder's loader does. Returns [{ name, width, height, fx, fy, cx, cy,
 * rotation, translation }].
 */
export function camerasOfTransforms(json) {
  if (!json || !Array.isArray(json.frames)) throw new TypeError('camerasOfTransforms: no frames array');
  const cameras = [], seen = new Set();
  for (const f of json.frames) {
    const name = f.camera || f.file_path;
    if (seen.has(name)) continue;
    seen.add(name);
    const m = f.transform_matrix, sign = [1, -1, -1];
    const rotation = [], translation = [0, 0, 0];
    for (let r = 0; r < 3; ++r) {
      for (let c = 0; c < 3; ++c) {
        rotation.push(sign[r] * m[c][r]);
        translation[r] -= sign[r] * m[c][r] * m[c][3];
      }
    }
    const get = (key) => f[key] ?? json[key];
    cameras.push({ name, width: get('w'), height: get('h'), fx: get('fl_x'), fy: get('fl_y'), cx: get('cx'), cy: get('cy'), rotation, translation });
  }
  return cameras;
}
