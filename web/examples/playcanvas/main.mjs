// An M4D stream played in a PlayCanvas app through the PlayCanvas adapter, next to an ordinary
// entity (a lit box). The stream is decoded in a Web Worker (M4dWorkerDecoder), whose
// SplatFrames (the static layer only when it changes) PlayerCore paces at the stream's fps and
// drops when decoding falls behind; the adapter shows them.
//
// Query parameters:
//   stream=URL     the stream (default /out/default.m4d)
//   module=URL     the directory of m4d.mjs (default /build/web/module/)
//   cameras=URL    a capture's transforms.json (as `m4d scene` writes); camera=N looks through
//                  capture camera N (scaled to the canvas's width and centred, as m4d_play does)
//   width, height  drawing size; autoplay=0 starts paused; box=0 leaves the box out
//   gops=1         streams by GOP with HTTP range requests (GopStreamer; the stream's sidecar
//                  index STREAM.gops.json from m4d_probe --gop-index) on a main-thread decoder,
//                  instead of one fetch into the worker decoder
//   manifest=URL   adaptive bitrate: plays the renditions of `m4d encode --renditions`
//                  (OUT.manifest.json) GOP by GOP by range requests, choosing each GOP's
//                  rendition from the measured throughput (AbrController through
//                  AbrFrameSource); window.m4dPlayCanvas.abr has the switch log and stalls
import * as pc from 'playcanvas';
import { M4dPlayCanvasAdapter, setCaptureCamera } from '../../adapters/playcanvas_adapter.mjs';
import { AbrController } from '../../js/abr_controller.mjs';
import { AbrFrameSource } from '../../js/abr_frame_source.mjs';
import { readRgb } from '../../js/canvas_readout.mjs';
import { camerasOfTransforms } from '../../js/capture_cameras.mjs';
import { GopStreamer } from '../../js/gop_streamer.mjs';
import { PlayerCore } from '../../js/player_core.mjs';
import { DecoderFrameSource } from '../../js/splat_frame.mjs';
import { M4dWorkerDecoder } from '../../js/worker_decoder.mjs';

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const canvas = $('view');
canvas.width = Number(params.get('width')) || 960;
canvas.height = Number(params.get('height')) || 540;

const moduleUrl = new URL(params.get('module') || '/build/web/module/', location.href).href.replace(/\/?$/, '/');
const streamUrl = new URL(params.get('stream') || '/out/default.m4d', location.href).href;
// The frame source: the worker decoder (fed by one fetch), or with gops=1 a GopStreamer.
let decoder, streamer = null, abr = null;
try {
  if (params.get('manifest')) {
    const { loadM4d } = await import(new URL('m4d.mjs', moduleUrl).href);
    const m4d = await loadM4d();
    const controller = new AbrController({
      manifestUrl: new URL(params.get('manifest'), location.href).href, openDecoder: () => m4d.openDecoder(),
    });
    decoder = await AbrFrameSource.open(controller);
    // For tests: the switches, the controller's stalls, the frames shown ({ index, rendition,
    // staticChanged, ms: wall clock }).
    abr = {
      source: decoder, shown: [],
      get switchLog() { return decoder.switchLog; },
      get stalls() { return decoder.stalls; },
      get rendition() { return decoder.shownRendition; },
    };
  } else if (params.get('gops') === '1') {
    const { loadM4d } = await import(new URL('m4d.mjs', moduleUrl).href);
    streamer = await GopStreamer.open({ m4d: await loadM4d(), url: streamUrl });
    decoder = new DecoderFrameSource(streamer);
  } else {
    decoder = new M4dWorkerDecoder({ moduleUrl: new URL('m4d.mjs', moduleUrl).href });
    await decoder.open();
  }
} catch (error) {
  $('error').textContent = String(error.message || error);
  throw error;
}
const core = new PlayerCore(decoder);

// The app draws at the canvas's own size; the drawing buffer is kept for read-back.
const device = await pc.createGraphicsDevice(canvas, {
  deviceTypes: [pc.DEVICETYPE_WEBGL2], antialias: false, preserveDrawingBuffer: true,
});
const createOptions = new pc.AppOptions();
createOptions.graphicsDevice = device;
createOptions.componentSystems = [pc.RenderComponentSystem, pc.CameraComponentSystem,
  pc.LightComponentSystem, pc.GSplatComponentSystem];
createOptions.resourceHandlers = [pc.TextureHandler, pc.ContainerHandler];
const app = new pc.AppBase(canvas);
app.init(createOptions);
app.setCanvasFillMode(pc.FILLMODE_NONE);
app.setCanvasResolution(pc.RESOLUTION_FIXED, canvas.width, canvas.height);

const camera = new pc.Entity('camera');
camera.addComponent('camera', { clearColor: new pc.Color(0, 0, 0, 1) });
app.root.addChild(camera);
const light = new pc.Entity('light');
light.addComponent('light', { type: 'directional', intensity: 1.5 });
light.setEulerAngles(45, 30, 0);
app.root.addChild(light);
app.scene.ambientLight = new pc.Color(0.35, 0.35, 0.35);
app.start();

const adapter = new M4dPlayCanvasAdapter(app, pc);
const state = { playing: params.get('autoplay') !== '0', ended: false, frame: null, shown: 0, history: [],
  looping: false, box: null, updateMs: 0, cameraSet: false };
if (state.playing) core.play();

// Capture camera `index` of a transforms.json, scaled to the canvas's width and centred.
async function captureCamera(url, index) {
  const c = camerasOfTransforms(await (await fetch(url)).json())[index];
  if (!c) throw new Error(`${url}: no camera ${index}`);
  const scale = canvas.width / c.width;
  return { fx: c.fx * scale, fy: c.fy * scale, cx: c.cx * scale,
    cy: c.cy * scale + 0.5 * (canvas.height - c.height * scale), rotation: c.rotation, translation: c.translation };
}

// Without capture cameras: m4d_play's orbit at angle 0 (the player's start) around the first
// dynamic layer: its mean, three times its spread away; the world's up is the stream's, else -y.
function orbitCamera(layer) {
  const c = [0, 0, 0];
  for (let i = 0; i < layer.count; ++i) for (let a = 0; a < 3; ++a) c[a] += layer.positions[3 * i + a] / layer.count;
  let sq = 0;
  for (let i = 0; i < layer.count; ++i) for (let a = 0; a < 3; ++a) sq += (layer.positions[3 * i + a] - c[a]) ** 2;
  const d = layer.count ? 3 * Math.sqrt(sq / layer.count) : 1;
  const up = decoder.streamInfo()?.upAxis ?? [0, -1, 0];
  const a = normalize(cross(up, Math.abs(up[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0])), b = cross(up, a);
  const eye = [0, 1, 2].map((k) => c[k] + d * (-b[k] + 0.3 * up[k]));
  const z = normalize(c.map((v, k) => v - eye[k])), x = normalize(cross(z, up)), y = cross(z, x);
  const rotation = [...x, ...y, ...z];
  const translation = [0, 1, 2].map((r) => -(rotation[3 * r] * eye[0] + rotation[3 * r + 1] * eye[1] + rotation[3 * r + 2] * eye[2]));
  const focal = 0.9 * canvas.width;
  return { centre: c, camera: { fx: focal, fy: focal, cx: canvas.width / 2, cy: canvas.height / 2, rotation, translation, near: 0.05 } };
}
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const l = Math.hypot(...a); return a.map((v) => v / l); };

// The box: an ordinary lit entity among the splats (fixed in the world, placed once between
// the camera and the dynamic layer's centre, to its right), drawn with the same depth buffer.
function addBox(centre) {
  const material = new pc.StandardMaterial();
  material.diffuse = new pc.Color(0.9, 0.5, 0.2);
  material.update();
  const box = new pc.Entity('box');
  box.addComponent('render', { type: 'box', material });
  const eye = camera.getPosition(), right = camera.right;
  const to = [centre[0] - eye.x, centre[1] - eye.y, centre[2] - eye.z], d = Math.hypot(...to);
  box.setLocalScale(0.12 * d, 0.12 * d, 0.12 * d);
  box.setPosition(eye.x + 0.6 * to[0] + 0.15 * d * right.x, eye.y + 0.6 * to[1] + 0.15 * d * right.y,
    eye.z + 0.6 * to[2] + 0.15 * d * right.z);
  box.setEulerAngles(20, 30, 0);
  app.root.addChild(box);
  state.box = box;
}

// Takes the frame PlayerCore says is due (if any) to the adapter; at the end, playing, loops.
function advance(now) {
  const frame = core.tick(now);
  if (frame) show(frame);
  if (core.error) $('error').textContent = String(core.error.message || core.error);
  if (core.playing && core.ended && state.frame && !state.looping && !abr) {
    state.looping = true;
    core.seek(0).finally(() => { state.looping = false; });
  }
  return frame !== null;
}

// Shows a SplatFrame (from the worker: the static layer only when it changed).
function show(splatFrame) {
  if (!state.cameraSet) {
    const orbit = orbitCamera(splatFrame.dynamic.count || !splatFrame.static ? splatFrame.dynamic : splatFrame.static);
    if (!params.get('cameras')) setCaptureCamera(pc, camera, orbit.camera, canvas.width, canvas.height);
    if (params.get('box') !== '0') addBox(orbit.centre);
    state.cameraSet = true;
  }
  state.updateMs = adapter.update(splatFrame);
  state.frame = { index: splatFrame.frameIndex, isKeyframe: splatFrame.isKeyframe, staticChanged: splatFrame.staticChanged };
  ++state.shown;
  state.history.push(splatFrame.frameIndex);
  if (abr) {
    abr.shown.push({ index: splatFrame.frameIndex, rendition: splatFrame.rendition, staticChanged: splatFrame.staticChanged, ms: performance.now() });
  }
  if (state.history.length > 64) state.history.shift();
  $('frame').textContent = `frame ${splatFrame.frameIndex}${splatFrame.isKeyframe ? ' (key)' : ''}`;
}

app.on('update', () => {
  advance(performance.now());
  $('readout').textContent = `decode ${decoder.lastDecodeMs.toFixed(1)} ms (${abr ? `rendition ${abr.rendition}` : streamer ? 'by GOP' : 'worker'})   update ${state.updateMs.toFixed(1)} ms   ` +
    `dropped ${core.stats.dropped}`;
});
$('play').textContent = state.playing ? 'Pause' : 'Play';
$('play').onclick = () => {
  state.playing = !state.playing;
  if (state.playing) core.play(); else core.pause();
  $('play').textContent = state.playing ? 'Pause' : 'Play';
};

// The splats are drawn once PlayCanvas's sorter has answered for the current splats.
let readyCount = 0;
app.systems.gsplat.on('frame:ready', (_camera, _layer, ready) => { if (ready) ++readyCount; });
const nextFrame = () => new Promise(requestAnimationFrame);

// For tests and embedding pages.
window.m4dPlayCanvas = {
  app, pc, adapter, state, decoder, core, streamer, abr, camera,
  // Pauses, shows frame `index` (the next frame by a step, any other through a seek of the
  // worker decoder, waiting for its bytes), and resolves after a sorted drawing of it.
  async showFrame(index) {
    state.playing = false;
    core.pause();
    $('play').textContent = 'Play';
    const shown = state.shown;
    if (state.frame && state.frame.index + 1 === index) {
      core.step();
    } else {
      while (!(await core.seek(index))) {
        if (state.ended) throw new Error(`frame ${index}: not in the stream`);
        await nextFrame();
      }
    }
    while (state.shown === shown) {
      if (core.error) throw core.error;
      if (!advance(performance.now())) await new Promise((done) => setTimeout(done, 1));
    }
    if (state.frame.index !== index) throw new Error(`frame ${index}: frame ${state.frame.index} came instead`);
    for (const seen = readyCount; readyCount < seen + 2;) await nextFrame();
    await nextFrame();
    return state.frame.index;
  },
  // The canvas as RGB bytes, top row first.
  readRgb() {
    const gl = device.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return readRgb(gl, canvas.width, canvas.height);
  },
  loaded: null,
};

async function load() {
  if (params.get('cameras')) {
    setCaptureCamera(pc, camera, await captureCamera(params.get('cameras'), Number(params.get('camera') || 0)),
      canvas.width, canvas.height);
  }
  if (streamer || abr) {
    state.ended = true;  // the streamer fetches GOPs as frames are asked for
    return;
  }
  const response = await fetch(streamUrl);
  if (!response.ok) throw new Error(`${response.url}: HTTP ${response.status}`);
  const reader = response.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    await decoder.push(value, { transfer: true });
  }
  await decoder.end();
  state.ended = true;
}
window.m4dPlayCanvas.loaded = load().catch((e) => { state.ended = true; $('error').textContent = String(e.message || e); });
