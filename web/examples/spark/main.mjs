// Example: an M4D stream played in a three.js scene through Spark (M4dSparkAdapter), beside an
// ordinary three.js mesh. The stream is decoded in a Web Worker (M4dWorkerDecoder), whose
// SplatFrames (the static layer only when it changes) PlayerCore paces at the stream's fps and
// drops when decoding falls behind; the adapter shows them.
//
// Query parameters:
//   stream=URL     the stream (default ../../../out/default.m4d)
//   module=URL     the directory of m4d.mjs (default ../../../build/web/module/)
//   cameras=URL    a capture's transforms.json; camera=N looks through its camera N (else an
//                  orbit around the first frame's dynamic layer)
//   width, height  drawing size (default 960x540); autoplay=0 starts paused
//   mesh=0         leaves the three.js mesh out
//   spark=default  Spark's own renderer settings (else m4dSparkRendererOptions(): as M4D's)
//   gops=1         streams by GOP with HTTP range requests (GopStreamer; the stream's sidecar
//                  index STREAM.gops.json from m4d_probe --gop-index) on a main-thread decoder,
//                  instead of one fetch into the worker decoder
//   manifest=URL   adaptive bitrate: plays the renditions of `m4d encode --renditions`
//                  (OUT.manifest.json) GOP by GOP by range requests, choosing each GOP's
//                  rendition from the measured throughput (AbrController through
//                  AbrFrameSource); window.m4dSpark.abr has the switch log and stalls
import * as THREE from 'three';
import * as spark from '@sparkjsdev/spark';
import {
  M4dSparkAdapter, camerasOfTransforms, fitCaptureCamera, m4dSparkRendererOptions,
} from '../../adapters/spark_adapter.mjs';
import { AbrController } from '../../js/abr_controller.mjs';
import { AbrFrameSource } from '../../js/abr_frame_source.mjs';
import { readRgb } from '../../js/canvas_readout.mjs';
import { GopStreamer } from '../../js/gop_streamer.mjs';
import { PlayerCore } from '../../js/player_core.mjs';
import { DecoderFrameSource } from '../../js/splat_frame.mjs';
import { M4dWorkerDecoder } from '../../js/worker_decoder.mjs';

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const width = Number(params.get('width')) || 960;
const height = Number(params.get('height')) || 540;
const canvas = $('view');

const moduleUrl = new URL(params.get('module') || '../../../build/web/module/', location.href);
const m4dUrl = new URL('m4d.mjs', moduleUrl.href.replace(/\/?$/, '/')).href;
const streamUrl = new URL(params.get('stream') || '../../../out/default.m4d', location.href).href;
// The frame source: the worker decoder (fed by one fetch), or with gops=1 a GopStreamer.
let decoder, streamer = null, abr = null;
try {
  if (params.get('manifest')) {
    const { loadM4d } = await import(m4dUrl);
    const m4d = await loadM4d();
    const controller = new AbrController({
      manifestUrl: new URL(params.get('manifest'), location.href).href, openDecoder: () => m4d.openDecoder(),
    });
    decoder = await AbrFrameSource.open(controller);
    abr = abrLog(decoder);
  } else if (params.get('gops') === '1') {
    const { loadM4d } = await import(m4dUrl);
    streamer = await GopStreamer.open({ m4d: await loadM4d(), url: streamUrl });
    decoder = new DecoderFrameSource(streamer);
  } else {
    decoder = new M4dWorkerDecoder({ moduleUrl: m4dUrl });
    await decoder.open();
  }
} catch (error) {
  $('error').textContent = String(error.message || error);
  throw error;
}
const core = new PlayerCore(decoder);

// What adaptive bitrate did, for tests: the switches, the controller's stalls, and the frames
// shown ({ index, rendition, staticChanged, ms: wall clock }).
function abrLog(source) {
  return {
    source,
    shown: [],
    get switchLog() { return source.switchLog; },
    get stalls() { return source.stalls; },
    get rendition() { return source.shownRendition; },
  };
}

const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setSize(width, height, false);
renderer.setClearColor(0x000000, 1);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(50, width / height, 0.05, 1000);
scene.add(camera);
const sparkRenderer = new spark.SparkRenderer({ renderer, ...(params.get('spark') === 'default' ? {} : m4dSparkRendererOptions()) });
scene.add(sparkRenderer);
const adapter = new M4dSparkAdapter({ THREE, spark, parent: scene });

// Compositing: a lit box that the splats sort against through the depth buffer.
const box = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), new THREE.MeshStandardMaterial({ color: 0x3080ff }));
scene.add(new THREE.AmbientLight(0xffffff, 0.6), new THREE.DirectionalLight(0xffffff, 1.5));
if (params.get('mesh') !== '0') scene.add(box);

const state = {
  playing: params.get('autoplay') !== '0', ended: false, frame: null, firstIndex: null, shown: 0, history: [],
  looping: false, cameras: [], camera: null, orbit: null, updateMs: 0, drawMs: 0,
};
if (state.playing) core.play();

async function streamInto(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const reader = response.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    await decoder.push(value, { transfer: true });
  }
  await decoder.end();
}

// The orbit: around the dynamic layer's mean, three times its spread away; the box beside it.
function setUpOrbit(layer) {
  const centre = new THREE.Vector3();
  for (let i = 0; i < layer.count; ++i) centre.add(new THREE.Vector3().fromArray(layer.positions, 3 * i));
  if (layer.count) centre.divideScalar(layer.count);
  let sq = 0;
  for (let i = 0; i < layer.count; ++i) sq += centre.distanceToSquared(new THREE.Vector3().fromArray(layer.positions, 3 * i));
  const spread = layer.count ? Math.sqrt(sq / layer.count) : 1;
  state.orbit = { centre, distance: 3 * spread, yaw: 0 };
  const up = decoder.streamInfo()?.upAxis ?? [0, -1, 0];
  adapter.setUpAxis(up);
  box.scale.setScalar(0.4 * spread);
  box.position.copy(centre).applyMatrix4(adapter.root.matrixWorld).add(new THREE.Vector3(1.2 * spread, 0, 0));
}

function placeCamera() {
  const capture = state.cameras[state.camera];
  if (capture) {
    adapter.applyCaptureCamera(camera, fitCaptureCamera(capture, width, height), width, height);
    return;
  }
  if (!state.orbit) return;
  const { centre, distance, yaw } = state.orbit;
  const target = centre.clone().applyMatrix4(adapter.root.matrixWorld);
  camera.position.set(target.x + distance * Math.sin(yaw), target.y + 0.3 * distance, target.z + distance * Math.cos(yaw));
  camera.up.set(0, 1, 0);
  camera.lookAt(target);
  camera.updateMatrixWorld(true);
}

// Takes the frame PlayerCore says is due (if any) to the adapter; at the end, playing, loops.
function advance(now) {
  const frame = core.tick(now);
  if (frame) show(frame);
  if (core.error) $('error').textContent = String(core.error.message || core.error);
  if (core.playing && core.ended && state.frame && !state.looping && !abr) {
    state.looping = true;
    core.seek(state.firstIndex).finally(() => { state.looping = false; });
  }
  return frame !== null;
}

// Shows a SplatFrame (from the worker: the static layer only when it changed).
function show(frame) {
  if (!state.orbit) setUpOrbit(frame.dynamic.count || !frame.static ? frame.dynamic : frame.static);
  state.updateMs = adapter.update(frame).ms;
  state.frame = { index: frame.frameIndex, isKeyframe: frame.isKeyframe, staticChanged: frame.staticChanged };
  if (state.firstIndex === null) state.firstIndex = frame.frameIndex;
  ++state.shown;
  state.history.push(frame.frameIndex);
  if (abr) {
    abr.shown.push({ index: frame.frameIndex, rendition: frame.rendition, staticChanged: frame.staticChanged, ms: performance.now() });
  }
  if (state.history.length > 64) state.history.shift();
}

function draw() {
  placeCamera();
  const start = performance.now();
  renderer.render(scene, camera);
  state.drawMs = performance.now() - start;
}

function tick(now) {
  advance(now);
  if (state.orbit && state.camera === null && state.playing) state.orbit.yaw += 0.003;
  // Paused, a frame is drawn again only when Spark asks (a finished sort).
  if (state.playing || sparkRenderer.dirty || !state.drawn) {
    draw();
    state.drawn = true;
  }
  if (state.frame) {
    $('frame').textContent = `frame ${state.frame.index}${state.frame.isKeyframe ? ' (key)' : ''}`;
    const s = adapter.stats;
    $('readout').textContent = `decode ${decoder.lastDecodeMs.toFixed(1)} ms (${abr ? `rendition ${abr.rendition}` : streamer ? 'by GOP' : 'worker'})   update ${state.updateMs.toFixed(1)} ms   ` +
      `draw ${state.drawMs.toFixed(1)} ms   ${s.staticCount} static + ${s.dynamicCount} dynamic splats   ` +
      `static uploads ${s.staticUploads}   dropped ${core.stats.dropped}`;
  }
  requestAnimationFrame(tick);
}

$('play').textContent = state.playing ? 'Pause' : 'Play';
$('play').onclick = () => {
  state.playing = !state.playing;
  if (state.playing) core.play(); else core.pause();
  $('play').textContent = state.playing ? 'Pause' : 'Play';
};

// For tests and benchmarks.
window.m4dSpark = {
  THREE, spark, adapter, scene, camera, renderer, sparkRenderer, decoder, core, streamer, abr, state,
  // Pauses, shows frame `index` (the next frame by a step, any other through a seek of the
  // worker decoder), lets Spark finish generating and sorting for the current camera, draws
  // (unless `settle` is false: then the page's loop draws it when Spark is ready); resolves
  // with the frame index.
  async showFrame(index, settle = true) {
    state.playing = false;
    core.pause();
    $('play').textContent = 'Play';
    const shown = state.shown;
    if (state.frame && state.frame.index + 1 === index) core.step();
    else if (!(await core.seek(index))) throw new Error(`frame ${index}: not available`);
    while (state.shown === shown) {
      if (core.error) throw core.error;
      if (!advance(performance.now())) await new Promise((done) => setTimeout(done, 1));
    }
    if (state.frame.index !== index) throw new Error(`frame ${index}: frame ${state.frame.index} came instead`);
    if (settle) await this.settle();
    return state.frame.index;
  },
  // Runs Spark's update (splat generation and the depth sort) to completion, then draws.
  async settle() {
    placeCamera();
    // Spark skips a new generation while a sort of the previous one runs: wait for it first.
    const idle = async () => {
      while (sparkRenderer.sorting || sparkRenderer.sortDirty) {
        await new Promise((done) => setTimeout(done, 2));
        await sparkRenderer.driveSort();
      }
    };
    await idle();
    await sparkRenderer.update({ scene, camera });
    await idle();
    draw();
  },
  // The canvas as RGB bytes, top row first.
  readRgb() {
    return readRgb(renderer.getContext(), width, height);
  },
  setMeshVisible(visible) { box.visible = visible; },
  loaded: null,
};

async function loadCameras(url) {
  const json = await (await fetch(url)).json();
  state.cameras = Array.isArray(json) ? json : camerasOfTransforms(json);
  const n = Number(params.get('camera'));
  if (params.get('camera') !== null && state.cameras[n]) state.camera = n;
}

const loading = [streamer || abr ? Promise.resolve() : streamInto(streamUrl)];
if (params.get('cameras')) loading.push(loadCameras(params.get('cameras')));
window.m4dSpark.loaded = Promise.all(loading)
  .then(() => { state.ended = true; })
  .catch((e) => { state.ended = true; $('error').textContent = String(e.message || e); });
requestAnimationFrame(tick);
