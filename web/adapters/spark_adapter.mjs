// The M4D adapter for three.js with Spark (@sparkjsdev/spark): plays decoded frames
// (SplatFrames: per frame a static and a dynamic layer of Gaussians, values as coded) as two
// Spark SplatMeshes in an ordinary three.js scene, where Spark sorts them together with the
// scene's other splats and composites them with its meshes.
//
// The static layer is packed and uploaded only when the frame says it changed (staticChanged:
// the first frame, a keyframe that replaces it, a seek); the dynamic layer every frame, packed
// in place into the same PackedSplats buffer (and the same GPU texture) while its count fits.
//
// THREE and Spark are passed in (no import here), so a page chooses how to load them. Frames
// come from the worker decoder (M4dWorkerDecoder, through PlayerCore), or from a main-thread
// decoder through SplatFrameMaker (../js/splat_frame.mjs), which sets staticChanged.
//
// Coordinates: an M4D stream's world is its capture's (OpenCV cameras: x right, y down,
// z forward). The splats keep those coordinates inside `adapter.root` (a THREE.Group under
// the given parent); `upAxis` turns the root so the stream's up is three.js's +y.
// applyCaptureCamera() places a THREE.PerspectiveCamera to look through a capture camera
// (fx, fy, cx, cy in pixels; R, t world to camera), whatever the root's placement.

import { SH_C0 } from '../js/splat_frame.mjs';

// Part of this module's API since before it moved to its own module.
export { camerasOfTransforms } from '../js/capture_cameras.mjs';

/** The quaternion [w, x, y, z] normalised, the identity when it is zero or not finite. */
function unitQuaternion(w, x, y, z, out) {
  const norm = Math.hypot(w, x, y, z);
  if (!(norm > 0) || !Number.isFinite(norm)) {
    out[0] = 1; out[1] = 0; out[2] = 0; out[3] = 0;
  } else {
    out[0] = w / norm; out[1] = x / norm; out[2] = y / norm; out[3] = z / norm;
  }
  return out;
}

/** Range of a Float32Array's finite values, [min, max]; [0, 0] when it has none. */
function finiteRange(values, count) {
  let min = Infinity, max = -Infinity;
  for (let i = 0; i < count; ++i) {
    const v = values[i];
    if (v < min) min = v;
    if (v > max) max = v;
  }
  return Number.isFinite(min) && Number.isFinite(max) ? [min, max] : [0, 0];
}

/** Largest absolute value of the SH coefficients k0 <= k < k1 of every Gaussian. */
function shMaxAbs(layer, k0, k1) {
  const stride = 3 * layer.shCoefficients;
  let max = 0;
  for (let i = 0; i < layer.count; ++i) {
    for (let j = i * stride + 3 * k0, end = i * stride + 3 * k1; j < end; ++j) {
      const a = Math.abs(layer.sh[j]);
      if (a > max && Number.isFinite(a)) max = a;
    }
  }
  return max > 0 ? max : 1;
}

/** Checks a SplatLayer's array sizes; throws a clear error when they do not match its count. */
export function checkLayer(layer, name = 'layer') {
  if (!layer || typeof layer !== 'object') throw new TypeError(`${name}: not a SplatLayer`);
  const n = layer.count;
  if (!Number.isInteger(n) || n < 0) throw new RangeError(`${name}: bad count ${n}`);
  const coefficients = layer.shCoefficients;
  if (!Number.isInteger(coefficients) || coefficients < 1) throw new RangeError(`${name}: bad shCoefficients ${coefficients}`);
  const need = { positions: 3 * n, logScales: 3 * n, rotations: 4 * n, opacityLogits: n, sh: 3 * coefficients * n };
  for (const [key, length] of Object.entries(need)) {
    const a = layer[key];
    if (!(a instanceof Float32Array) || a.length < length) {
      throw new RangeError(`${name}: ${key} holds ${a?.length ?? 'no'} values, ${length} needed for ${n} Gaussians`);
    }
  }
}

/**
 * One layer as a Spark SplatMesh over a PackedSplats that is re-packed in place: the packed
 * array (and its GPU texture) is kept while the count fits, and grows geometrically otherwise.
 */
class SparkLayer {
  constructor(THREE, spark, parent, maxSh, name) {
    this.THREE = THREE;
    this.spark = spark;
    this.maxSh = maxSh;
    this.packed = new spark.PackedSplats({ maxSplats: 0 });
    this.mesh = new spark.SplatMesh({ packedSplats: this.packed });
    this.mesh.name = name;
    this.mesh.visible = false;
    this.encoding = { ...spark.defines.DEFAULT_SPLAT_ENCODING };
    this.packed.splatEncoding = this.encoding;
    this.mesh.packedSplats.splatEncoding = this.encoding;
    this.shLevels = 0;
    this.uploads = 0;
    this.reallocations = 0;
    parent.add(this.mesh);
  }

  // Packs `layer` into the PackedSplats and marks it for upload. Returns true when a buffer
  // had to be (re)allocated.
  set(layer) {
    const { spark, packed } = this;
    const n = layer.count;
    const capacityBefore = packed.packedArray ? packed.packedArray.length / 4 : 0;
    const array = packed.ensureSplats(Math.max(n, 1));
    let grew = array.length / 4 !== capacityBefore;
    // Per-layer ranges: log scales (Spark stores 8 bits over [lnScaleMin, lnScaleMax]) and SH.
    const [lnMin, lnMax] = finiteRange(layer.logScales, 3 * n);
    const enc = this.encoding;
    enc.rgbMin = 0;
    enc.rgbMax = 1;
    enc.lnScaleMin = Math.max(-30, lnMin - 1e-3);
    enc.lnScaleMax = Math.min(30, Math.max(lnMax, lnMin + 1e-2) + 1e-3);
    const levels = Math.min(this.maxSh, Math.max(0, Math.round(Math.sqrt(layer.shCoefficients)) - 1));
    if (levels >= 1) enc.sh1Max = shMaxAbs(layer, 1, 4);
    if (levels >= 2) enc.sh2Max = shMaxAbs(layer, 4, 9);
    if (levels >= 3) enc.sh3Max = shMaxAbs(layer, 9, 16);

    const { positions: p, logScales: s, rotations: r, opacityLogits: o, sh } = layer;
    const stride = 3 * layer.shCoefficients;
    const q = [1, 0, 0, 0];
    for (let i = 0; i < n; ++i) {
      unitQuaternion(r[4 * i], r[4 * i + 1], r[4 * i + 2], r[4 * i + 3], q);
      const base = i * stride;
      spark.setPackedSplat(array, i, p[3 * i], p[3 * i + 1], p[3 * i + 2],
        Math.exp(s[3 * i]), Math.exp(s[3 * i + 1]), Math.exp(s[3 * i + 2]),
        q[1], q[2], q[3], q[0],
        1 / (1 + Math.exp(-o[i])),
        0.5 + SH_C0 * sh[base], 0.5 + SH_C0 * sh[base + 1], 0.5 + SH_C0 * sh[base + 2], enc);
    }
    packed.numSplats = n;
    packed.needsUpdate = true;

    // Higher SH bands: Spark's sh1 (7 bits), sh2 (8 bits), sh3 (6 bits) arrays in `extra`,
    // each with its own texture, kept and re-filled in place like the packed array.
    const keys = ['sh1', 'sh2', 'sh3'];
    const words = [2, 4, 4];
    const ranges = [[1, 4], [4, 9], [9, 16]];
    const encoders = [spark.utils.encodeSh1Rgb, spark.utils.encodeSh2Rgb, spark.utils.encodeSh3Rgb];
    let rebuild = levels !== this.shLevels;
    for (let level = 0; level < 3; ++level) {
      const key = keys[level];
      if (level >= levels) {
        if (packed.extra[key]) this.dropShTexture(key);
        delete packed.extra[key];
        continue;
      }
      const before = packed.extra[key];
      const shArray = packed.ensureSplatsSh(level + 1, Math.max(n, 1));
      if (shArray !== before) {
        this.dropShTexture(key);
        rebuild = true;
        grew = true;
      }
      shArray.fill(0, 0, words[level] * n);  // Spark's encoders OR bits in
      const [k0, k1] = ranges[level];
      const encode = encoders[level];
      for (let i = 0; i < n; ++i) {
        const base = i * stride;
        encode(shArray, i, sh.subarray(base + 3 * k0, base + 3 * k1), enc);
      }
      const texture = packed.extra[`${key}Texture`]?.value;
      if (texture) texture.needsUpdate = true;
    }
    this.shLevels = levels;
    if (rebuild) this.mesh.updateGenerator();
    this.mesh.visible = n > 0;
    this.mesh.updateVersion();
    this.uploads++;
    if (grew) this.reallocations++;
    return grew;
  }

  dropShTexture(key) {
    const uniform = this.packed.extra[`${key}Texture`];
    if (uniform?.value?.dispose) uniform.value.dispose();
    delete this.packed.extra[`${key}Texture`];
  }

  clear() {
    this.packed.numSplats = 0;
    this.mesh.visible = false;
    this.mesh.updateVersion();
  }

  dispose() {
    this.mesh.removeFromParent();
    this.mesh.dispose();
  }
}

/**
 * SparkRenderer options that draw as M4D's own renderer does (the reference 3DGS
 * rasterizer): 0.3 px^2 added to the 2D covariance without opacity compensation
 * (preBlurAmount, not Spark's default blurAmount), splats sorted by view depth rather than
 * radially, alpha below 1/255 skipped, no level of detail. Spread into
 * `new SparkRenderer({ renderer, ...m4dSparkRendererOptions() })`.
 */
export function m4dSparkRendererOptions() {
  return { preBlurAmount: 0.3, blurAmount: 0, sortRadial: false, minAlpha: 1 / 255, maxStdDev: 3, enableLod: false };
}

/** The M4D adapter for three.js + Spark: two SplatMeshes (static, dynamic) updated per frame. */
export class M4dSparkAdapter {
  /**
   * @param {object} options { THREE, spark, parent (a THREE.Scene or Object3D), maxSh (0..3,
   *   default 3), upAxis ([x, y, z] of the stream's world that becomes three.js's +y; default
   *   none: the capture's world as is) }
   */
  constructor(options) {
    const { THREE, spark, parent } = options || {};
    if (!THREE?.Group || !spark?.SplatMesh || !spark?.PackedSplats) {
      throw new TypeError('M4dSparkAdapter needs { THREE, spark } modules (three and @sparkjsdev/spark)');
    }
    if (!parent?.isObject3D) throw new TypeError('M4dSparkAdapter needs a parent THREE.Object3D (e.g. the scene)');
    this.THREE = THREE;
    this.spark = spark;
    const maxSh = Math.max(0, Math.min(3, options.maxSh ?? 3));
    /** The group holding both layers; move it to place the stream in the scene. */
    this.root = new THREE.Group();
    this.root.name = 'm4d';
    parent.add(this.root);
    if (options.upAxis) this.setUpAxis(options.upAxis);
    this.staticLayer = new SparkLayer(THREE, spark, this.root, maxSh, 'm4d-static');
    this.dynamicLayer = new SparkLayer(THREE, spark, this.root, maxSh, 'm4d-dynamic');
    /** The last frame applied: { frameIndex, isKeyframe }, or null. */
    this.frame = null;
    this.lastUpdateMs = 0;
  }

  /** Turns the root so that the stream's up axis (world coordinates) is three.js's +y. */
  setUpAxis(up) {
    const { THREE } = this;
    const from = new THREE.Vector3(up[0], up[1], up[2]).normalize();
    this.root.quaternion.setFromUnitVectors(from, new THREE.Vector3(0, 1, 0));
    this.root.updateMatrixWorld(true);
  }

  /**
   * Shows a SplatFrame: re-packs the static layer when `staticChanged`, the dynamic layer
   * always. Returns { staticUploaded, dynamicReallocated, ms }.
   */
  update(frame) {
    if (!frame || typeof frame !== 'object') throw new TypeError('update: not a SplatFrame');
    const start = performance.now();
    let staticUploaded = false;
    if (frame.staticChanged) {
      if (frame.static) {
        checkLayer(frame.static, 'static');
        this.staticLayer.set(frame.static);
      } else {
        this.staticLayer.clear();
      }
      staticUploaded = true;
    } else if (!this.frame) {
      throw new Error('update: the first frame must carry the static layer (staticChanged)');
    }
    let dynamicReallocated = false;
    if (frame.dynamic) {
      checkLayer(frame.dynamic, 'dynamic');
      dynamicReallocated = this.dynamicLayer.set(frame.dynamic);
    } else {
      this.dynamicLayer.clear();
    }
    this.frame = { frameIndex: frame.frameIndex, isKeyframe: frame.isKeyframe };
    this.lastUpdateMs = performance.now() - start;
    return { staticUploaded, dynamicReallocated, ms: this.lastUpdateMs };
  }

  /** Counts since construction: layer uploads and buffer (re)allocations. */
  get stats() {
    return {
      staticUploads: this.staticLayer.uploads,
      dynamicUploads: this.dynamicLayer.uploads,
      staticReallocations: this.staticLayer.reallocations,
      dynamicReallocations: this.dynamicLayer.reallocations,
      staticCount: this.staticLayer.packed.numSplats,
      dynamicCount: this.dynamicLayer.packed.numSplats,
    };
  }

  /** The two SplatMeshes: { static, dynamic }. */
  get meshes() {
    return { static: this.staticLayer.mesh, dynamic: this.dynamicLayer.mesh };
  }

  /**
   * Places `camera` (a THREE.PerspectiveCamera in the scene, without a transformed parent)
   * to see what a capture camera sees: intrinsics in pixels of a width x height image,
   * world-to-camera rotation (9, row-major) and translation of the stream's world.
   */
  applyCaptureCamera(camera, capture, width, height) {
    this.root.updateMatrixWorld(true);
    applyCaptureCamera(this.THREE, camera, capture, width, height, this.root.matrixWorld);
  }

  /** Removes both layers from the scene and frees their buffers and textures. */
  dispose() {
    this.staticLayer.dispose();
    this.dynamicLayer.dispose();
    this.root.removeFromParent();
    this.frame = null;
  }
}

/**
 * Places a THREE.PerspectiveCamera as an OpenCV capture camera (x right, y down, z forward;
 * fx, fy, cx, cy in pixels of width x height, pixel centres at +0.5; `rotation` 9 values
 * row-major and `translation` 3, world to camera), with an off-centre projection for the
 * principal point. `worldMatrix` (optional THREE.Matrix4) places the capture's world in the
 * scene (the adapter's root). Near and far from capture.near (default 0.2) and capture.far
 * (default 1000).
 */
export function applyCaptureCamera(THREE, camera, capture, width, height, worldMatrix) {
  const { fx, fy, cx, cy, rotation: R, translation: t } = capture;
  if (![fx, fy, cx, cy, width, height].every(Number.isFinite) || !(fx > 0 && fy > 0 && width > 0 && height > 0) ||
      !R || R.length !== 9 || !t || t.length !== 3) {
    throw new RangeError('applyCaptureCamera: needs fx, fy > 0, cx, cy, rotation (9), translation (3) and a size');
  }
  const near = capture.near ?? 0.2, far = capture.far ?? 1000;
  // Camera to world: [R^T | -R^T t], then OpenCV's axes to three.js's (y up, looking down -z).
  const c = [0, 1, 2].map((i) => -(R[i] * t[0] + R[3 + i] * t[1] + R[6 + i] * t[2]));
  const cameraToWorld = new THREE.Matrix4().set(
    R[0], -R[3], -R[6], c[0],
    R[1], -R[4], -R[7], c[1],
    R[2], -R[5], -R[8], c[2],
    0, 0, 0, 1);
  if (worldMatrix) cameraToWorld.premultiply(worldMatrix);
  cameraToWorld.decompose(camera.position, camera.quaternion, camera.scale);
  camera.updateMatrixWorld(true);
  // x_ndc = 2 (fx X / Z + cx) / width - 1, y_ndc = 1 - 2 (fy Y / Z + cy) / height (OpenCV X, Y, Z).
  camera.near = near;
  camera.far = far;
  camera.aspect = width / height;
  camera.fov = (2 * Math.atan(0.5 * height / fy) * 180) / Math.PI;
  camera.projectionMatrix.set(
    2 * fx / width, 0, 1 - 2 * cx / width, 0,
    0, 2 * fy / height, 2 * cy / height - 1, 0,
    0, 0, -(far + near) / (far - near), -2 * far * near / (far - near),
    0, 0, -1, 0);
  camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
}

/**
 * A capture camera scaled to a width x height view and centred, as `m4d_play --capture` and
 * the web player do.
 */
export function fitCaptureCamera(c, width, height) {
  const scale = width / c.width;
  return {
    ...c,
    fx: c.fx * scale, fy: c.fy * scale,
    cx: c.cx * scale + 0.5 * (width - c.width * scale),
    cy: c.cy * scale + 0.5 * (height - c.height * scale),
    width, height,
  };
}
