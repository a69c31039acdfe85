// splat_frame.mjs - decoded M4D frames as owned, transferable typed arrays (SplatFrame), and
// the conversions splat viewers take (linear scales, opacities, unit quaternions, base colour).
//
//   const frame = decoder.nextFrame();                        // M4dFrame (views of wasm memory)
//   const splat = splatFrameFromDecoder(frame, { staticChanged: true });
//   postMessage(splat, transferablesOf(splat));               // no copy across threads
//
// A SplatLayer has the fields of M4dLayerView (m4d.d.mts): count, shDegree, shCoefficients,
// positions (3 per Gaussian), logScales (3), rotations (4: w, x, y, z, not normalised),
// opacityLogits (1), sh (3 * shCoefficients: [k][r, g, b]); each array owns its buffer.
// A SplatFrame is { frameIndex, isKeyframe, layers, concealedLayers, staticChanged, static,
// dynamic }; `static` may be null when staticChanged is false (the previous one still holds).

/** The zeroth-order spherical-harmonics constant, 1 / (2 sqrt(pi)). */
export const SH_C0 = 0.28209479177387814;

const ARRAYS = ['positions', 'logScales', 'rotations', 'opacityLogits', 'sh'];

// An owned copy of a layer (an M4dLayerView or a SplatLayer): each array gets its own buffer.
export function copySplatLayer(layerView) {
  const layer = {
    count: layerView.count,
    shDegree: layerView.shDegree,
    shCoefficients: layerView.shCoefficients,
  };
  for (const name of ARRAYS) layer[name] = new Float32Array(layerView[name]);
  return layer;
}

// A SplatFrame from the frame a main-thread decoder (M4dDecoder.nextFrame) returned. The
// dynamic layer is always copied; the static layer only when options.staticChanged is true
// (else `static` is null: the receiver keeps the one it has).
export function splatFrameFromDecoder(frame, options = {}) {
  const staticChanged = options.staticChanged === true;
  return {
    frameIndex: frame.frameIndex,
    isKeyframe: frame.isKeyframe,
    layers: frame.layers,
    concealedLayers: frame.concealedLayers,
    staticChanged,
    static: staticChanged ? copySplatLayer(frame.static) : null,
    dynamic: copySplatLayer(frame.dynamic),
  };
}

// Makes SplatFrames from a main-thread decoder's frames (M4dDecoder.nextFrame) and sets
// staticChanged itself: true on the first frame, on the first frame after reset() (call it
// after a seek), and at a keyframe whose static layer differs from the one last sent (a
// random-access keyframe or a STATIC_UPDATE; the static set changes only at keyframes,
// bitstream-spec 6.2). The worker decoder (m4d_worker.mjs) uses it too.
export class SplatFrameMaker {
  constructor() {
    /** An owned copy of the static layer last sent, or null. */
    this.lastStatic = null;
    this.stale = true;
  }

  // The next frame sends its static layer whatever it is (after a seek, a new stream).
  reset() {
    this.stale = true;
  }

  // The SplatFrame of an M4dFrame (the decoder's views are copied; `frame` may be reused after).
  make(frame) {
    const staticChanged = this.stale || (frame.isKeyframe && !layersEqual(frame.static, this.lastStatic));
    const splat = splatFrameFromDecoder(frame, { staticChanged });
    if (staticChanged) {
      // The frame's own copy goes out (and may be transferred): keep another to compare with.
      this.lastStatic = copySplatLayer(splat.static);
      this.stale = false;
    }
    return splat;
  }
}

// A frame source for PlayerCore (player_core.mjs) over a main-thread producer of M4dFrames
// whose nextFrame() returns one (or a promise of one) and seek(frame) moves it: an M4dDecoder
// given every byte (end() called), or a GopStreamer (gop_streamer.mjs) fetching GOPs as it
// plays. Frames come out as SplatFrames (SplatFrameMaker); null from the producer means the end.
export class DecoderFrameSource {
  constructor(producer) {
    if (!producer || typeof producer.nextFrame !== 'function' || typeof producer.seek !== 'function') {
      throw new TypeError('DecoderFrameSource: the producer needs nextFrame() and seek()');
    }
    this.producer = producer;
    this.maker = new SplatFrameMaker();
    /** True once the producer returned no frame. */
    this.ended = false;
    /** Milliseconds the last nextFrame() took (decoding, and for a streamer waiting for bytes). */
    this.lastDecodeMs = 0;
  }

  // The next frame as a SplatFrame, or null at the end.
  async nextFrame() {
    const start = performance.now();
    const frame = await this.producer.nextFrame();
    this.lastDecodeMs = performance.now() - start;
    if (!frame) {
      this.ended = true;
      return null;
    }
    return this.maker.make(frame);
  }

  // Moves the producer to `frame`; its next SplatFrame carries the static layer. Resolves
  // false when the producer refused (returned false).
  async seek(frame) {
    const done = this.producer.seek(frame) !== false;
    if (done) {
      this.maker.reset();
      this.ended = false;
    }
    return done;
  }

  // The stream's M4dStreamInfo (the producer's decoder's), or null before its header.
  streamInfo() {
    const decoder = typeof this.producer.streamInfo === 'function' ? this.producer : this.producer.decoder;
    return decoder && typeof decoder.streamInfo === 'function' ? decoder.streamInfo() : null;
  }
}

// The distinct ArrayBuffers of a SplatFrame's layers, for postMessage's transfer list.
export function transferablesOf(splatFrame) {
  const buffers = new Set();
  for (const layer of [splatFrame.static, splatFrame.dynamic]) {
    if (!layer) continue;
    for (const name of ARRAYS) if (layer[name]) buffers.add(layer[name].buffer);
  }
  return [...buffers];
}

// True when two layers hold the same Gaussians bit for bit (count, degree and every value).
export function layersEqual(a, b) {
  if (!a || !b) return a === b;
  if (a.count !== b.count || a.shDegree !== b.shDegree || a.shCoefficients !== b.shCoefficients) return false;
  for (const name of ARRAYS) {
    const x = a[name], y = b[name];
    if (x.length !== y.length) return false;
    const u = new Uint32Array(x.buffer, x.byteOffset, x.length);
    const v = new Uint32Array(y.buffer, y.byteOffset, y.length);
    for (let i = 0; i < u.length; ++i) if (u[i] !== v[i]) return false;
  }
  return true;
}

// Scales as viewers take them: exp(logScales), 3 per Gaussian. `out` (optional) is reused
// when long enough.
export function linearScales(layer, out) {
  const n = 3 * layer.count, s = layer.logScales;
  const result = out && out.length >= n ? out : new Float32Array(n);
  for (let i = 0; i < n; ++i) result[i] = Math.exp(s[i]);
  return result;
}

// Opacities in [0, 1]: sigmoid(opacityLogits), 1 per Gaussian.
export function opacities(layer, out) {
  const n = layer.count, o = layer.opacityLogits;
  const result = out && out.length >= n ? out : new Float32Array(n);
  for (let i = 0; i < n; ++i) result[i] = 1 / (1 + Math.exp(-o[i]));
  return result;
}

// Unit quaternions in x, y, z, w order (three.js, PlayCanvas), 4 per Gaussian, from the coded
// w, x, y, z; a zero (or non-finite) quaternion becomes the identity.
export function normalisedRotationsXyzw(layer, out) {
  const n = layer.count, r = layer.rotations;
  const result = out && out.length >= 4 * n ? out : new Float32Array(4 * n);
  for (let i = 0; i < n; ++i) {
    const w = r[4 * i], x = r[4 * i + 1], y = r[4 * i + 2], z = r[4 * i + 3];
    const length = Math.hypot(w, x, y, z);
    if (length > 0 && Number.isFinite(length)) {
      result[4 * i] = x / length;
      result[4 * i + 1] = y / length;
      result[4 * i + 2] = z / length;
      result[4 * i + 3] = w / length;
    } else {
      result.fill(0, 4 * i, 4 * i + 3);
      result[4 * i + 3] = 1;
    }
  }
  return result;
}

// Base colour (degree 0 of the SH), RGB per Gaussian: 0.5 + SH_C0 * dc, not clamped (values
// outside [0, 1] are possible; viewers clamp after adding the higher degrees).
export function rgbFromShDc(layer, out) {
  const n = layer.count, sh = layer.sh, stride = 3 * layer.shCoefficients;
  const result = out && out.length >= 3 * n ? out : new Float32Array(3 * n);
  for (let i = 0; i < n; ++i) {
    for (let c = 0; c < 3; ++c) result[3 * i + c] = 0.5 + SH_C0 * sh[stride * i + c];
  }
  return result;
}
