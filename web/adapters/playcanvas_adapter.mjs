// The PlayCanvas engine adapter: shows decoded M4D frames (SplatFrames of splat_frame.mjs: the
// worker decoder's output, or SplatFrameMaker's copies of a main-thread decoder's frames) as
// two gsplat entities of a PlayCanvas app, one per layer, beside the app's other entities.
//
// PlayCanvas 2.x builds a gsplat resource from PLY-style properties (GSplatData): x, y, z;
// scale_0..2 as log scales; rot_0..3 as w, x, y, z; opacity as a logit; f_dc_0..2 and f_rest_*
// grouped by channel (all of red's higher coefficients, then green's, then blue's). Our layers
// hold the same values (sh as [k][r, g, b]), so the conversion is a transposition.
//
// The static layer's entity is rebuilt only when a frame says `staticChanged`. The dynamic
// layer's resource is kept and updated in place (its textures rewritten, its centres re-sent
// to the sorter) while its Gaussian count fits; it has spare room (padding Gaussians with zero
// opacity), and is rebuilt with 1.5 times the room when a frame has more Gaussians.
//
// Coordinates: the stream's world is the capture's (OpenCV: x right, y down, z forward); the
// entities are not transformed, and `setCaptureCamera` places a PlayCanvas camera so that it
// sees what a capture camera (fx, fy, cx, cy, world-to-camera R, t) sees.

const PAD_LOG_SCALE = -30;
const PAD_OPACITY = -30;

// The properties of a GSplatData of `count` Gaussians with SH degree `degree`.
function makeProperties(count, degree) {
  const names = ['x', 'y', 'z', 'scale_0', 'scale_1', 'scale_2', 'rot_0', 'rot_1', 'rot_2', 'rot_3',
    'opacity', 'f_dc_0', 'f_dc_1', 'f_dc_2'];
  const rest = 3 * ((degree + 1) ** 2 - 1);
  for (let i = 0; i < rest; ++i) names.push(`f_rest_${i}`);
  return names.map((name) => ({ type: 'float', name, storage: new Float32Array(count), byteSize: 4 }));
}

// Writes a layer's Gaussians into the properties (by name) of a GSplatData holding `capacity`
// Gaussians; the ones past the layer's count become invisible (zero opacity, tiny scale).
function fillProperties(props, layer, degree, capacity) {
  const n = layer.count;
  const { positions: p, logScales: s, rotations: r, opacityLogits: o, sh } = layer;
  const x = props.x, y = props.y, z = props.z;
  const s0 = props.scale_0, s1 = props.scale_1, s2 = props.scale_2;
  const r0 = props.rot_0, r1 = props.rot_1, r2 = props.rot_2, r3 = props.rot_3;
  const op = props.opacity, d0 = props.f_dc_0, d1 = props.f_dc_1, d2 = props.f_dc_2;
  for (let i = 0; i < n; ++i) {
    x[i] = p[3 * i]; y[i] = p[3 * i + 1]; z[i] = p[3 * i + 2];
    s0[i] = s[3 * i]; s1[i] = s[3 * i + 1]; s2[i] = s[3 * i + 2];
    r0[i] = r[4 * i]; r1[i] = r[4 * i + 1]; r2[i] = r[4 * i + 2]; r3[i] = r[4 * i + 3];
    op[i] = o[i];
  }
  // Our SH: shCoefficients per channel, [k][r, g, b] per Gaussian; we draw at most `degree`.
  const coefficients = layer.shCoefficients, used = (degree + 1) ** 2, rest = used - 1;
  const restProps = [];
  for (let j = 0; j < 3 * rest; ++j) restProps.push(props[`f_rest_${j}`]);
  const stride = 3 * coefficients;
  for (let i = 0; i < n; ++i) {
    const base = stride * i;
    d0[i] = sh[base]; d1[i] = sh[base + 1]; d2[i] = sh[base + 2];
    for (let k = 1; k < used; ++k) {
      const v = k < coefficients ? base + 3 * k : -1;
      for (let c = 0; c < 3; ++c) restProps[c * rest + k - 1][i] = v < 0 ? 0 : sh[v + c];
    }
  }
  // Padding: at the first Gaussian (or the origin), invisible.
  const px = n ? x[0] : 0, py = n ? y[0] : 0, pz = n ? z[0] : 0;
  for (let i = n; i < capacity; ++i) {
    x[i] = px; y[i] = py; z[i] = pz;
    s0[i] = s1[i] = s2[i] = PAD_LOG_SCALE;
    r0[i] = 1; r1[i] = r2[i] = r3[i] = 0;
    op[i] = PAD_OPACITY;
    d0[i] = d1[i] = d2[i] = 0;
    for (const q of restProps) q[i] = 0;
  }
}

// A clear error for a layer whose arrays do not hold `count` Gaussians.
function checkLayer(layer, name) {
  const fail = (what) => { throw new TypeError(`M4dPlayCanvasAdapter.update: ${name} layer: ${what}`); };
  if (!layer || typeof layer !== 'object') fail('missing');
  const n = layer.count, k = layer.shCoefficients;
  if (!Number.isInteger(n) || n < 0) fail(`bad count ${n}`);
  if (!Number.isInteger(layer.shDegree) || layer.shDegree < 0 || layer.shDegree > 3) fail(`bad shDegree ${layer.shDegree}`);
  if (!Number.isInteger(k) || k < 1) fail(`bad shCoefficients ${k}`);
  for (const [key, per] of [['positions', 3], ['logScales', 3], ['rotations', 4], ['opacityLogits', 1], ['sh', 3 * k]]) {
    if (!(layer[key] instanceof Float32Array) || layer[key].length < per * n) fail(`${key} must be a Float32Array of ${per * n} values`);
  }
}

/** Shows SplatFrames as two gsplat entities (static, dynamic) of a PlayCanvas app. */
export class M4dPlayCanvasAdapter {
  /**
   * app: a running pc.AppBase; pc: the playcanvas module (the adapter imports nothing itself).
   * options.parent: the entity the layers' entities go under (default app.root);
   * options.shDegree: the largest SH degree drawn, 0..3 (default 3).
   */
  constructor(app, pc, options = {}) {
    if (!app || !app.graphicsDevice || !app.root) throw new TypeError('M4dPlayCanvasAdapter: app must be a PlayCanvas app');
    if (!pc || typeof pc.GSplatData !== 'function' || typeof pc.GSplatResource !== 'function') {
      throw new TypeError('M4dPlayCanvasAdapter: pc must be the playcanvas module (GSplatData, GSplatResource)');
    }
    this.app = app;
    this.pc = pc;
    this.parent = options.parent || app.root;
    this.maxShDegree = Math.max(0, Math.min(3, options.shDegree ?? 3));
    /** Counters of what update() did, for tests and benchmarks. */
    this.stats = { frames: 0, staticBuilds: 0, dynamicBuilds: 0, dynamicInPlace: 0, lastUpdateMs: 0 };
    this._static = null;   // { entity, resource, count }
    this._dynamic = null;  // { entity, resource, data, props, capacity, degree, count }
    this._destroyed = false;
  }

  /** The static and dynamic layers' entities (null before the first frame or for an empty layer). */
  get entities() {
    return { static: this._static?.entity ?? null, dynamic: this._dynamic?.entity ?? null };
  }

  /**
   * Shows a SplatFrame: rebuilds the static entity when frame.staticChanged, updates the
   * dynamic one (in place when it can). Returns the milliseconds it took (CPU side: conversion
   * and texture writes; the GPU upload happens at the app's next render).
   */
  update(frame) {
    if (this._destroyed) throw new Error('M4dPlayCanvasAdapter: update() after destroy()');
    if (!frame || typeof frame !== 'object') throw new TypeError('M4dPlayCanvasAdapter.update: a SplatFrame is needed');
    const t0 = performance.now();
    if (frame.staticChanged) {
      if (!frame.static) throw new TypeError('M4dPlayCanvasAdapter.update: staticChanged without a static layer');
      checkLayer(frame.static, 'static');
    }
    if (frame.dynamic) checkLayer(frame.dynamic, 'dynamic');
    if (frame.staticChanged) this._setStatic(frame.static);
    if (frame.dynamic) this._setDynamic(frame.dynamic);
    ++this.stats.frames;
    this.stats.lastUpdateMs = performance.now() - t0;
    return this.stats.lastUpdateMs;
  }

  /** Removes the entities and frees their resources. */
  destroy() {
    this._dropStatic();
    this._dropDynamic();
    this._destroyed = true;
  }

  _degree(layer) {
    return Math.max(0, Math.min(this.maxShDegree, layer.shDegree | 0));
  }

  _build(name, layer, capacity, degree) {
    const pc = this.pc;
    const properties = makeProperties(capacity, degree);
    const props = Object.fromEntries(properties.map((p) => [p.name, p.storage]));
    fillProperties(props, layer, degree, capacity);
    const data = new pc.GSplatData([{ name: 'vertex', count: capacity, properties }]);
    const resource = new pc.GSplatResource(this.app.graphicsDevice, data);
    const entity = new pc.Entity(name);
    entity.addComponent('gsplat', { resource });
    this.parent.addChild(entity);
    return { entity, resource, data, props, capacity, degree, count: layer.count };
  }

  _setStatic(layer) {
    this._dropStatic();
    if (layer.count > 0) this._static = this._build('m4d-static', layer, layer.count, this._degree(layer));
    ++this.stats.staticBuilds;
  }

  _setDynamic(layer) {
    const degree = this._degree(layer);
    const d = this._dynamic;
    if (d && layer.count <= d.capacity && degree === d.degree) {
      // In place: rewrite the property arrays, then the resource's textures and centres.
      fillProperties(d.props, layer, degree, d.capacity);
      d.resource.updateColorData(d.data);
      d.resource.updateTransformData(d.data);
      if (degree > 0) d.resource.updateSHData(d.data);
      const centres = d.resource.centers;
      if (centres) {
        const { x, y, z } = d.props;
        for (let i = 0; i < d.capacity; ++i) {
          centres[3 * i] = x[i]; centres[3 * i + 1] = y[i]; centres[3 * i + 2] = z[i];
        }
      }
      d.data.calcAabb(d.resource.aabb);
      d.resource.centersVersion++;  // the sorter takes the new centres, the world state changes
      d.entity.gsplat.workBufferUpdate = this.pc.WORKBUFFER_UPDATE_ONCE ?? 1;  // re-read the textures
      d.count = layer.count;
      ++this.stats.dynamicInPlace;
      return;
    }
    this._dropDynamic();
    if (layer.count > 0) {
      this._dynamic = this._build('m4d-dynamic', layer, Math.max(16, Math.ceil(1.5 * layer.count)), degree);
      ++this.stats.dynamicBuilds;
    }
  }

  _dropStatic() {
    if (!this._static) return;
    this._static.entity.destroy();
    this._static.resource.destroy?.();
    this._static = null;
  }

  _dropDynamic() {
    if (!this._dynamic) return;
    this._dynamic.entity.destroy();
    this._dynamic.resource.destroy?.();
    this._dynamic = null;
  }
}

/**
 * Places a PlayCanvas camera entity so that it sees what a capture camera sees: camera
 * { fx, fy, cx, cy, rotation (9, row-major, world to camera, OpenCV axes), translation (3),
 * near? far? } in pixels of a `width` x `height` image (default: the camera's canvas size).
 * Sets the entity's world position and rotation and the camera's projection (principal point
 * included).
 */
export function setCaptureCamera(pc, cameraEntity, camera, width, height) {
  if (!cameraEntity?.camera) throw new TypeError('setCaptureCamera: the entity needs a camera component');
  const R = camera.rotation, t = camera.translation;
  if (!R || R.length !== 9 || !t || t.length !== 3) throw new TypeError('setCaptureCamera: rotation (9) and translation (3) are needed');
  const device = cameraEntity.camera.system?.app?.graphicsDevice;
  const W = width ?? device?.width, H = height ?? device?.height;
  if (!(W > 0 && H > 0 && camera.fx > 0 && camera.fy > 0)) throw new TypeError('setCaptureCamera: positive fx, fy, width and height are needed');
  // Camera centre C = -R^T t; PlayCanvas's camera axes (x right, y up, looking along -z) are
  // OpenCV's with y and z negated: the world matrix's columns are R's rows 0, -1, -2.
  const C = [0, 1, 2].map((k) => -(R[k] * t[0] + R[3 + k] * t[1] + R[6 + k] * t[2]));
  const m = new pc.Mat4();
  const d = m.data;  // column-major
  for (let k = 0; k < 3; ++k) {
    d[k] = R[k];
    d[4 + k] = -R[3 + k];
    d[8 + k] = -R[6 + k];
  }
  const q = new pc.Quat().setFromMat4(m);
  cameraEntity.setPosition(C[0], C[1], C[2]);
  cameraEntity.setRotation(q);
  const near = camera.near ?? 0.2, far = camera.far ?? 1000;
  cameraEntity.camera.nearClip = near;
  cameraEntity.camera.farClip = far;
  cameraEntity.camera.fov = (2 * Math.atan(H / (2 * camera.fy)) * 180) / Math.PI;
  const { fx, fy, cx, cy } = camera;
  // Off-centre perspective: x_clip = 2fx/W x + (1 - 2cx/W) z, y_clip = 2fy/H y + (2cy/H - 1) z.
  cameraEntity.camera.calculateProjection = (matrix) => {
    const p = matrix.data;
    p.fill(0);
    p[0] = (2 * fx) / W;
    p[5] = (2 * fy) / H;
    p[8] = 1 - (2 * cx) / W;
    p[9] = (2 * cy) / H - 1;
    p[10] = -(far + near) / (far - near);
    p[11] = -1;
    p[14] = (-2 * far * near) / (far - near);
  };
}
