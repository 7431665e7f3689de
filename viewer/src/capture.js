// Reading a capture (docs/capture-format.md) in the browser: JSON Lines text into a header,
// a scene and steps, checked line by line, and the world's state at any step.
//   1. split the text into lines; a last line without its newline that does not parse is a
//      cut file ("line N is cut");
//   2. parse each line with JSON.parse; a line that does not parse names its line number;
//   3. check the members the viewer relies on (header format and version, objects' ids and
//      meshes, the steps' sequence of indices), naming the line and the member;
//   4. CaptureState replays the scene and the steps 0..N in order (removed, added, poses) to
//      give the objects and their poses after step N.
// Nothing here knows three.js: it is plain data, so node's test runner can read it too.

/** A capture that cannot be read: `line` (1-based; 0 when the file as a whole is wrong) and what is wrong. */
export class CaptureError extends Error {
  constructor(line, message) {
    super(line > 0 ? `line ${line}: ${message}` : message);
    this.name = 'CaptureError';
    this.line = line;
  }
}

/** The layer names of the draw stream, in the order the viewer lists them. */
export const DRAW_LAYERS = ['shapes', 'bounds', 'bvh', 'broadphase', 'contacts', 'normals', 'sweeps', 'queries', 'text', 'user'];

const DRAW_KINDS = ['lines', 'triangles', 'points', 'boxes', 'texts'];

function fail(line, message) {
  throw new CaptureError(line, message);
}

function isObject(value) {
  return value !== null && typeof value === 'object' && !Array.isArray(value);
}

/** Checks that `value` is an array of `length` numbers (null stands for a non-finite number). */
function checkVector(value, length, line, field) {
  if (!Array.isArray(value) || value.length !== length) fail(line, `${field} must be an array of ${length} numbers`);
  for (const x of value) {
    if (x !== null && typeof x !== 'number') fail(line, `${field} must hold numbers`);
  }
}

function checkPose(record, line, field) {
  checkVector(record.position, 3, line, `${field}.position`);
  checkVector(record.rotation, 4, line, `${field}.rotation`);
}

/** Checks one OBJECT record (the scene's objects, a step's `added`). */
function checkObject(object, line, field) {
  if (!isObject(object)) fail(line, `${field} must be an object`);
  if (!Number.isInteger(object.id)) fail(line, `${field}.id must be an integer`);
  checkPose(object, line, field);
  const mesh = object.mesh;
  if (!isObject(mesh) || !Array.isArray(mesh.positions) || !Array.isArray(mesh.indices)) {
    fail(line, `${field}.mesh must have positions and indices arrays`);
  }
  if (mesh.positions.length % 3 !== 0) fail(line, `${field}.mesh.positions: length ${mesh.positions.length} is not a multiple of 3`);
  if (mesh.indices.length % 3 !== 0) fail(line, `${field}.mesh.indices: length ${mesh.indices.length} is not a multiple of 3`);
  const vertexCount = mesh.positions.length / 3;
  for (let i = 0; i < mesh.indices.length; ++i) {
    const index = mesh.indices[i];
    if (!Number.isInteger(index) || index < 0 || index >= vertexCount) {
      fail(line, `${field}.mesh.indices[${i}] = ${index} is not a vertex (${vertexCount} vertices)`);
    }
  }
}

function checkHeader(header) {
  if (!isObject(header) || header.format !== 'proxima-capture') fail(1, 'not a capture: "format" must be "proxima-capture"');
  if (header.version !== 1) fail(1, `version ${JSON.stringify(header.version)} is not supported (this viewer reads version 1)`);
  if (header.camera !== undefined && !isObject(header.camera)) fail(1, 'camera must be an object');
}

function checkScene(scene) {
  if (!isObject(scene) || scene.type !== 'scene') fail(2, 'the second line must be the scene ({"type": "scene", ...})');
  if (!Array.isArray(scene.objects)) fail(2, 'scene.objects must be an array');
  scene.objects.forEach((object, i) => checkObject(object, 2, `objects[${i}]`));
}

function checkStep(step, expectedIndex, line) {
  if (!isObject(step) || step.type !== 'step') fail(line, 'a step line must have "type": "step"');
  if (step.index !== expectedIndex) fail(line, `index is ${JSON.stringify(step.index)}, expected ${expectedIndex}`);
  for (const member of ['poses', 'added', 'removed', 'contacts', 'queries']) {
    if (step[member] !== undefined && !Array.isArray(step[member])) fail(line, `${member} must be an array`);
  }
  (step.poses ?? []).forEach((pose, i) => {
    if (!isObject(pose) || !Number.isInteger(pose.id)) fail(line, `poses[${i}].id must be an integer`);
    checkPose(pose, line, `poses[${i}]`);
  });
  (step.added ?? []).forEach((object, i) => checkObject(object, line, `added[${i}]`));
  if (step.draw !== undefined) {
    if (!isObject(step.draw)) fail(line, 'draw must be an object');
    for (const kind of DRAW_KINDS) {
      if (step.draw[kind] !== undefined && !Array.isArray(step.draw[kind])) fail(line, `draw.${kind} must be an array`);
    }
  }
}

/** Parses one line; a failure names the line and, for the last line of a file without its final newline, says it is cut. */
function parseLine(text, line, isCutLast) {
  try {
    return JSON.parse(text);
  } catch (error) {
    if (isCutLast) fail(line, 'the line is cut: the file ends in the middle of it (a truncated capture)');
    fail(line, `not valid JSON (${error.message})`);
  }
}

/**
 * Reads a whole capture: returns {header, scene, steps, levels}. `levels` maps each draw layer
 * to the sorted hierarchy levels its primitives use over all steps. Throws CaptureError.
 */
export function parseCapture(text) {
  if (typeof text !== 'string' || text.length === 0) fail(0, 'the capture is empty');
  const endsWithNewline = text.endsWith('\n');
  const lines = text.split('\n');
  if (endsWithNewline) lines.pop();
  const records = [];
  for (let i = 0; i < lines.length; ++i) {
    const raw = lines[i].endsWith('\r') ? lines[i].slice(0, -1) : lines[i];
    if (raw.trim() === '') fail(i + 1, 'empty line');
    records.push(parseLine(raw, i + 1, !endsWithNewline && i === lines.length - 1));
  }
  if (records.length < 2) fail(records.length + 1, 'the capture ends before its scene line');
  checkHeader(records[0]);
  checkScene(records[1]);
  const steps = records.slice(2);
  steps.forEach((step, i) => checkStep(step, i, i + 3));
  return { header: records[0], scene: records[1], steps, levels: drawLevels(steps) };
}

function drawLevels(steps) {
  const levels = new Map(DRAW_LAYERS.map((layer) => [layer, new Set()]));
  for (const step of steps) {
    if ((step.queries ?? []).length > 0) levels.get('queries').add(0);
    for (const kind of DRAW_KINDS) {
      for (const primitive of step.draw?.[kind] ?? []) {
        const set = levels.get(primitive.layer);
        if (set) set.add(Number.isInteger(primitive.level) ? primitive.level : 0);
      }
    }
  }
  return new Map([...levels].map(([layer, set]) => [layer, [...set].sort((a, b) => a - b)]));
}

/**
 * The objects of a capture at one step: `objects` maps id -> {record, position, rotation}.
 * Moving forward applies the next steps; moving back replays from the scene.
 */
export class CaptureState {
  constructor(capture) {
    this.capture = capture;
    this.reset();
  }

  /** Back to the scene as written (before step 0 is applied). */
  reset() {
    this.objects = new Map();
    for (const record of this.capture.scene.objects) this.#place(record);
    this.step = -1;
  }

  /** Applies steps until the state is the one after step `index` (0..steps.length-1). */
  seek(index) {
    if (index < this.step) this.reset();
    while (this.step < index) this.#apply(this.capture.steps[++this.step]);
  }

  #place(record) {
    this.objects.set(record.id, { record, position: record.position, rotation: record.rotation });
  }

  #apply(step) {
    for (const id of step.removed ?? []) this.objects.delete(id);
    for (const record of step.added ?? []) this.#place(record);
    for (const pose of step.poses ?? []) {
      const object = this.objects.get(pose.id);
      if (object) {
        object.position = pose.position;
        object.rotation = pose.rotation;
      }
    }
  }
}
