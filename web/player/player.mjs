// The M4D web player: streams an M4D file with fetch, decodes it with the WebAssembly SDK
// (m4d.mjs) as the bytes arrive, and draws every frame with the SDK's renderer in WebGL2.
//
// Query parameters:
//   stream=URL       the stream (default: the demo's, ../../out/default.m4d)
//   module=URL       the directory of m4d.mjs (default: ../../build/web/module/)
//   cameras=URL      capture cameras: a capture's transforms.json (nerfstudio's format, which
//                    `m4d scene` writes), or a JSON array of { width, height, fx, fy, cx, cy,
//                    rotation (9, row-major, world to camera), translation (3) }
//   camera=N         start with capture camera N (default: the orbit)
//   background=URL   a stream whose first static layer can replace this one's
//   width, height    drawing size (default 1280x720); autoplay=0 starts paused
//
// The orbit camera circles the first frame's dynamic layer as `m4d_play --orbit` does (the
// world's up is the one the stream states, else -y, OpenCV's convention): drag to turn it,
// wheel to move closer.
import { readRgb } from '../js/canvas_readout.mjs';
import { camerasOfTransforms } from '../js/capture_cameras.mjs';

const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const canvas = $('view');
canvas.width = Number(params.get('width')) || 1280;
canvas.height = Number(params.get('height')) || 720;

const moduleUrl = new URL(params.get('module') || '../../build/web/module/', location.href);
const { loadM4d } = await import(new URL('m4d.mjs', moduleUrl.href.replace(/\/?$/, '/')));
const m4d = await loadM4d();
const decoder = m4d.openDecoder();
const renderer = m4d.openRenderer(canvas);

const state = {
  playing: params.get('autoplay') !== '0',
  ended: false,         // every byte has arrived
  frame: null,          // the frame on screen: { index, isKeyframe }
  seekTo: null,         // a seek waiting for its bytes
  lastShown: -1,
  firstIndex: null,     // the stream's first frame: the slider and the loop start there
  nextDue: 0,           // time the next frame is due
  orbit: { yaw: 0, pitch: 0, zoom: 1, centre: null, distance: 1 },
  camera: 'orbit',
  cameras: [],
  decodeMs: 0, renderMs: 0, fps: 0,
  errorsSeen: 0,
  framesShown: 0,
};

// --- loading ---------------------------------------------------------------------------

async function streamInto(dec, url, onChunk) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const reader = response.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    dec.push(value);
    if (onChunk) onChunk();
  }
  dec.end();
}

async function loadCameras(url) {
  const json = await (await fetch(url)).json();
  // A transforms.json without frames gives no camera here (camerasOfTransforms would throw).
  const cameras = Array.isArray(json) ? json : camerasOfTransforms(json.frames ? json : { ...json, frames: [] });
  cameras.forEach((c, i) => $('camera').add(new Option(c.name || `capture ${i}`, String(i))));
  state.cameras = cameras;
  const first = params.get('camera');
  if (first !== null && cameras[Number(first)]) {
    state.camera = first;
    $('camera').value = first;
  }
}

async function loadBackground(url) {
  const source = m4d.openDecoder({ layers: 'static' });
  await streamInto(source, url);
  if (!source.nextFrame()) throw new Error(`${url}: no static layer decoded`);
  $('replace-background').disabled = false;
  $('replace-background').onchange = (e) => decoder.setBackground(e.target.checked ? source : null);
}

// --- cameras ---------------------------------------------------------------------------

const sub = (a, b) => a.map((v, i) => v - b[i]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const l = Math.hypot(...a); return a.map((v) => v / l); };

// A pinhole camera of the canvas size looking from eye at target (m4d_play's LookAt).
function lookAt(eye, target, up) {
  const z = normalize(sub(target, eye));
  const x = normalize(cross(z, up));  // then y = z x x: the image's down is the world's
  const y = cross(z, x);
  const rotation = [...x, ...y, ...z];
  const translation = [0, 1, 2].map((r) => -(rotation[3 * r] * eye[0] + rotation[3 * r + 1] * eye[1] + rotation[3 * r + 2] * eye[2]));
  const focal = 0.9 * canvas.width;
  return { fx: focal, fy: focal, cx: 0.5 * canvas.width, cy: 0.5 * canvas.height, rotation, translation, near: 0.05 };
}

// The orbit's centre and radius: the mean and three times the spread of the dynamic layer
// (or of the static one when there is none).
function setUpOrbit(frame) {
  const g = frame.dynamic.count ? frame.dynamic : frame.static;
  const centre = [0, 0, 0];
  for (let i = 0; i < g.count; ++i) for (let a = 0; a < 3; ++a) centre[a] += g.positions[3 * i + a];
  if (g.count) for (let a = 0; a < 3; ++a) centre[a] /= g.count;
  let sq = 0;
  for (let i = 0; i < g.count; ++i) for (let a = 0; a < 3; ++a) sq += (g.positions[3 * i + a] - centre[a]) ** 2;
  state.orbit.centre = centre;
  state.orbit.distance = g.count ? 3 * Math.sqrt(sq / g.count) : 1;
}

function orbitCamera() {
  const { yaw, pitch, zoom, centre, distance } = state.orbit;
  const up = decoder.streamInfo()?.upAxis ?? [0, -1, 0];
  // m4d_play's Perpendiculars(up): a = up x (1, 0, 0) (x (0, 1, 0) when up is along x), b = up x a.
  const a = normalize(cross(up, Math.abs(up[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0]));
  const b = cross(up, a);
  const d = distance * zoom;
  const lift = 0.3 + Math.sin(pitch);
  const eye = [0, 1, 2].map((k) => centre[k] + d * (Math.sin(yaw) * a[k] - Math.cos(yaw) * b[k] + lift * up[k]));
  return lookAt(eye, centre, up);
}

// A capture camera scaled to the canvas's width and centred, as m4d_play --capture does.
function captureCamera(c) {
  const scale = canvas.width / c.width;
  return {
    fx: c.fx * scale, fy: c.fy * scale,
    cx: c.cx * scale + 0.5 * (canvas.width - c.width * scale),
    cy: c.cy * scale + 0.5 * (canvas.height - c.height * scale),
    rotation: c.rotation, translation: c.translation, near: c.near ?? 0.2,
  };
}

function currentCamera() {
  const capture = state.cameras[Number(state.camera)];
  return state.camera === 'orbit' || !capture ? orbitCamera() : captureCamera(capture);
}

// --- decoding and drawing ----------------------------------------------------------------

// The layers damage made the decoder conceal in the frame on screen (bitstream-spec 6.8).
function concealedText(layers) {
  if (!layers) return '';
  const names = [layers & 1 ? 'static' : '', layers & 2 ? 'dynamic' : ''].filter(Boolean);
  return ` (${names.join(' and ')} layer concealed: damaged stream)`;
}

function layersShown() {
  return $('foreground').checked ? 'dynamic' : 'all';
}

// Decodes the next frame (or the one sought) and uploads it; false when its bytes have not
// arrived yet.
function advance() {
  if (state.seekTo !== null) {
    if (!decoder.seek(state.seekTo)) return false;
    state.seekTo = null;
  }
  const start = performance.now();
  let frame = decoder.nextFrame();
  if (!frame && state.ended && state.lastShown >= 0) {
    decoder.seek(state.firstIndex);  // loop
    frame = decoder.nextFrame();
  }
  reportErrors();
  if (!frame) return false;
  state.decodeMs = performance.now() - start;
  if (!state.orbit.centre) setUpOrbit(frame);
  renderer.upload(decoder, layersShown());
  state.frame = { index: frame.frameIndex, isKeyframe: frame.isKeyframe,
                  concealed: frame.concealedLayers };
  state.lastShown = frame.frameIndex;
  if (state.firstIndex === null) state.firstIndex = frame.frameIndex;
  return true;
}

function draw() {
  if (!state.frame) return;
  const start = performance.now();
  renderer.draw(currentCamera());
  state.renderMs = performance.now() - start;
}

function reportErrors() {
  const e = decoder.errors;
  if (e.count === state.errorsSeen) return;
  state.errorsSeen = e.count;
  $('error').textContent = `stream damaged at byte ${e.lastOffset} (${e.lastCodeName}: ${e.lastMessage}); ` +
    `playback resumes at the next GOP (${e.count} error${e.count > 1 ? 's' : ''})`;
}

// A frame's place in the stream: frame numbers may start anywhere and wrap at 2^32.
const place = (index) => (index - (state.firstIndex ?? 0)) >>> 0;

function updateReadout() {
  const info = decoder.streamInfo();
  const frames = info && info.numFrames ? info.numFrames
    : state.lastShown >= 0 ? place(state.lastShown) + 1 : 1;
  $('seek').max = String(frames - 1);
  if (state.frame) {
    $('seek').value = String(place(state.frame.index));
    $('frame').textContent = `frame ${state.frame.index} / ${frames - 1}${state.frame.isKeyframe ? ' (key)' : ''}${concealedText(state.frame.concealed)}`;
  }
  const stats = state.frame ? renderer.stats() : { visible: 0 };
  $('readout').textContent =
    `${state.fps.toFixed(1)} fps   decode ${state.decodeMs.toFixed(1)} ms   render ${state.renderMs.toFixed(1)} ms` +
    `   ${stats.visible} splats   ${(decoder.bufferedBytes / 1024).toFixed(0)} KB received${state.ended ? '' : ' (loading)'}` +
    (info ? `   bitstream ${info.bitstreamVersion}, ${info.fps.toFixed(0)} fps` : '');
}

let lastTick = 0;
function tick(now) {
  const info = decoder.streamInfo();
  const period = 1000 / (info && info.fps > 0 ? info.fps : 30);
  if ((state.playing && now >= state.nextDue) || state.seekTo !== null || !state.frame) {
    if (advance()) state.nextDue = Math.max(now, state.nextDue + period) || now + period;
  }
  draw();
  if (lastTick) state.fps = 0.9 * state.fps + 0.1 * (1000 / Math.max(now - lastTick, 1));
  lastTick = now;
  state.framesShown++;
  updateReadout();
  requestAnimationFrame(tick);
}

// --- controls ----------------------------------------------------------------------------

$('play').textContent = state.playing ? 'Pause' : 'Play';
$('play').onclick = () => {
  state.playing = !state.playing;
  $('play').textContent = state.playing ? 'Pause' : 'Play';
};
$('seek').oninput = (e) => { state.seekTo = ((state.firstIndex ?? 0) + Number(e.target.value)) >>> 0; };
$('camera').onchange = (e) => { state.camera = e.target.value; };
$('foreground').onchange = () => { if (state.frame) renderer.upload(decoder, layersShown()); };
let drag = null;
canvas.onpointerdown = (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); };
canvas.onpointerup = () => { drag = null; };
canvas.onpointermove = (e) => {
  if (!drag) return;
  state.camera = 'orbit';
  $('camera').value = 'orbit';
  state.orbit.yaw += (e.clientX - drag.x) * 0.01;
  state.orbit.pitch = Math.max(-1.2, Math.min(1.2, state.orbit.pitch + (e.clientY - drag.y) * 0.01));
  drag = { x: e.clientX, y: e.clientY };
};
canvas.onwheel = (e) => {
  e.preventDefault();
  state.orbit.zoom = Math.max(0.1, Math.min(10, state.orbit.zoom * Math.exp(e.deltaY * 0.001)));
};

// For tests and embedding pages: wait for frames, draw one, read the drawing back.
window.m4dPlayer = {
  state,
  decoder,
  // The last draw's splat count and stage times (project, sort, upload, draw in ms).
  renderStats: () => renderer.stats(),
  // Pauses, shows frame `index` once its bytes have arrived, and resolves after drawing it.
  async showFrame(index) {
    state.playing = false;
    state.seekTo = index;
    while (state.seekTo !== null || !state.frame || state.frame.index !== index) {
      await new Promise(requestAnimationFrame);
    }
    draw();
    return state.frame.index;
  },
  // The canvas as RGB bytes, top row first.
  readRgb() {
    return readRgb(canvas.getContext('webgl2'), canvas.width, canvas.height);
  },
  loaded: null,
};

const extras = [];
if (params.get('cameras')) extras.push(loadCameras(params.get('cameras')));
if (params.get('background')) extras.push(loadBackground(params.get('background')));
const streamUrl = params.get('stream') || '../../out/default.m4d';
window.m4dPlayer.loaded = Promise.all([streamInto(decoder, streamUrl), ...extras])
  .then(() => { state.ended = true; })
  .catch((e) => { state.ended = true; $('error').textContent = String(e.message || e); });
requestAnimationFrame(tick);
