// three.js objects for a capture: one mesh per world object (its local-frame tessellation,
// moved by the step's pose) and the step's draw stream grouped by layer and level.
//   1. objectMesh: a BufferGeometry from the record's flat positions / indices, coloured by
//      the record's colour (translucent when alpha < 255), flat shaded;
//   2. drawStreamGroups: for each (layer, level) of the step's primitives one THREE.Group
//      holding its lines (boxes become their twelve edges), triangles and point markers;
//      texts are returned apart, for HTML labels;
//   3. the step's recorded queries (rays) join the "queries" layer: the ray up to its last
//      hit (or `reach` when it has none), a marker and the normal at each hit;
//   4. markers (points) and the contact / normal / query lines are drawn over the shapes
//      (no depth test) so that a contact inside two overlapping objects stays visible.
import * as THREE from 'three';

/** Layers drawn over everything (no depth test): what a user looks for inside the shapes. */
const ON_TOP_LAYERS = new Set(['contacts', 'normals', 'queries', 'sweeps']);

/** A three.js colour (linear, as three.js works) from a capture's sRGB [r, g, b, a] 0..255. */
export function colorOf(rgba) {
  const [r, g, b] = Array.isArray(rgba) ? rgba : [200, 200, 200];
  return new THREE.Color().setRGB(r / 255, g / 255, b / 255, THREE.SRGBColorSpace);
}

function alphaOf(rgba) {
  return Array.isArray(rgba) && rgba.length > 3 ? rgba[3] / 255 : 1;
}

/** A number of the capture (null: non-finite) as something WebGL can hold. */
function finite(x) {
  return typeof x === 'number' && Number.isFinite(x) ? x : 0;
}

/** Sets `target` (Object3D) to a capture pose: position [x,y,z], rotation [x,y,z,w]. */
export function applyPose(target, position, rotation) {
  target.position.set(finite(position[0]), finite(position[1]), finite(position[2]));
  target.quaternion.set(finite(rotation[0]), finite(rotation[1]), finite(rotation[2]), finite(rotation[3] ?? 1));
  if (target.quaternion.lengthSq() === 0) target.quaternion.identity();
  target.quaternion.normalize();
}

/** The mesh of one OBJECT record, in its local frame (the caller sets the pose). */
export function objectMesh(record) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(record.mesh.positions.map(finite), 3));
  geometry.setIndex(record.mesh.indices);
  geometry.computeBoundingSphere();
  const opacity = alphaOf(record.color);
  const material = new THREE.MeshStandardMaterial({
    color: colorOf(record.color),
    flatShading: true,
    roughness: 0.8,
    metalness: 0,
    transparent: opacity < 1,
    opacity,
    depthWrite: opacity >= 1,
    side: THREE.DoubleSide,
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.userData.objectId = record.id;
  return mesh;
}

function pushVec(array, v) {
  array.push(finite(v?.[0]), finite(v?.[1]), finite(v?.[2]));
}

function pushColor(array, rgba) {
  const c = colorOf(rgba);
  array.push(c.r, c.g, c.b);
}

/** The twelve edges of a box primitive, appended as line-segment end points. */
function pushBoxEdges(positions, colors, box) {
  const h = box.half_extents ?? [0, 0, 0];
  const q = box.rotation ?? [0, 0, 0, 1];
  const rotation = new THREE.Quaternion(finite(q[0]), finite(q[1]), finite(q[2]), finite(q[3])).normalize();
  const center = new THREE.Vector3(finite(box.center?.[0]), finite(box.center?.[1]), finite(box.center?.[2]));
  const corner = (i) =>
    new THREE.Vector3(i & 1 ? h[0] : -h[0], i & 2 ? h[1] : -h[1], i & 4 ? h[2] : -h[2])
      .applyQuaternion(rotation)
      .add(center);
  const corners = [0, 1, 2, 3, 4, 5, 6, 7].map(corner);
  const edges = [[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]];
  for (const [a, b] of edges) {
    positions.push(corners[a].x, corners[a].y, corners[a].z, corners[b].x, corners[b].y, corners[b].z);
    pushColor(colors, box.color);
    pushColor(colors, box.color);
  }
}

/** An empty bucket of primitives for one (layer, level). */
function newBucket() {
  return { lines: [], lineColors: [], triangles: [], triangleColors: [], points: new Map() };
}

function fillBuckets(draw) {
  const buckets = new Map();
  const bucketOf = (primitive) => {
    const layer = typeof primitive.layer === 'string' ? primitive.layer : 'user';
    const level = Number.isInteger(primitive.level) ? primitive.level : 0;
    const key = `${layer}:${level}`;
    if (!buckets.has(key)) buckets.set(key, { layer, level, ...newBucket() });
    return buckets.get(key);
  };
  for (const line of draw.lines ?? []) {
    const bucket = bucketOf(line);
    pushVec(bucket.lines, line.from);
    pushVec(bucket.lines, line.to);
    pushColor(bucket.lineColors, line.color);
    pushColor(bucket.lineColors, line.color);
  }
  for (const box of draw.boxes ?? []) {
    const bucket = bucketOf(box);
    pushBoxEdges(bucket.lines, bucket.lineColors, box);
  }
  for (const triangle of draw.triangles ?? []) {
    const bucket = bucketOf(triangle);
    for (const corner of [triangle.a, triangle.b, triangle.c]) {
      pushVec(bucket.triangles, corner);
      pushColor(bucket.triangleColors, triangle.color);
    }
  }
  for (const point of draw.points ?? []) {
    // Points of one size share a THREE.Points (its size is per material).
    const bucket = bucketOf(point);
    const size = Math.max(1, finite(point.size) || 6);
    if (!bucket.points.has(size)) bucket.points.set(size, { positions: [], colors: [] });
    pushVec(bucket.points.get(size).positions, point.position);
    pushColor(bucket.points.get(size).colors, point.color);
  }
  return buckets;
}

function geometryOf(positions, colors) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  return geometry;
}

function groupOf(bucket, pixelRatio) {
  const group = new THREE.Group();
  group.userData = { layer: bucket.layer, level: bucket.level };
  const onTop = ON_TOP_LAYERS.has(bucket.layer);
  const order = onTop ? 10 : 1;
  if (bucket.lines.length > 0) {
    const material = new THREE.LineBasicMaterial({ vertexColors: true, depthTest: !onTop });
    const lines = new THREE.LineSegments(geometryOf(bucket.lines, bucket.lineColors), material);
    lines.renderOrder = order;
    group.add(lines);
  }
  if (bucket.triangles.length > 0) {
    const material = new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide, transparent: true, opacity: 0.6 });
    group.add(new THREE.Mesh(geometryOf(bucket.triangles, bucket.triangleColors), material));
  }
  for (const [size, points] of bucket.points) {
    // Markers are always drawn on top, at their size in CSS pixels.
    const material = new THREE.PointsMaterial({ vertexColors: true, size: size * pixelRatio, sizeAttenuation: false, depthTest: false });
    const markers = new THREE.Points(geometryOf(points.positions, points.colors), material);
    markers.renderOrder = 20;
    group.add(markers);
  }
  return group;
}

const RAY_COLOR = [120, 200, 255, 255];
const HIT_COLOR = [255, 255, 255, 255];

/** The lines and points that draw a step's recorded ray queries (layer "queries"). */
export function queryPrimitives(queries, reach) {
  const tag = { layer: 'queries', level: 0 };
  const lines = [];
  const points = [];
  for (const query of queries ?? []) {
    if (query.kind !== 'ray' || !Array.isArray(query.origin) || !Array.isArray(query.direction)) continue;
    const origin = query.origin.map(finite);
    const direction = query.direction.map(finite);
    const speed = Math.hypot(...direction) || 1;
    const hits = Array.isArray(query.hits) ? query.hits : [];
    const maxT = typeof query.max_t === 'number' ? query.max_t : Infinity;
    const lastHit = Math.max(0, ...hits.map((hit) => finite(hit.t)));
    const t = hits.length > 0 ? lastHit : Math.min(maxT, reach / speed);
    lines.push({ from: origin, to: origin.map((o, i) => o + direction[i] * t), color: RAY_COLOR, ...tag });
    for (const hit of hits) {
      if (!Array.isArray(hit.point)) continue;
      points.push({ position: hit.point, size: 5, color: HIT_COLOR, ...tag });
      if (Array.isArray(hit.normal)) {
        const to = hit.point.map((p, i) => finite(p) + finite(hit.normal[i]) * reach * 0.05);
        lines.push({ from: hit.point, to, color: HIT_COLOR, ...tag });
      }
    }
  }
  return { lines, points };
}

/**
 * The draw stream of one step (and its queries) as THREE.Groups, one per (layer, level), each
 * with userData {layer, level}; and its texts as {position, text, color, layer, level}.
 * `reach`: how far a ray with no hit and no finite max_t is drawn (length units).
 */
export function drawStreamGroups(step, pixelRatio, reach) {
  const draw = step?.draw ?? {};
  const queries = queryPrimitives(step?.queries, reach);
  const merged = { ...draw, lines: [...(draw.lines ?? []), ...queries.lines], points: [...(draw.points ?? []), ...queries.points] };
  const groups = [...fillBuckets(merged).values()].map((bucket) => groupOf(bucket, pixelRatio));
  const texts = (draw.texts ?? []).map((t) => ({
    position: [finite(t.position?.[0]), finite(t.position?.[1]), finite(t.position?.[2])],
    text: String(t.text ?? ''),
    color: t.color,
    layer: typeof t.layer === 'string' ? t.layer : 'text',
    level: Number.isInteger(t.level) ? t.level : 0,
  }));
  return { groups, texts };
}

/** Frees the GPU buffers of a group made by drawStreamGroups. */
export function disposeGroup(group) {
  group.traverse((child) => {
    child.geometry?.dispose();
    child.material?.dispose();
  });
}
