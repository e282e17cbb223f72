// polysim view, drawing: the scene's bodies and a frame's contacts as three.js objects
// (viewer.js plays them). The dynamic bodies of a run are two draw calls, faces and
// edges, moved on the CPU each frame: a 1000-box pile is 2000 objects otherwise, and
// draw calls, not vertices, are what a browser runs out of.
"use strict";

const STATIC_COLOUR = 0x9a9a9a, EDGE_COLOUR = 0x1a1a1a;
const CONTACT_COLOUR = 0x35e0ff, NORMAL_COLOUR = 0xff3df0;

// A body's faces as triangle fans and its polygon edges, body frame, flat arrays.
function polygons(body) {
  const v = body.vertices, triangles = [], edges = [];
  const at = (i) => [v[3 * i], v[3 * i + 1], v[3 * i + 2]];
  for (const face of body.faces) {
    for (let k = 1; k + 1 < face.length; ++k) triangles.push(...at(face[0]), ...at(face[k]), ...at(face[k + 1]));
    for (let k = 0; k < face.length; ++k) edges.push(...at(face[k]), ...at(face[(k + 1) % face.length]));
  }
  return {triangles, edges};
}

function dynamicColour(slot) {
  return new THREE.Color().setHSL((0.08 + 0.17 * slot) % 1, 0.85, 0.55);
}

const faceMaterial = (options) => new THREE.MeshLambertMaterial(Object.assign(
  {side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1}, options));

// A static body: its own mesh and edges, placed once.
function staticObject(body) {
  const {triangles, edges} = polygons(body);
  const faces = new THREE.BufferGeometry();
  faces.setAttribute("position", new THREE.Float32BufferAttribute(triangles, 3));
  faces.computeVertexNormals();
  const mesh = new THREE.Mesh(faces, faceMaterial({color: STATIC_COLOUR}));
  const lines = new THREE.BufferGeometry();
  lines.setAttribute("position", new THREE.Float32BufferAttribute(edges, 3));
  const group = new THREE.Group();
  group.add(mesh, new THREE.LineSegments(lines, new THREE.LineBasicMaterial({color: EDGE_COLOUR})));
  group.position.set(...body.position);
  const q = body.orientation;
  group.quaternion.set(q[1], q[2], q[3], q[0]);
  mesh.userData.body = body;
  return {group, mesh};
}

// Rotates (quaternion w x y z) and moves body-frame points `from` into `to` at `offset`.
function place(from, to, offset, q, t, translate) {
  const [w, x, y, z] = q;
  const r = [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
             2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
             2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)];
  for (let i = 0; i < from.length; i += 3) {
    const a = from[i], b = from[i + 1], c = from[i + 2], o = offset + i;
    to[o] = r[0] * a + r[1] * b + r[2] * c + (translate ? t[0] : 0);
    to[o + 1] = r[3] * a + r[4] * b + r[5] * c + (translate ? t[1] : 0);
    to[o + 2] = r[6] * a + r[7] * b + r[8] * c + (translate ? t[2] : 0);
  }
}

// Every dynamic body of a run (scene bodies in slot order) in one mesh and one set of lines.
class DynamicBodies {
  constructor(bodies) {
    this.local = bodies.map((b) => {
      const {triangles, edges} = polygons(b);
      const normals = [];
      for (let i = 0; i < triangles.length; i += 9) {
        const p = [0, 3, 6].map((k) => new THREE.Vector3(triangles[i + k], triangles[i + k + 1], triangles[i + k + 2]));
        const n = p[1].clone().sub(p[0]).cross(p[2].clone().sub(p[0])).normalize();
        for (let k = 0; k < 3; ++k) normals.push(n.x, n.y, n.z);
      }
      return {triangles: new Float32Array(triangles), normals: new Float32Array(normals), edges: new Float32Array(edges)};
    });
    const triangleFloats = this.local.reduce((s, l) => s + l.triangles.length, 0);
    const edgeFloats = this.local.reduce((s, l) => s + l.edges.length, 0);
    const colours = new Float32Array(triangleFloats);
    this.triangleSlot = new Int32Array(triangleFloats / 9);
    let at = 0;
    this.local.forEach((l, slot) => {
      const c = dynamicColour(slot);
      for (let i = 0; i < l.triangles.length; i += 3) colours.set([c.r, c.g, c.b], at + i);
      this.triangleSlot.fill(slot, at / 9, (at + l.triangles.length) / 9);
      at += l.triangles.length;
    });
    const faces = new THREE.BufferGeometry();
    faces.setAttribute("position", new THREE.BufferAttribute(new Float32Array(triangleFloats), 3));
    faces.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(triangleFloats), 3));
    faces.setAttribute("color", new THREE.BufferAttribute(colours, 3));
    const lines = new THREE.BufferGeometry();
    lines.setAttribute("position", new THREE.BufferAttribute(new Float32Array(edgeFloats), 3));
    this.mesh = new THREE.Mesh(faces, faceMaterial({vertexColors: THREE.VertexColors}));
    this.edges = new THREE.LineSegments(lines, new THREE.LineBasicMaterial({color: EDGE_COLOUR}));
    this.mesh.frustumCulled = this.edges.frustumCulled = false;  // their bounds change every frame
  }

  // pose(slot) -> {position, orientation [w x y z]}
  place(pose) {
    const faces = this.mesh.geometry.attributes, lines = this.edges.geometry.attributes;
    let tri = 0, edge = 0;
    this.local.forEach((l, slot) => {
      const p = pose(slot);
      place(l.triangles, faces.position.array, tri, p.orientation, p.position, true);
      place(l.normals, faces.normal.array, tri, p.orientation, p.position, false);
      place(l.edges, lines.position.array, edge, p.orientation, p.position, true);
      tri += l.triangles.length;
      edge += l.edges.length;
    });
    faces.position.needsUpdate = faces.normal.needsUpdate = lines.position.needsUpdate = true;
    this.mesh.geometry.computeBoundingSphere();  // for picking
  }
}

// A frame's contacts in four objects: area fills, outlines and lines, points, and each
// contact's normal as an arrow from the middle of its points. Built from flat arrays: a
// resting 1000-box pile has some 2000 contacts in every frame.
function contactObjects(pairs, scale) {
  const fill = [], lines = [], points = [], arrows = [];
  const length = 0.3 * scale, head = 0.25 * length, spread = 0.1 * length;
  for (const pair of pairs) {
    for (const c of pair.contacts) {
      const p = c.points, m = [0, 0, 0];
      for (const x of p) m[0] += x[0] / p.length, m[1] += x[1] / p.length, m[2] += x[2] / p.length;
      if (c.type === "area") {
        for (let k = 1; k + 1 < p.length; ++k) fill.push(...p[0], ...p[k], ...p[k + 1]);
        p.forEach((x, k) => lines.push(...x, ...p[(k + 1) % p.length]));
      } else if (c.type === "line") {
        lines.push(...p[0], ...p[1]);
      }
      for (const x of p) points.push(...x);
      const n = c.normal, tip = [m[0] + length * n[0], m[1] + length * n[1], m[2] + length * n[2]];
      const u = new THREE.Vector3(...n).cross(Math.abs(n[0]) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0)).normalize();
      const w = new THREE.Vector3(...n).cross(u);
      arrows.push(...m, ...tip);
      for (const d of [u, u.clone().negate(), w, w.clone().negate()])
        arrows.push(...tip, tip[0] - head * n[0] + spread * d.x, tip[1] - head * n[1] + spread * d.y, tip[2] - head * n[2] + spread * d.z);
    }
  }
  const group = new THREE.Group(), onTop = {depthTest: false};  // seen through the bodies they touch
  const geometry = (list) => {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(list, 3));
    return g;
  };
  if (fill.length) group.add(new THREE.Mesh(geometry(fill), new THREE.MeshBasicMaterial(
    Object.assign({color: CONTACT_COLOUR, transparent: true, opacity: 0.45, side: THREE.DoubleSide}, onTop))));
  if (lines.length) group.add(new THREE.LineSegments(geometry(lines), new THREE.LineBasicMaterial(Object.assign({color: CONTACT_COLOUR}, onTop))));
  if (points.length) group.add(new THREE.Points(geometry(points), new THREE.PointsMaterial(
    Object.assign({color: CONTACT_COLOUR, size: 6, sizeAttenuation: false}, onTop))));
  if (arrows.length) group.add(new THREE.LineSegments(geometry(arrows), new THREE.LineBasicMaterial(Object.assign({color: NORMAL_COLOUR}, onTop))));
  group.renderOrder = 1;
  return group;
}
