// The viewer page: a scene, its methods and a picture that answers within a
// frame. It talks to an engine (engines.js) in the messages of
// docs/viewer-protocol.md and never knows which engine answers.
//
// URL parameters:
//   engine=socket       the native server of `lumiere view` (else WebAssembly)
//   scene=ID            what opens first (default cornell-box-point)
//   sets=K=V,K=V        overrides, as `--set`
//   methods=A,B         the first family's options to offer (a topic page)
//   embed=1             the canvas and the main controls only (an iframe)

import { engineFor } from './engines.js';
import { encodeOpenFiles, typeAndId } from './protocol.js';

// ---------------------------------------------------------------------------
// What the page was asked for

const params = new URLSearchParams(location.search);
const firstScene = params.get('scene') || 'cornell-box-point';
const urlSets = listParam('sets');
const offeredMethods = listParam('methods');
const embedded = params.get('embed') === '1';

function listParam(name) {
  return (params.get(name) ?? '').split(',').map((s) => s.trim()).filter(Boolean);
}

/** After this long without a move, the picture is drawn again at full quality. */
const SETTLE_MS = 150;
/** Pitch stays short of the poles, as in the native window (src/cli/view/orbit.rs). */
const MAX_PITCH = 1.5;
/** What a wheel notch or a pinch's step scales the distance by. */
const ZOOM_PER_LINE = 0.9;

// ---------------------------------------------------------------------------
// State: what is shown, as the page asked for it

const view = {
  scene: null, // the last `scene` reply
  sceneId: null, // its catalogue id, or null for files
  choices: {}, // family name → option name
  orbit: null, // {yaw, pitch, distance}
  split: null, // an option of the first family, or null
  difference: false,
  buffer: null, // a buffer's name, or null for the image
  exposure: 1,
  lights: [], // per light, its [dx, dy, dz] offset from where the scene puts it
  light: 0, // the light the arrows move
  paused: false,
  overlay: true,
};

let engine = null;
let frame = null; // the frame on screen: {header, pixels}
let frameCount = 0;
let roundTrip = null; // ms from sending a message to its frame
const errors = [];

let markReady;
let failReady;
const ready = new Promise((resolve, reject) => {
  markReady = resolve;
  failReady = reject;
});
ready.catch(() => {}); // an engine that never starts is shown in the banner

const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------
// Requests: every message gets the next id; its replies settle its promise

let nextId = 0;
/** Messages waiting for their last reply, in the order they were sent. */
const outstanding = [];
/**
 * The reply type that ends each message's answer (null: it has no reply of
 * its own). Any other message waits for its error.
 */
const LAST_REPLY = {
  catalogue: 'catalogue',
  open: 'frame',
  'open-files': 'frame',
  set: 'frame',
  export: 'export',
  solve: null,
  quit: null,
};
const lastReply = (type) => (Object.hasOwn(LAST_REPLY, type) ? LAST_REPLY[type] : 'error');

/**
 * Sends `message` (an object; for `open-files` with `files: [{name, bytes}]`
 * and `main`) and returns a promise of its replies, up to and including its
 * frame, export or error.
 */
function request(message) {
  const id = ++nextId;
  const entry = { id, type: message.type, replies: [], sentAt: performance.now() };
  // An open names its catalogue entry; files name none.
  entry.sceneId = message.type === 'open' ? message.scene : null;
  const done = new Promise((resolve) => {
    entry.resolve = resolve;
  });
  if (engine.failed) {
    entry.resolve([{ type: 'error', id, message: engine.failed }]);
    return { id, done, entry };
  }
  if (lastReply(message.type)) outstanding.push(entry);
  else entry.resolve([]);
  if (message.type === 'open-files') {
    engine.send(encodeOpenFiles(id, message.files, message.main, message.sets ?? []));
  } else {
    engine.send({ ...message, id });
  }
  if (lastReply(message.type) === 'frame') flow.inFlight = id;
  return { id, done, entry };
}

/** The message a reply answers (null: one the engine sent on its own). */
function ownerOf(type, id) {
  if (id != null) return outstanding.find((entry) => entry.id === id) ?? null;
  // An error without an id answers a message the engine could not read;
  // replies come in order, so it is the oldest one's.
  return type === 'error' ? outstanding[0] ?? null : null;
}

function onReply(reply) {
  const { type, id } = typeAndId(reply);
  const owner = ownerOf(type, id);
  show(type, reply, owner);
  if (owner) {
    owner.replies.push(reply);
    if (type === lastReply(owner.type) || type === 'error') settle(owner);
  }
}

function settle(entry) {
  outstanding.splice(outstanding.indexOf(entry), 1);
  if (flow.inFlight === entry.id) {
    flow.inFlight = null;
    pump();
  }
  entry.resolve(entry.replies);
}

/** The engine is gone: every waiting message fails, and the banner says why. */
function onEngineFailed(message) {
  showError(message);
  setStatus('');
  dropPending(message);
  for (const entry of [...outstanding]) {
    entry.replies.push({ type: 'error', id: entry.id, message });
    settle(entry);
  }
  failReady(new Error(message));
}

/** A promise of a message's frame, or a rejection with its error's message. */
async function frameOf(done) {
  const replies = await done;
  const last = replies.at(-1);
  if (!last) throw new Error('no reply');
  if (last.type === 'error') throw new Error(last.message);
  return asFrame(last);
}

function asFrame(reply) {
  const { header, payload } = reply;
  return { header, pixels: new Uint8ClampedArray(payload.buffer, payload.byteOffset, payload.length) };
}

// ---------------------------------------------------------------------------
// Flow control: at most one `set` in flight. Changes made meanwhile gather in
// `pending` and go together when its frame comes, so frames never queue up
// behind a drag.

const flow = {
  inFlight: null, // the id of the open/set whose frame has not come
  pending: null, // {fields, quality, waiters}
  settleTimer: null,
  confirmed: null, // what the last answered set showed, to go back to on an error
};

/**
 * Asks for `fields` (already in `view`). A move (`moving`) is drawn at preview
 * quality, and at full quality once the moves stop for SETTLE_MS.
 * Returns a promise of the frame that shows it.
 */
function change(fields, { moving = false } = {}) {
  const pending = (flow.pending ??= { fields: {}, waiters: [] });
  for (const [key, value] of Object.entries(fields)) {
    pending.fields[key] = key === 'choices' ? { ...pending.fields.choices, ...value } : value;
  }
  pending.quality = moving ? 'preview' : 'full';
  clearTimeout(flow.settleTimer);
  if (moving) flow.settleTimer = setTimeout(() => change({}), SETTLE_MS);
  const shown = new Promise((resolve, reject) => pending.waiters.push({ resolve, reject }));
  shown.catch(() => {}); // the banner shows errors; a click awaits nothing
  pump();
  return shown;
}

/** Sends what is pending, if nothing is in flight. */
function pump() {
  if (engine.failed) return dropPending(engine.failed);
  if (flow.inFlight != null || !flow.pending) return;
  const { fields, quality, waiters } = flow.pending;
  flow.pending = null;
  const sent = request({ type: 'set', ...fields, quality });
  sent.entry.view = snapshot(); // what its frame will show, to undo to later
  frameOf(sent.done).then(
    (shown) => waiters.forEach((w) => w.resolve(shown)),
    (error) => {
      undo(fields);
      waiters.forEach((w) => w.reject(error));
    },
  );
}

/** Pending changes are dropped (another scene opens): their promises fail. */
function dropPending(reason) {
  clearTimeout(flow.settleTimer);
  const waiters = flow.pending?.waiters ?? [];
  flow.pending = null;
  waiters.forEach((w) => w.reject(new Error(reason)));
}

/** The fields a set can carry, as they are now. */
function snapshot() {
  const { orbit, choices, lights, split, difference, buffer, exposure } = view;
  return structuredClone({ orbit, choices, lights, split, difference, buffer, exposure });
}

/** A set the engine refused: its fields go back to what is on screen. */
function undo(fields) {
  if (!flow.confirmed) return;
  for (const key of Object.keys(fields)) {
    if (key in view && !(flow.pending && key in flow.pending.fields)) {
      view[key] = structuredClone(flow.confirmed[key]);
    }
  }
  refreshControls();
}

// ---------------------------------------------------------------------------
// Replies on screen

function show(type, reply, owner) {
  switch (type) {
    case 'catalogue': return showCatalogue(reply.entries ?? []);
    case 'scene': return showScene(reply, owner);
    case 'frame': return showFrame(reply, owner);
    case 'export': return; // its requester downloads it
    case 'error': return showError(reply.message ?? 'an error without a message');
    default: console.warn('a reply the page does not know:', type);
  }
}

function showCatalogue(entries) {
  const select = $('scene-select');
  select.replaceChildren();
  const topics = new Map();
  for (const entry of entries) {
    if (!topics.has(entry.topic)) topics.set(entry.topic, []);
    topics.get(entry.topic).push(entry);
  }
  for (const [topic, list] of topics) {
    const group = element('optgroup', { label: topic || 'other' });
    for (const entry of list) {
      group.append(element('option', { value: entry.id, title: entry.paper ?? '' }, entry.title || entry.id));
    }
    select.append(group);
  }
  select.disabled = false;
  refreshSceneChooser();
}

/** A new scene: the controls are built again from its reply. */
function showScene(scene, owner) {
  dropPending('another scene was opened');
  view.scene = scene;
  // Opened from the catalogue (its id) or from files (null).
  view.sceneId = owner ? owner.sceneId ?? null : scene.entry?.id ?? null;
  view.choices = Object.fromEntries(scene.families.map((f) => [f.name, f.chosen]));
  view.orbit = { ...scene.orbit };
  view.split = null;
  view.difference = false;
  view.buffer = null;
  view.exposure = scene.exposure ?? 1;
  view.lights = scene.lights.map(() => [0, 0, 0]);
  view.light = Math.max(0, scene.lights.findIndex((l) => l.movable));
  view.paused = false;
  flow.confirmed = snapshot();

  showEntry(scene);
  buildFamilies(scene.families);
  buildLights(scene.lights);
  buildBuffers(scene.buffers ?? []);
  buildSplit();
  showWarnings(scene.warnings ?? []);
  refreshSceneChooser();
  refreshControls();

  // A topic page offers some methods only: start on the first of them.
  const first = scene.families[0];
  const offered = offeredOptions();
  if (first && offered.length && !offered.some((o) => o.name === first.chosen)) {
    chooseOption(first.name, offered[0].name);
  }
}

function showEntry(scene) {
  const entry = scene.entry;
  const title = entry?.title || scene.title || 'lumiere';
  $('entry-title').textContent = title;
  $('entry-paper').textContent = entry?.paper ?? '';
  $('entry-summary').textContent = entry?.summary ?? '';
  document.title = `${title} — lumiere`;
}

function showWarnings(warnings) {
  const list = $('warnings');
  list.replaceChildren(...warnings.map((w) => element('li', {}, w)));
  list.hidden = warnings.length === 0;
}

function showFrame(reply, owner) {
  // A frame the engine made before reading the newest set is already stale.
  const id = reply.header.id ?? null;
  if (flow.inFlight != null && id != null && id < flow.inFlight) return;
  const { header, pixels } = asFrame(reply);
  if (pixels.length !== header.width * header.height * 4) {
    showError(`a frame of ${pixels.length} bytes for ${header.width} × ${header.height} pixels`);
    return;
  }
  draw(header, pixels);
  frame = { header, pixels };
  frameCount += 1;
  updateBuffers(header.buffers);
  if (owner) {
    roundTrip = performance.now() - owner.sentAt;
    if (owner.view) flow.confirmed = owner.view;
  }
  clearError();
  showFrameInfo(header);
  // Ready once what the page asked for is drawn (a topic page's first method
  // may still be on its way).
  if (!flow.pending) markReady(frame);
}

function draw(header, pixels) {
  const canvas = $('canvas');
  if (canvas.width !== header.width || canvas.height !== header.height) {
    canvas.width = header.width;
    canvas.height = header.height;
    fitCanvas();
  }
  canvas.getContext('2d').putImageData(new ImageData(pixels, header.width, header.height), 0, 0);
  $('canvas-wrap').classList.add('drawn');
}

function showFrameInfo(header) {
  setStatus(header.status || (header.quality === 'preview' ? 'preview: one sample a pixel' : ''));
  const took = header.times?.[header.method];
  const parts = [];
  if (took != null) parts.push(`${header.method}: ${formatMs(took)} a full frame`);
  if (roundTrip != null) parts.push(`${formatMs(roundTrip)} round trip`);
  $('frame-time').textContent = parts.join(' · ');

  const legend = $('buffer-legend');
  legend.textContent = header.buffer ? `${header.buffer.name}: ${header.buffer.legend}` : '';
  legend.hidden = !header.buffer;

  const stats = $('split-stats');
  stats.textContent = header.split ? splitText(header.split) : '';
  stats.hidden = !header.split;

  refreshSolveControls();
  showOverlay();
}

function splitText(split) {
  return `RMSE ${split.rmse.toPrecision(3)} · ${(100 * split.differing).toFixed(1)}% of pixels differ`;
}

function formatMs(ms) {
  return ms < 10 ? `${ms.toFixed(1)} ms` : `${Math.round(ms)} ms`;
}

/** The native window's overlay: the method, its paper, every method's time. */
function showOverlay() {
  const overlay = $('overlay');
  overlay.hidden = !view.overlay || !view.scene;
  if (overlay.hidden) return;
  const header = frame?.header ?? {};
  const first = view.scene.families[0];
  const method = header.method ?? view.choices[first?.name];
  const lines = []; // strings, or [class, string] for lines a small screen leaves out
  if (first) lines.push(named(method, paperOf(first, method)));
  if (view.split) {
    lines.push(`split: ${named(view.split, paperOf(first, view.split))}${view.difference ? ' (difference ×4)' : ''}`);
    if (header.split) lines.push(splitText(header.split));
  }
  if (header.buffer) lines.push(`buffer: ${header.buffer.name}`);
  if (view.scene.lights.length) lines.push(`moving ${view.scene.lights[view.light]?.label ?? ''}`);
  if (view.choices.filter) lines.push(`texture filter: ${view.choices.filter}`);
  if (header.status) lines.push(header.status);
  const times = offeredOptions().map((o, i) => {
    const ms = header.times?.[o.name];
    return `${i + 1} ${o.name}${ms == null ? '' : ` ${formatMs(ms)}`}`;
  });
  if (times.length) lines.push(['times', times.join(' | ')]);
  lines.push(['help', 'drag orbit, wheel zoom, s split, d difference, b buffers, f filter, tab/arrows light, p pause . step, h hide']);
  overlay.replaceChildren(...lines.map((l) =>
    (Array.isArray(l) ? element('div', { class: l[0] }, l[1]) : element('div', {}, l))));
}

/** An option and its paper, when it has one. */
function named(option, paper) {
  return paper ? `${option} — ${paper}` : option;
}

function paperOf(family, option) {
  return family?.options.find((o) => o.name === option)?.paper ?? '';
}

function setStatus(text) {
  $('status').textContent = text;
}

function showError(message) {
  errors.push(message);
  $('error-message').textContent = message;
  $('error').hidden = false;
  refreshSceneChooser(); // a scene that did not open: the chooser names the open one
}

function clearError() {
  $('error').hidden = true;
  $('error-message').textContent = '';
}

// ---------------------------------------------------------------------------
// Controls, built from the scene reply

/** The first family's options this page offers (`methods=`, else all). */
function offeredOptions() {
  const first = view.scene?.families[0];
  if (!first) return [];
  const some = first.options.filter((o) => offeredMethods.includes(o.name));
  return some.length ? some : first.options;
}

function hasSolver() {
  return Boolean(view.scene?.families.some((f) => f.name === 'solver'));
}

/** A name made safe for an element id (stable: tests find controls by it). */
function slug(name) {
  return String(name).replace(/[^A-Za-z0-9_-]/g, '-');
}

/** One group a family: radio buttons, or a select when there are many options. */
function buildFamilies(families) {
  const box = $('families');
  box.replaceChildren();
  families.forEach((family, index) => {
    const options = index === 0 ? offeredOptions() : family.options;
    const group = element('fieldset', { id: `family-${slug(family.name)}`, class: 'group family' });
    group.append(element('legend', {}, family.label || family.name));
    if (options.length <= 8) {
      options.forEach((option, i) => {
        const input = element('input', {
          type: 'radio',
          name: `family-${slug(family.name)}`,
          id: `family-${slug(family.name)}-${slug(option.name)}`,
          value: option.name,
        });
        input.addEventListener('change', () => chooseOption(family.name, option.name));
        const key = index === 0 && i < 9 ? element('kbd', {}, String(i + 1)) : '';
        group.append(element('label', { class: 'choice', title: option.paper ?? '' }, input, key, ` ${option.name}`));
      });
    } else {
      const select = element('select', { id: `family-${slug(family.name)}-select`, 'aria-label': family.label });
      for (const option of options) {
        select.append(element('option', { value: option.name, title: option.paper ?? '' }, option.name));
      }
      select.addEventListener('change', () => chooseOption(family.name, select.value));
      group.append(select);
    }
    box.append(group);
  });
}

function buildLights(lights) {
  $('light-controls').hidden = lights.length === 0;
  const select = $('light-select');
  select.replaceChildren(...lights.map((light, i) => {
    const option = element('option', { value: String(i) }, light.label + (light.movable ? '' : ' (fixed)'));
    option.disabled = !light.movable; // Tab still names it, as the native window does
    return option;
  }));
}

/** The buffers come with each frame: they depend on the method shown. */
function updateBuffers(buffers) {
  if (!buffers || !view.scene) return;
  const known = view.scene.buffers ?? [];
  if (known.length === buffers.length && known.every((name, i) => name === buffers[i])) return;
  view.scene.buffers = buffers;
  buildBuffers(buffers);
  $('buffer-select').value = view.buffer ?? '';
}

function buildBuffers(buffers) {
  const select = $('buffer-select');
  select.replaceChildren(element('option', { value: '' }, 'image'));
  for (const name of buffers) select.append(element('option', { value: name }, name));
  select.disabled = buffers.length === 0;
}

function buildSplit() {
  const options = offeredOptions();
  $('split-controls').hidden = options.length < 2;
  const select = $('split-select');
  select.replaceChildren(element('option', { value: '' }, 'off'));
  for (const option of options) {
    select.append(element('option', { value: option.name, title: option.paper ?? '' }, option.name));
  }
}

/** The controls show `view` (after a key, an API call or an undone set). */
function refreshControls() {
  const scene = view.scene;
  if (!scene) return;
  for (const family of scene.families) {
    const chosen = view.choices[family.name];
    const radio = $(`family-${slug(family.name)}-${slug(chosen)}`);
    if (radio) radio.checked = true;
    const select = $(`family-${slug(family.name)}-select`);
    if (select) select.value = chosen;
  }
  $('split-select').value = view.split ?? '';
  $('split-difference').checked = view.difference;
  $('split-difference').disabled = !view.split;
  $('buffer-select').value = view.buffer ?? '';
  $('exposure').value = String(Math.log2(view.exposure));
  $('exposure-value').textContent = `×${formatExposure(view.exposure)}`;
  $('overlay-toggle').checked = view.overlay;
  refreshSolveControls();
  refreshLight();
  showOverlay();
}

/** Radiosity's controls, on a scene with a solver or while a solve reports. */
function refreshSolveControls() {
  const solving = Boolean(frame?.header.solving || frame?.header.status);
  $('solve-controls').hidden = !(hasSolver() || solving);
  $('solve-pause').textContent = view.paused ? 'resume' : 'pause';
}

function refreshLight() {
  const light = view.scene?.lights[view.light];
  $('light-select').value = String(view.light);
  for (const button of document.querySelectorAll('#light-controls .pad button')) {
    button.disabled = !light?.movable;
  }
  const offset = view.lights[view.light];
  $('light-offset').textContent = light
    ? (light.movable ? `moved by (${offset.map((v) => v.toFixed(2)).join(', ')})` : 'this light does not move')
    : '';
}

function refreshSceneChooser() {
  const select = $('scene-select');
  let files = select.querySelector('option[data-files]');
  if (view.scene && view.sceneId == null) {
    if (!files) {
      files = element('option', { value: '', 'data-files': '' }, 'your files');
      select.prepend(files);
    }
    files.textContent = `your files: ${view.scene.title ?? ''}`;
    select.value = '';
  } else {
    files?.remove();
    if (view.sceneId != null) select.value = view.sceneId;
  }
}

function formatExposure(e) {
  return e >= 10 ? e.toFixed(0) : e >= 1 ? e.toFixed(2) : e.toPrecision(2);
}

/** A DOM element with attributes and children. */
function element(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) {
    if (name === 'class') node.className = value;
    else node.setAttribute(name, value);
  }
  node.append(...children.filter((c) => c !== ''));
  return node;
}

// ---------------------------------------------------------------------------
// Changes: each updates `view`, the controls, and asks the engine

function chooseOption(family, option) {
  view.choices[family] = option;
  const fields = { choices: { [family]: option } };
  // As the native window does: a new method shows its image, not a buffer.
  if (family === view.scene?.families[0]?.name && view.buffer != null) {
    view.buffer = null;
    fields.buffer = null;
  }
  refreshControls();
  return change(fields);
}

function setOrbit(orbit, moving) {
  view.orbit = {
    yaw: orbit.yaw,
    pitch: Math.max(-MAX_PITCH, Math.min(MAX_PITCH, orbit.pitch)),
    distance: Math.max(1e-6, orbit.distance),
  };
  return change({ orbit: { ...view.orbit } }, { moving });
}

/** Moves light `index` by `by` (scene units); the engine gets every light's offset. */
function moveLight(index, by, moving) {
  if (!view.lights[index]) return Promise.reject(new Error(`the scene has no light ${index}`));
  view.light = index;
  view.lights[index] = view.lights[index].map((v, axis) => v + (by[axis] ?? 0));
  refreshLight();
  showOverlay();
  return change({ lights: structuredClone(view.lights) }, { moving });
}

/** A step of the chosen light along `axis` (0 x, 1 y, 2 z) in direction `sign`. */
function stepLight(axis, sign) {
  const light = view.scene?.lights[view.light];
  if (!light?.movable) return;
  const by = [0, 0, 0];
  by[axis] = sign * (view.scene.step ?? 1);
  moveLight(view.light, by, true);
}

function setSplit(option, difference) {
  view.split = option || null;
  view.difference = Boolean(difference) && view.split != null;
  refreshControls();
  return change({ split: view.split, difference: view.difference });
}

function setBuffer(name) {
  view.buffer = name || null;
  refreshControls();
  return change({ buffer: view.buffer });
}

function setExposure(exposure) {
  view.exposure = exposure;
  refreshControls();
  return change({ exposure });
}

function solve(action) {
  if (action === 'pause' || action === 'resume') view.paused = action === 'pause';
  refreshControls();
  return request({ type: 'solve', action }).done;
}

function openScene(id, sets = urlSets) {
  dropPending('another scene was opened');
  setStatus(`opening ${id}…`);
  const sent = request({ type: 'open', scene: id, sets: setsList(sets) });
  return frameOf(sent.done);
}

/** Opens files given as [{name, bytes}]; `main` is the scene's own file. */
function openFiles(files, main = mainFile(files.map((f) => f.name)), sets = urlSets) {
  if (!main) {
    const message = 'no .toml, .gltf, .glb or .obj among the files';
    showError(message);
    return Promise.reject(new Error(message));
  }
  dropPending('another scene was opened');
  setStatus(`opening ${main}…`);
  const sent = request({ type: 'open-files', files, main, sets: setsList(sets) });
  return frameOf(sent.done);
}

/** `key=value` overrides from a list, an object or a comma-separated string. */
function setsList(sets) {
  if (!sets) return [];
  if (typeof sets === 'string') return sets.split(',').filter(Boolean);
  if (Array.isArray(sets)) return sets;
  return Object.entries(sets).map(([k, v]) => `${k}=${v}`);
}

/** The scene among the files: a TOML first, else a glTF, a GLB, an OBJ. */
function mainFile(names) {
  for (const extension of ['.toml', '.gltf', '.glb', '.obj']) {
    const found = names.find((n) => n.toLowerCase().endsWith(extension));
    if (found) return found;
  }
  return null;
}

// ---------------------------------------------------------------------------
// Export: the linear values as a PFM file

async function exportPfm(what = 'image') {
  const replies = await request({ type: 'export', what }).done;
  const last = replies.at(-1);
  if (!last || last.type === 'error') throw new Error(last?.message ?? 'no reply');
  return pfm(last.header, last.payload);
}

/**
 * PFM: "PF" (colour) or "Pf" (grey), the size, a negative scale for
 * little-endian, then f32 rows from the bottom up (the export's rows run from
 * the top).
 */
function pfm(header, payload) {
  const { width, height, channels } = header;
  if (payload.length !== width * height * channels * 4) {
    const message = `an export of ${payload.length} bytes for ${width} × ${height} × ${channels} values`;
    showError(message);
    throw new Error(message);
  }
  const out = channels === 1 ? 1 : 3;
  const head = new TextEncoder().encode(`${out === 1 ? 'Pf' : 'PF'}\n${width} ${height}\n-1.0\n`);
  const values = new Float32Array(payload.slice().buffer); // a copy: the payload may sit unaligned
  const bytes = new Uint8Array(head.length + width * height * out * 4);
  bytes.set(head);
  const body = new DataView(bytes.buffer, head.length);
  let at = 0;
  for (let y = height - 1; y >= 0; y -= 1) {
    for (let x = 0; x < width; x += 1) {
      for (let c = 0; c < out; c += 1) {
        const value = c < channels ? values[(y * width + x) * channels + c] : 0;
        body.setFloat32(at, value, true);
        at += 4;
      }
    }
  }
  return bytes;
}

async function downloadExport() {
  const button = $('export');
  button.disabled = true;
  try {
    const bytes = await exportPfm('image');
    const method = frame?.header.method ?? 'image';
    const link = element('a', {
      href: URL.createObjectURL(new Blob([bytes], { type: 'application/octet-stream' })),
      download: `${slug(view.sceneId ?? view.scene?.title ?? 'scene')}-${slug(method)}.pfm`,
    });
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
  } catch {
    // The error is in the banner already.
  } finally {
    button.disabled = false;
  }
}

// ---------------------------------------------------------------------------
// The canvas: drag orbits, wheel and pinch zoom, files dropped open

/** The canvas as large as its box allows, its pixels scaled crisp by CSS. */
function fitCanvas() {
  const canvas = $('canvas');
  const box = $('frame-box');
  const phone = matchMedia('(max-width: 760px)').matches; // the box grows with the canvas
  const style = getComputedStyle(box); // client sizes count the padding in
  const width = box.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
  const height = phone
    ? window.innerHeight * 0.7
    : box.clientHeight - parseFloat(style.paddingTop) - parseFloat(style.paddingBottom);
  if (!width || !height) return;
  const scale = Math.min(width / canvas.width, height / canvas.height);
  canvas.style.width = `${Math.floor(canvas.width * scale)}px`;
  canvas.style.height = `${Math.floor(canvas.height * scale)}px`;
}

const pointers = new Map(); // pointerId → {x, y}

function onPointerDown(event) {
  if (!view.orbit) return;
  event.currentTarget.setPointerCapture(event.pointerId);
  pointers.set(event.pointerId, { x: event.clientX, y: event.clientY });
}

function onPointerMove(event) {
  const last = pointers.get(event.pointerId);
  if (!last || !view.orbit) return;
  const now = { x: event.clientX, y: event.clientY };
  if (pointers.size === 1) {
    // A drag across the canvas turns the view by pi, as the native window's did.
    const turn = Math.PI / Math.max(1, $('canvas').clientWidth);
    setOrbit({
      yaw: view.orbit.yaw - (now.x - last.x) * turn,
      pitch: view.orbit.pitch + (now.y - last.y) * turn,
      distance: view.orbit.distance,
    }, true);
  } else if (pointers.size === 2) {
    // Pinch: fingers apart by twice as much bring the camera twice as close.
    const other = [...pointers].find(([id]) => id !== event.pointerId)[1];
    const before = Math.hypot(last.x - other.x, last.y - other.y);
    const after = Math.hypot(now.x - other.x, now.y - other.y);
    if (before > 0 && after > 0) setOrbit({ ...view.orbit, distance: view.orbit.distance * (before / after) }, true);
  }
  pointers.set(event.pointerId, now);
}

function onPointerUp(event) {
  pointers.delete(event.pointerId);
}

function onWheel(event) {
  if (!view.orbit) return;
  event.preventDefault();
  // Lines of scroll, up positive: a notch is about 100 pixels in browsers.
  const perLine = [100, 1, 0.1][event.deltaMode] ?? 100;
  const lines = -event.deltaY / perLine;
  setOrbit({ ...view.orbit, distance: view.orbit.distance * ZOOM_PER_LINE ** lines }, true);
}

/** Names relative to the chosen folder: its own name is not part of them. */
function relativeName(file) {
  const path = file.webkitRelativePath;
  return path ? path.split('/').slice(1).join('/') : file.name;
}

async function openChosenFiles(list) {
  const files = await Promise.all(list.map(async ({ file, name }) =>
    ({ name, bytes: new Uint8Array(await file.arrayBuffer()) })));
  return openFiles(files).catch(() => {}); // the banner shows why
}

/** The files dropped, folders walked, names relative to a dropped folder. */
async function droppedFiles(entries, files) {
  if (!entries.length) return files.map((file) => ({ file, name: file.name }));
  const found = [];
  for (const entry of entries) {
    await walk(entry, entry.isDirectory ? entry.fullPath.length + 1 : 1, found);
  }
  return found;
}

async function walk(entry, strip, found) {
  if (entry.isFile) {
    const file = await new Promise((resolve, reject) => entry.file(resolve, reject));
    found.push({ file, name: entry.fullPath.slice(strip) });
    return;
  }
  const reader = entry.createReader();
  for (;;) {
    // readEntries answers in batches, and an empty one at the end.
    const batch = await new Promise((resolve, reject) => reader.readEntries(resolve, reject));
    if (!batch.length) break;
    for (const child of batch) await walk(child, strip, found);
  }
}

function onDrop(event) {
  event.preventDefault();
  $('drop-hint').hidden = true;
  // Entries must be taken while the event lasts; reading them can wait.
  const entries = [...event.dataTransfer.items]
    .map((item) => item.webkitGetAsEntry?.())
    .filter(Boolean);
  const files = [...event.dataTransfer.files];
  droppedFiles(entries, files).then(openChosenFiles, (error) => showError(`the dropped files: ${error.message}`));
}

// ---------------------------------------------------------------------------
// Keys, as the native window's

/** The keys a focused radio button, checkbox, slider or button uses itself. */
const CONTROL_KEYS = ['Tab', 'Enter', ' ', 'ArrowLeft', 'ArrowRight', 'ArrowUp', 'ArrowDown',
  'PageUp', 'PageDown', 'Home', 'End', 'Escape'];

/**
 * Keys typed in a form field are the field's: all of them in a text field or a
 * select, the ones it uses in a radio button, checkbox, slider or button (a
 * letter after a click on a method still works).
 */
function keyIsTheField(event) {
  const target = event.target;
  if (!(target instanceof Element)) return false;
  if (target.closest('select, textarea, [contenteditable]')) return true;
  if (target.matches('input')) {
    const clickable = ['radio', 'checkbox', 'range', 'button', 'file'].includes(target.type);
    return !clickable || CONTROL_KEYS.includes(event.key);
  }
  return target.closest('button, summary') != null && CONTROL_KEYS.includes(event.key);
}

const KEYS = {
  s: () => {
    if (view.split) return setSplit(null, false);
    const options = offeredOptions();
    const at = options.findIndex((o) => o.name === view.choices[view.scene.families[0].name]);
    if (options.length > 1) setSplit(options[(at + 1) % options.length].name, false);
  },
  d: () => view.split && setSplit(view.split, !view.difference),
  b: () => {
    const buffers = view.scene.buffers ?? [];
    if (!buffers.length) return;
    const at = buffers.indexOf(view.buffer);
    setBuffer(at + 1 < buffers.length ? buffers[at + 1] : null);
  },
  f: () => {
    const filter = view.scene.families.find((f) => f.name === 'filter');
    if (!filter) return;
    const at = filter.options.findIndex((o) => o.name === view.choices.filter);
    chooseOption('filter', filter.options[(at + 1) % filter.options.length].name);
  },
  p: () => solve(view.paused ? 'resume' : 'pause'),
  '.': () => solve('step'),
  h: () => toggleOverlay(),
  q: () => quit(),
  Escape: () => quit(),
  ArrowLeft: () => stepLight(0, -1),
  ArrowRight: () => stepLight(0, 1),
  ArrowUp: () => stepLight(2, -1),
  ArrowDown: () => stepLight(2, 1),
  PageUp: () => stepLight(1, 1),
  PageDown: () => stepLight(1, -1),
};

function onKey(event) {
  if (event.ctrlKey || event.metaKey || event.altKey || keyIsTheField(event) || !view.scene) return;
  const key = event.key;
  if (/^[1-9]$/.test(key)) {
    const option = offeredOptions()[Number(key) - 1];
    if (option) chooseOption(view.scene.families[0].name, option.name);
  } else if (key === 'Tab') {
    const count = view.scene.lights.length;
    if (!count) return;
    view.light = (view.light + (event.shiftKey ? count - 1 : 1)) % count;
    refreshLight();
    showOverlay();
  } else if (KEYS[key]) {
    KEYS[key]();
  } else {
    return;
  }
  event.preventDefault(); // arrows and page keys would scroll, Tab would move focus
}

function toggleOverlay(on = !view.overlay) {
  view.overlay = on;
  refreshControls();
}

/** `quit` ends the native server; in the browser there is nothing to end. */
function quit() {
  if (engine.native) request({ type: 'quit' });
}

// ---------------------------------------------------------------------------
// Wiring

function wire() {
  const canvas = $('canvas');
  canvas.addEventListener('pointerdown', onPointerDown);
  canvas.addEventListener('pointermove', onPointerMove);
  canvas.addEventListener('pointerup', onPointerUp);
  canvas.addEventListener('pointercancel', onPointerUp);
  canvas.addEventListener('wheel', onWheel, { passive: false });

  const box = $('frame-box');
  box.addEventListener('dragover', (event) => {
    if (!event.dataTransfer.types.includes('Files')) return; // text, links: not ours
    event.preventDefault();
    $('drop-hint').hidden = false;
  });
  box.addEventListener('dragleave', () => { $('drop-hint').hidden = true; });
  box.addEventListener('drop', onDrop);
  new ResizeObserver(fitCanvas).observe(box);
  window.addEventListener('resize', fitCanvas);

  $('scene-select').addEventListener('change', (event) => {
    if (event.target.value) openScene(event.target.value).catch(() => {});
  });
  for (const id of ['open-files', 'open-folder']) {
    $(id).addEventListener('change', (event) => {
      const list = [...event.target.files].map((file) => ({ file, name: relativeName(file) }));
      event.target.value = ''; // the same files can be chosen again
      if (list.length) openChosenFiles(list);
    });
  }

  $('split-select').addEventListener('change', (event) => setSplit(event.target.value, view.difference));
  $('split-difference').addEventListener('change', (event) => setSplit(view.split, event.target.checked));
  $('buffer-select').addEventListener('change', (event) => setBuffer(event.target.value));
  $('exposure').addEventListener('input', (event) => setExposure(2 ** Number(event.target.value)));
  $('overlay-toggle').addEventListener('change', (event) => toggleOverlay(event.target.checked));
  $('export').addEventListener('click', downloadExport);
  $('error-close').addEventListener('click', clearError);

  $('light-select').addEventListener('change', (event) => {
    view.light = Number(event.target.value);
    refreshLight();
    showOverlay();
  });
  const pad = { x: 0, y: 1, z: 2 };
  for (const [axis, index] of Object.entries(pad)) {
    $(`light-${axis}-minus`).addEventListener('click', () => stepLight(index, -1));
    $(`light-${axis}-plus`).addEventListener('click', () => stepLight(index, 1));
  }
  $('solve-pause').addEventListener('click', () => solve(view.paused ? 'resume' : 'pause'));
  $('solve-step').addEventListener('click', () => solve('step'));

  window.addEventListener('keydown', onKey);
}

// ---------------------------------------------------------------------------
// What tests drive (headless Chromium through the DevTools protocol)

function exposeApi() {
  window.lumiere = {
    ready,
    state: () => structuredClone({
      engine: engine.name,
      scene: view.scene,
      sceneId: view.sceneId,
      choices: view.choices,
      orbit: view.orbit,
      split: view.split,
      difference: view.difference,
      buffer: view.buffer,
      exposure: view.exposure,
      lights: view.lights,
      light: view.light,
      paused: view.paused,
      overlay: view.overlay,
      frame: frame?.header ?? null,
      pending: flow.pending != null,
      inFlight: flow.inFlight,
    }),
    lastFrame: () => frame && { header: frame.header, pixels: frame.pixels },
    /** Any message; the page gives it its id. Resolves with its replies. */
    send(message) {
      if (message.type === 'set') applyToView(message);
      return request(message).done;
    },
    choose: (family, option) => chooseOption(family, option),
    orbit(yaw, pitch, distance) {
      if (!view.orbit) return Promise.reject(new Error('no scene is open'));
      const { orbit } = view;
      return setOrbit({ yaw: yaw ?? orbit.yaw, pitch: pitch ?? orbit.pitch, distance: distance ?? orbit.distance }, false);
    },
    moveLight: (index, by) => moveLight(index, by, false),
    split: (option, difference = false) => setSplit(option, difference),
    buffer: (name) => setBuffer(name),
    exposure: (value) => setExposure(value),
    solve,
    open: (sceneId, sets = []) => openScene(sceneId, sets),
    openFiles: (files, main, sets = []) => openFiles(files, main ?? mainFile(files.map((f) => f.name)), sets),
    exportPfm,
    get frameCount() { return frameCount; },
    errors,
  };
}

/** A set a test sends by hand: the controls follow it. */
function applyToView(message) {
  for (const key of ['orbit', 'split', 'difference', 'buffer', 'exposure', 'lights']) {
    if (key in message) view[key] = structuredClone(message[key]);
  }
  if (message.choices) Object.assign(view.choices, message.choices);
  refreshControls();
}

function start() {
  if (embedded) document.body.classList.add('embed');
  engine = engineFor(params);
  engine.onreply = onReply;
  engine.onfail = onEngineFailed;
  $('footer').textContent = engine.native
    ? 'lumiere — rendered by the lumiere server'
    : 'lumiere — rendered in your browser by WebAssembly';
  wire();
  exposeApi();
  setStatus(engine.native ? 'connecting to the lumiere server…' : 'starting the WebAssembly engine…');
  request({ type: 'catalogue' });
  openScene(firstScene).catch(() => {});
}

start();
