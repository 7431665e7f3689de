// The viewer page: opens a capture, plays and scrubs its steps, toggles the layers, and shows
// the fields of the object clicked.
//   1. load: the capture named by ?capture=URL (default "capture.jsonl", which `proxima view`
//      serves), or a file chosen with "Open…"; fetch has a time limit and every failure ends
//      in the error panel (the line and what is wrong), never in a hang;
//   2. build: one three.js mesh per object; the camera is the capture's or one fitted to the
//      scene (Z up, seen from +x -y +z);
//   3. show step N: replay the steps to N (CaptureState), move the meshes, rebuild the step's
//      draw stream by layer and level, update the labels and the inspector;
//   4. play: advance by the steps' dt in real time; the slider, the arrow keys and the space
//      bar scrub and pause;
//   5. pick: a click (not a drag) casts a ray from the camera and selects the nearest mesh.
// window.proximaViewer exposes the state, setStep, setLayer and project for the browser test.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

import { CaptureError, CaptureState, DRAW_LAYERS, parseCapture } from './capture.js';
import { applyPose, colorOf, disposeGroup, drawStreamGroups, objectMesh } from './scene_objects.js';

const FETCH_TIMEOUT_MS = 15000;
const MAX_LABELS = 200;
const BACKGROUND = [32, 34, 40];

const elements = {
  view: document.getElementById('view'),
  labels: document.getElementById('labels'),
  play: document.getElementById('play'),
  slider: document.getElementById('step-slider'),
  stepLabel: document.getElementById('step-label'),
  open: document.getElementById('open-file'),
  source: document.getElementById('source'),
  layers: document.getElementById('layers'),
  inspector: document.getElementById('inspector'),
  error: document.getElementById('error'),
};

/** What the page shows: the capture, its replayed state, the three.js scene and the UI's choices. */
const viewer = {
  status: 'loading', // 'loading' | 'ready' | 'error'
  error: null,
  capture: null,
  state: null,
  step: 0,
  playing: false,
  layerOn: new Map(DRAW_LAYERS.map((layer) => [layer, true])),
  levelOn: new Map(), // "layer:level" -> bool (absent: on)
  meshes: new Map(), // object id -> THREE.Mesh
  drawGroups: [],
  reach: 10, // length of a ray drawn with no hit: a few times the scene's size
  texts: [],
  selectedId: null,
};

// ---- three.js set-up -------------------------------------------------------------------

const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(new THREE.Color().setRGB(BACKGROUND[0] / 255, BACKGROUND[1] / 255, BACKGROUND[2] / 255, THREE.SRGBColorSpace));
elements.view.appendChild(renderer.domElement);

const scene = new THREE.Scene();
scene.add(new THREE.HemisphereLight(0xffffff, 0x444455, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(3, -2, 5);
scene.add(sun);
const objectsRoot = new THREE.Group();
const drawRoot = new THREE.Group();
scene.add(objectsRoot, drawRoot);

let camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
camera.up.set(0, 0, 1);
let controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);

function viewSize() {
  return { width: Math.max(1, elements.view.clientWidth), height: Math.max(1, elements.view.clientHeight) };
}

function resize() {
  const { width, height } = viewSize();
  renderer.setSize(width, height);
  if (camera.isPerspectiveCamera) {
    camera.aspect = width / height;
  } else {
    const halfHeight = (camera.top - camera.bottom) / 2;
    camera.left = (-halfHeight * width) / height;
    camera.right = (halfHeight * width) / height;
  }
  camera.updateProjectionMatrix();
  render();
}
window.addEventListener('resize', resize);

function render() {
  renderer.render(scene, camera);
  placeLabels();
}

// ---- camera ------------------------------------------------------------------------------

function vector(v) {
  return new THREE.Vector3(v?.[0] ?? 0, v?.[1] ?? 0, v?.[2] ?? 0);
}

/** Bounds of what the camera should frame: the meshes (half-spaces left out: they are huge) and the step's draw stream (rays left out: they may be long). */
function sceneBounds() {
  const box = new THREE.Box3();
  for (const mesh of viewer.meshes.values()) {
    const record = viewer.state.objects.get(mesh.userData.objectId)?.record;
    if (record?.geometry?.type === 'halfspace') continue;
    box.expandByObject(mesh);
  }
  for (const group of viewer.drawGroups) {
    if (group.userData.layer !== 'queries') box.expandByObject(group);
  }
  if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  return box;
}

/** Replaces the camera by the capture's (header.camera) or one fitted to the scene. */
function setCamera(header) {
  const { width, height } = viewSize();
  const spec = header.camera;
  let position;
  let target;
  let up = new THREE.Vector3(0, 0, 1);
  if (spec && Array.isArray(spec.position) && Array.isArray(spec.target)) {
    position = vector(spec.position);
    target = vector(spec.target);
    if (Array.isArray(spec.up)) up = vector(spec.up);
  } else {
    const sphere = sceneBounds().getBoundingSphere(new THREE.Sphere());
    const radius = Math.max(sphere.radius, 1e-3);
    target = sphere.center;
    const flat = header.dimension === 2;
    const direction = flat ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(1, -1.2, 0.9).normalize();
    if (flat) up = new THREE.Vector3(0, 1, 0);
    position = target.clone().addScaledVector(direction, radius / Math.sin(THREE.MathUtils.degToRad(20)) * 1.1);
  }
  const distance = position.distanceTo(target);
  const fov = spec?.fov_degrees ?? 40;
  if (fov > 0) {
    camera = new THREE.PerspectiveCamera(fov, width / height, distance / 1000, distance * 100);
  } else {
    const halfHeight = (spec?.ortho_height ?? 2) / 2;
    const halfWidth = (halfHeight * width) / height;
    camera = new THREE.OrthographicCamera(-halfWidth, halfWidth, halfHeight, -halfHeight, -distance * 100, distance * 100);
  }
  camera.up.copy(up);
  camera.position.copy(position);
  camera.lookAt(target);
  controls.dispose();
  controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();
  controls.addEventListener('change', render);
}

// ---- objects and the draw stream ---------------------------------------------------------

/** Makes the meshes match the state's objects: new ones built, gone ones dropped, poses set. */
function syncMeshes() {
  for (const [id, mesh] of viewer.meshes) {
    const object = viewer.state.objects.get(id);
    if (!object || object.record !== mesh.userData.record) {
      objectsRoot.remove(mesh);
      mesh.geometry.dispose();
      mesh.material.dispose();
      viewer.meshes.delete(id);
    }
  }
  for (const [id, object] of viewer.state.objects) {
    let mesh = viewer.meshes.get(id);
    if (!mesh) {
      mesh = objectMesh(object.record);
      mesh.userData.record = object.record;
      viewer.meshes.set(id, mesh);
      objectsRoot.add(mesh);
    }
    applyPose(mesh, object.position, object.rotation);
    mesh.material.emissive.setHex(id === viewer.selectedId ? 0x553300 : 0x000000);
  }
}

function rebuildDrawStream(step) {
  for (const group of viewer.drawGroups) {
    drawRoot.remove(group);
    disposeGroup(group);
  }
  const { groups, texts } = drawStreamGroups(step, renderer.getPixelRatio(), viewer.reach);
  viewer.drawGroups = groups;
  viewer.texts = texts;
  for (const group of groups) drawRoot.add(group);
}

function isShown(layer, level) {
  return viewer.layerOn.get(layer) !== false && viewer.levelOn.get(`${layer}:${level}`) !== false;
}

function applyVisibility() {
  objectsRoot.visible = viewer.layerOn.get('shapes') !== false;
  for (const group of viewer.drawGroups) group.visible = isShown(group.userData.layer, group.userData.level);
  rebuildLabels();
  render();
}

// ---- text labels (HTML over the canvas) --------------------------------------------------

let labelNodes = [];

function rebuildLabels() {
  elements.labels.replaceChildren();
  labelNodes = [];
  for (const text of viewer.texts) {
    if (labelNodes.length >= MAX_LABELS) break;
    if (!isShown(text.layer, text.level) || viewer.layerOn.get('text') === false) continue;
    const node = document.createElement('span');
    node.className = 'label';
    node.textContent = text.text;
    node.style.color = `#${colorOf(text.color).getHexString(THREE.SRGBColorSpace)}`;
    elements.labels.appendChild(node);
    labelNodes.push({ node, position: text.position });
  }
  placeLabels();
}

function placeLabels() {
  for (const { node, position } of labelNodes) {
    const p = project(position);
    node.hidden = !p.visible;
    node.style.transform = `translate(${p.x.toFixed(1)}px, ${p.y.toFixed(1)}px)`;
  }
}

/** Where world point [x, y, z] appears: CSS pixels from the page's top-left corner; visible when in front of the camera and inside the view. */
function project(point) {
  const ndc = vector(point).project(camera);
  const rect = renderer.domElement.getBoundingClientRect();
  const x = rect.left + ((ndc.x + 1) / 2) * rect.width;
  const y = rect.top + ((1 - ndc.y) / 2) * rect.height;
  const visible = ndc.z > -1 && ndc.z < 1 && Math.abs(ndc.x) <= 1 && Math.abs(ndc.y) <= 1;
  return { x, y, visible };
}

// ---- steps ---------------------------------------------------------------------------------

function stepCount() {
  return viewer.capture ? viewer.capture.steps.length : 0;
}

/** Shows the state after step `index` (clamped to the capture's steps). */
function setStep(index) {
  if (!viewer.capture) return;
  const count = stepCount();
  viewer.step = count === 0 ? 0 : Math.min(Math.max(0, Math.trunc(index)), count - 1);
  if (count > 0) viewer.state.seek(viewer.step);
  const step = viewer.capture.steps[viewer.step];
  syncMeshes();
  rebuildDrawStream(step);
  applyVisibility();
  elements.slider.value = String(viewer.step);
  const time = viewer.capture.steps.slice(0, viewer.step + 1).reduce((t, s) => t + (s.dt ?? 0), 0);
  elements.stepLabel.textContent =
    count === 0 ? 'no steps' : `step ${viewer.step} / ${count - 1} (world step ${step.world_step ?? '?'}, t = ${time.toFixed(3)} s)`;
  showInspector();
}

let lastFrameTime = 0;
let carriedTime = 0;

function setPlaying(playing) {
  viewer.playing = playing && stepCount() > 1;
  elements.play.textContent = viewer.playing ? 'Pause' : 'Play';
  if (viewer.playing) {
    if (viewer.step >= stepCount() - 1) setStep(0);
    lastFrameTime = performance.now();
    carriedTime = 0;
    requestAnimationFrame(playFrame);
  }
}

function playFrame(now) {
  if (!viewer.playing) return;
  carriedTime += Math.min(0.25, (now - lastFrameTime) / 1000);
  lastFrameTime = now;
  let next = viewer.step;
  while (next < stepCount() - 1) {
    const dt = viewer.capture.steps[next + 1].dt || 1 / 60;
    if (carriedTime < dt) break;
    carriedTime -= dt;
    next += 1;
  }
  if (next !== viewer.step) setStep(next);
  if (viewer.step >= stepCount() - 1) setPlaying(false);
  else requestAnimationFrame(playFrame);
}

// ---- layers panel ----------------------------------------------------------------------------

function checkbox(label, checked, onChange, className) {
  const wrapper = document.createElement('label');
  if (className) wrapper.className = className;
  const input = document.createElement('input');
  input.type = 'checkbox';
  input.checked = checked;
  input.addEventListener('change', () => onChange(input.checked));
  wrapper.append(input, ` ${label}`);
  return { wrapper, input };
}

/** One checkbox per layer (all of them; a layer the capture does not use says so) and, for hierarchies, one per level. */
function buildLayersPanel() {
  elements.layers.replaceChildren();
  for (const layer of DRAW_LAYERS) {
    const levels = viewer.capture.levels.get(layer) ?? [];
    const used = layer === 'shapes' || levels.length > 0;
    const { wrapper, input } = checkbox(used ? layer : `${layer} (none)`, viewer.layerOn.get(layer), (on) => setLayer(layer, on));
    input.dataset.layer = layer;
    elements.layers.appendChild(wrapper);
    if (levels.length > 1) {
      const row = document.createElement('div');
      row.className = 'levels';
      for (const level of levels) {
        const box = checkbox(`${level}`, true, (on) => {
          viewer.levelOn.set(`${layer}:${level}`, on);
          applyVisibility();
        });
        box.input.dataset.layer = layer;
        box.input.dataset.level = String(level);
        row.appendChild(box.wrapper);
      }
      elements.layers.appendChild(row);
    }
  }
}

/** Shows or hides a layer ("shapes" also hides the objects' meshes). */
function setLayer(layer, on) {
  viewer.layerOn.set(layer, Boolean(on));
  const input = elements.layers.querySelector(`input[data-layer="${layer}"]:not([data-level])`);
  if (input) input.checked = Boolean(on);
  applyVisibility();
}

// ---- picking and the inspector ---------------------------------------------------------------

const raycaster = new THREE.Raycaster();
let pointerDown = null;

renderer.domElement.addEventListener('pointerdown', (event) => {
  pointerDown = { x: event.clientX, y: event.clientY };
});
renderer.domElement.addEventListener('pointerup', (event) => {
  if (!pointerDown || Math.hypot(event.clientX - pointerDown.x, event.clientY - pointerDown.y) > 4) return;
  pick(event.clientX, event.clientY);
});

/** Selects the nearest visible object under page pixel (x, y), or nothing. Returns its id or null. */
function pick(x, y) {
  const rect = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const hits = objectsRoot.visible ? raycaster.intersectObjects([...viewer.meshes.values()], false) : [];
  viewer.selectedId = hits.length > 0 ? hits[0].object.userData.objectId : null;
  syncMeshes();
  showInspector();
  render();
  return viewer.selectedId;
}

function formatNumbers(values) {
  return Array.isArray(values) ? `[${values.map((v) => (typeof v === 'number' ? +v.toPrecision(6) : String(v))).join(', ')}]` : String(values);
}

function geometryText(geometry) {
  if (!geometry) return '?';
  const parts = Object.entries(geometry)
    .filter(([key]) => key !== 'type' && key !== 'children')
    .map(([key, value]) => `${key} ${Array.isArray(value) ? formatNumbers(value) : value}`);
  if (Array.isArray(geometry.children)) parts.push(`${geometry.children.length} children (${geometry.children.map((c) => c.type).join(', ')})`);
  return `${geometry.type}${parts.length ? ': ' + parts.join(', ') : ''}`;
}

function showInspector() {
  const object = viewer.selectedId === null ? null : viewer.state?.objects.get(viewer.selectedId);
  if (!object) {
    elements.inspector.textContent = 'Click an object to see its fields.';
    return;
  }
  const record = object.record;
  const rows = [
    ['id', String(record.id)],
    ['kind', record.kind ?? '?'],
    ['sensor', String(record.sensor ?? false)],
    ['filter', record.filter ? `layer ${record.filter.layer}, mask ${record.filter.mask}, group ${record.filter.group}` : '?'],
    ['user data', record.user_data ?? '?'],
    ['ccd', record.ccd ?? '?'],
    ['geometry', geometryText(record.geometry)],
    ['position', formatNumbers(object.position)],
    ['rotation', formatNumbers(object.rotation)],
  ];
  const table = document.createElement('table');
  for (const [name, value] of rows) {
    const row = table.insertRow();
    row.insertCell().textContent = name;
    row.insertCell().textContent = value;
  }
  elements.inspector.replaceChildren(table);
}

// ---- loading ---------------------------------------------------------------------------------

function showError(message) {
  viewer.status = 'error';
  viewer.error = message;
  setPlaying(false);
  elements.error.textContent = `Cannot show this capture: ${message}`;
  elements.error.hidden = false;
}

/** Opens capture text (named `source` in the page); a bad capture shows its error. */
function openCapture(text, source) {
  elements.source.textContent = source;
  let capture;
  try {
    capture = parseCapture(text);
  } catch (error) {
    if (error instanceof CaptureError) {
      showError(`${source}: ${error.message}`);
      return;
    }
    throw error;
  }
  for (const mesh of viewer.meshes.values()) objectsRoot.remove(mesh);
  viewer.meshes.clear();
  viewer.capture = capture;
  viewer.state = new CaptureState(capture);
  viewer.selectedId = null;
  viewer.levelOn.clear();
  elements.error.hidden = true;
  elements.slider.max = String(Math.max(0, capture.steps.length - 1));
  elements.slider.disabled = capture.steps.length <= 1;
  elements.play.disabled = capture.steps.length <= 1;
  buildLayersPanel();
  setStep(0);
  viewer.reach = 4 * Math.max(1, sceneBounds().getBoundingSphere(new THREE.Sphere()).radius);
  setStep(0);
  setCamera(capture.header);
  resize();
  viewer.status = 'ready';
  viewer.error = null;
}

async function fetchText(url) {
  const abort = new AbortController();
  const timer = setTimeout(() => abort.abort(), FETCH_TIMEOUT_MS);
  try {
    const response = await fetch(url, { signal: abort.signal, cache: 'no-store' });
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status} ${response.statusText}`);
    return await response.text();
  } catch (error) {
    throw new Error(error.name === 'AbortError' ? `${url}: no answer within ${FETCH_TIMEOUT_MS / 1000} s` : error.message);
  } finally {
    clearTimeout(timer);
  }
}

async function loadFromUrl(url) {
  viewer.status = 'loading';
  elements.source.textContent = `loading ${url}…`;
  try {
    openCapture(await fetchText(url), url);
  } catch (error) {
    showError(error.message);
  }
}

// ---- controls ----------------------------------------------------------------------------------

elements.play.addEventListener('click', () => setPlaying(!viewer.playing));
elements.slider.addEventListener('input', () => {
  setPlaying(false);
  setStep(Number(elements.slider.value));
});
elements.open.addEventListener('change', async () => {
  const file = elements.open.files?.[0];
  if (!file) return;
  setPlaying(false);
  try {
    openCapture(await file.text(), file.name);
  } catch (error) {
    showError(`${file.name}: ${error.message}`);
  }
});
window.addEventListener('keydown', (event) => {
  if (!viewer.capture || event.target instanceof HTMLInputElement) return;
  if (event.key === ' ') {
    setPlaying(!viewer.playing);
  } else if (event.key === 'ArrowRight' || event.key === 'ArrowLeft') {
    setPlaying(false);
    setStep(viewer.step + (event.key === 'ArrowRight' ? 1 : -1));
  } else {
    return;
  }
  event.preventDefault();
});

/** The page's interface for scripts and the browser test (viewer/test/). */
window.proximaViewer = {
  get status() {
    return viewer.status;
  },
  get error() {
    return viewer.error;
  },
  get step() {
    return viewer.step;
  },
  get stepCount() {
    return stepCount();
  },
  get selectedId() {
    return viewer.selectedId;
  },
  /** The background colour, sRGB 0..255. */
  background: BACKGROUND,
  setStep: (index) => {
    setPlaying(false);
    setStep(index);
  },
  setLayer,
  project,
  pick,
};

resize();
loadFromUrl(new URLSearchParams(window.location.search).get('capture') ?? 'capture.jsonl');
