// polysim view: plays step logs of one scene (sim/view_data.h describes the data). One
// view per log, side by side, on one clock; contacts as the log reports them; the energy
// and penetration under the views. The state drawn is written to #test-state after each
// frame, for the headless tests (tests/sim/view_test.py).
"use strict";

const data = JSON.parse(document.getElementById("polysim-data").textContent);
const FLOATS = 10;  // per body and frame: position 3, orientation [w x y z] 4, velocity 3
const BACKGROUND = 0x1d2330;
const TIME_ROUNDOFF = 1e-12;  // s: a step's logged time is "at or before t" despite round-off in t
const LEAST_DEPTH_SCALE = 1e-12;  // m: the penetration axis's top when nothing ever overlapped

function decodePoses(text) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}

// Where the camera looks: the box the dynamic bodies sweep over the run, or the statics.
function sceneBounds() {
  const box = new THREE.Box3();
  for (const run of data.runs) {
    const poses = run.decoded;
    for (let i = 0; i < poses.length; i += FLOATS) box.expandByPoint(new THREE.Vector3(poses[i], poses[i + 1], poses[i + 2]));
  }
  let reach = 0.5;
  for (const b of data.scene.bodies) {
    if (b.static) continue;
    for (let i = 0; i < b.vertices.length; i += 3) reach = Math.max(reach, Math.hypot(b.vertices[i], b.vertices[i + 1], b.vertices[i + 2]));
  }
  if (box.isEmpty()) {
    for (const b of data.scene.bodies) box.expandByPoint(new THREE.Vector3(...b.position));
  }
  return box.expandByScalar(reach);
}

function frameAt(run, t) {  // the last frame at or before t
  let lo = 0, hi = run.frames - 1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (run.times[mid] <= t + TIME_ROUNDOFF) lo = mid; else hi = mid - 1;
  }
  return lo;
}

function makeView(run, index, camera) {
  const element = document.createElement("div");
  element.className = "view";
  element.innerHTML = `<canvas></canvas><div class="label"></div>`;
  element.querySelector(".label").textContent = run.label;
  document.getElementById("views").appendChild(element);
  const canvas = element.querySelector("canvas");
  const renderer = new THREE.WebGLRenderer({canvas, antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(1, -2, 3);
  scene.add(sun);
  const statics = data.scene.bodies.filter((b) => b.static).map(staticObject);
  for (const s of statics) scene.add(s.group);
  const dynamic = new DynamicBodies(run.dynamic.map((i) => data.scene.bodies[i]));
  scene.add(dynamic.mesh, dynamic.edges);
  const controls = new THREE.OrbitControls(camera, canvas);
  return {run, index, element, canvas, renderer, scene, statics, dynamic, controls, contacts: null, contactSet: -1, frame: -1};
}

const views = [];
const state = {t: 0, playing: false, speed: 1, showContacts: true, end: 0, last: null};

function contactsAt(run, frame) {
  return run.contactSets[run.contactSetOf[frame]];
}

function poseOf(view, slot, frame) {
  const p = view.run.decoded, at = (frame * view.run.dynamic.length + slot) * FLOATS;
  return {position: [p[at], p[at + 1], p[at + 2]], orientation: [p[at + 3], p[at + 4], p[at + 5], p[at + 6]],
          velocity: [p[at + 7], p[at + 8], p[at + 9]]};
}

function showFrame(view, frame, scale) {
  const began = performance.now();
  view.frame = frame;
  view.dynamic.place((slot) => poseOf(view, slot, frame));
  // The same set of contacts as the frame before (a resting scene): keep what is drawn.
  const set = state.showContacts && view.run.contactSets ? view.run.contactSetOf[frame] : -1;
  if (set !== view.contactSet) {
    if (view.contacts) {
      view.scene.remove(view.contacts);
      view.contacts.traverse((o) => o.geometry && o.geometry.dispose());  // free the GPU buffers
    }
    view.contacts = set < 0 ? null : contactObjects(view.run.contactSets[set], scale);
    if (view.contacts) view.scene.add(view.contacts);
    view.contactSet = set;
  }
  state.frameMs = performance.now() - began;  // the script's share of a frame change (the GPU's is not in it)
}

function resize(camera) {
  for (const v of views) {
    const w = v.element.clientWidth, h = v.element.clientHeight;
    v.renderer.setSize(w, h, false);
    camera.aspect = w / h;
  }
  camera.updateProjectionMatrix();
  for (const id of ["timeline", "plot"]) {
    const c = document.getElementById(id);
    c.width = c.clientWidth;
  }
}

function drawTimeline() {
  const c = document.getElementById("timeline"), g = c.getContext("2d");
  g.fillStyle = "#262d3d";
  g.fillRect(0, 0, c.width, c.height);
  const x = (t) => (t / state.end) * (c.width - 1);
  data.runs.forEach((run, r) => {
    g.strokeStyle = r === 0 ? "#ff6a3d" : "#ffd23d";
    const top = (r * c.height) / data.runs.length, h = c.height / data.runs.length;
    for (const t of run.events) {
      g.beginPath();
      g.moveTo(x(t) + 0.5, top);
      g.lineTo(x(t) + 0.5, top + h);
      g.stroke();
    }
  });
  g.fillStyle = "#ffffff";
  g.fillRect(x(state.t) - 1, 0, 3, c.height);
}

function drawPlot() {
  const c = document.getElementById("plot"), g = c.getContext("2d");
  g.fillStyle = "#1f2535";
  g.fillRect(0, 0, c.width, c.height);
  const finite = (list) => list.filter((v) => v !== null);
  const energies = data.runs.flatMap((r) => finite(r.energy)), depths = data.runs.flatMap((r) => finite(r.penetration));
  const eMin = Math.min(...energies), eMax = Math.max(...energies), dMax = Math.max(LEAST_DEPTH_SCALE, ...depths);
  const x = (t) => (t / state.end) * (c.width - 1), pad = 14;
  const line = (run, values, low, high, colour, dashed) => {
    g.strokeStyle = colour;
    g.setLineDash(dashed ? [5, 4] : []);
    g.beginPath();
    let pen = false;
    values.forEach((v, k) => {
      if (v === null) { pen = false; return; }
      const y = c.height - pad - ((v - low) / (high - low || 1)) * (c.height - 2 * pad);
      if (pen) g.lineTo(x(run.times[k]), y); else g.moveTo(x(run.times[k]), y);
      pen = true;
    });
    g.stroke();
  };
  data.runs.forEach((run, r) => {
    line(run, run.energy, eMin, eMax, "#6fb3ff", r > 0);
    line(run, run.penetration, 0, dMax, "#ff5a5a", r > 0);
  });
  g.setLineDash([]);
  g.fillStyle = "#dde3ee";
  g.fillText(`energy ${eMin.toPrecision(4)} .. ${eMax.toPrecision(4)} J (blue)   penetration 0 .. ${dMax.toExponential(2)} m (red)` +
             (data.runs.length > 1 ? `   dashed: ${data.runs[1].label}` : ""), 6, 11);
  g.fillStyle = "#ffffff";
  g.fillRect(x(state.t) - 1, 0, 2, c.height);
}

function screenOf(view, camera, position) {
  const p = new THREE.Vector3(...position).project(camera), box = view.canvas.getBoundingClientRect();
  return [box.left + ((p.x + 1) / 2) * box.width, box.top + ((1 - p.y) / 2) * box.height];
}

function writeTestState(camera) {
  // The camera as a matrix from world to clip space (column-major), so that a test can
  // project the logged poses itself.
  const viewProjection = camera.projectionMatrix.clone().multiply(camera.matrixWorldInverse).elements;
  const out = {errors: window.polysimErrors, t: state.t, info: document.getElementById("info").textContent, readyMs: state.readyMs, renderMs: state.renderMs, frameMs: state.frameMs, viewProjection, runs: []};
  for (const v of views) {
    const bodies = v.run.dynamic.map((i, slot) => {
      const pose = poseOf(v, slot, v.frame);
      return {name: data.scene.bodies[i].name, position: pose.position, screen: screenOf(v, camera, pose.position)};
    });
    const contacts = v.run.contactSets && state.showContacts ? contactsAt(v.run, v.frame) : [];
    const drawn = v.contacts ? v.contacts.children.length : 0;
    const box = v.canvas.getBoundingClientRect(), canvas = [box.left, box.top, box.width, box.height];
    out.runs.push({label: v.run.label, frame: v.frame, time: v.run.times[v.frame], canvas, bodies, contacts, drawnContactObjects: drawn});
  }
  document.getElementById("test-state").textContent = JSON.stringify(out);
}

function render(camera, scale) {
  const began = performance.now();
  for (const v of views) {
    const frame = frameAt(v.run, state.t);
    if (frame !== v.frame) showFrame(v, frame, scale);
    v.renderer.render(v.scene, camera);
  }
  const run = data.runs[0], frame = frameAt(run, state.t);
  document.getElementById("slider").value = frame;
  document.getElementById("clock").textContent = `t = ${run.times[frame].toFixed(4)} s  step ${frame}`;
  drawTimeline();
  drawPlot();
  state.renderMs = performance.now() - began;
  if (state.readyMs === undefined) state.readyMs = performance.now();  // since the page began loading
  if (!state.playing) writeTestState(camera);  // a 1000-body frame's state is large: not at every played frame
}

// What a click on a body shows: a dynamic body's pose and velocity at the frame shown.
function showInfo(view, hit) {
  const info = document.getElementById("info");
  if (hit.object !== view.dynamic.mesh) {
    const body = hit.object.userData.body;
    info.textContent = `${body.name} (static)  position ${body.position.join(", ")}`;
    return;
  }
  const slot = view.dynamic.triangleSlot[hit.faceIndex], body = data.scene.bodies[view.run.dynamic[slot]];
  const pose = poseOf(view, slot, view.frame), f = (v) => v.map((x) => x.toFixed(5)).join(", ");
  info.textContent = `${body.name} (${view.run.label}, t = ${view.run.times[view.frame].toFixed(4)} s)\n` +
    `position [${f(pose.position)}] m  orientation [${f(pose.orientation)}]  velocity [${f(pose.velocity)}] m/s`;
}

// The camera looks at the bodies from the side and above; where a static body (a pen's
// wall, a cup's rim) stands between it and them, from higher up, until none does.
function placeCamera(camera, centre, distance, radius) {
  const statics = data.scene.bodies.filter((b) => b.static).map((b) => {
    const made = staticObject(b);
    made.group.updateMatrixWorld(true);
    return made.mesh;
  });
  const ray = new THREE.Raycaster();
  for (const degrees of [25, 40, 55, 70, 85]) {
    const elevation = (degrees * Math.PI) / 180;
    const towards = new THREE.Vector3(0.48 * Math.cos(elevation), -0.88 * Math.cos(elevation), Math.sin(elevation)).normalize();
    camera.position.copy(centre).addScaledVector(towards, distance);
    ray.set(camera.position, towards.clone().negate());
    ray.far = distance - radius;
    if (ray.intersectObjects(statics).length === 0) return;
  }
}

// A click at page pixel (x, y) on a view: the body under it, if any, in the info line.
function pick(view, camera, x, y) {
  const box = view.canvas.getBoundingClientRect();
  const mouse = new THREE.Vector2(((x - box.left) / box.width) * 2 - 1, -((y - box.top) / box.height) * 2 + 1);
  const ray = new THREE.Raycaster();
  ray.setFromCamera(mouse, camera);
  const hit = ray.intersectObjects([view.dynamic.mesh, ...view.statics.map((b) => b.mesh)])[0];
  if (hit) showInfo(view, hit);
}

function start() {
  for (const run of data.runs) run.decoded = decodePoses(run.poses);
  state.end = Math.max(...data.runs.map((r) => r.times[r.frames - 1]));
  const bounds = sceneBounds(), centre = bounds.getCenter(new THREE.Vector3());
  const radius = bounds.getSize(new THREE.Vector3()).length() / 2, scale = Math.max(0.2, Math.min(radius / 4, 2));
  const camera = new THREE.PerspectiveCamera(40, 1, radius / 100, radius * 100);
  camera.up.set(0, 0, 1);
  placeCamera(camera, centre, (1.15 * radius) / Math.sin((20 * Math.PI) / 180), radius);
  data.runs.forEach((run, i) => views.push(makeView(run, i, camera)));
  for (const v of views) {
    v.controls.target.copy(centre);
    v.controls.update();
    v.controls.addEventListener("change", () => render(camera, scale));
    v.canvas.addEventListener("click", (e) => pick(v, camera, e.clientX, e.clientY));
  }
  const slider = document.getElementById("slider");
  slider.max = data.runs[0].frames - 1;
  slider.addEventListener("input", () => { state.t = data.runs[0].times[Number(slider.value)]; render(camera, scale); });
  document.getElementById("speed").addEventListener("change", (e) => { state.speed = Number(e.target.value); });
  document.getElementById("showContacts").addEventListener("change", (e) => {
    state.showContacts = e.target.checked;
    for (const v of views) v.frame = -1;  // redrawn with or without them
    render(camera, scale);
  });
  document.getElementById("timeline").addEventListener("click", (e) => {
    state.t = (e.offsetX / e.target.clientWidth) * state.end;
    render(camera, scale);
  });
  const play = document.getElementById("play");
  play.addEventListener("click", () => {
    state.playing = !state.playing;
    if (state.playing && state.t >= state.end) state.t = 0;
    play.textContent = state.playing ? "pause" : "play";
    state.last = null;
  });
  // #t=1.5 opens the page at that time (links, tests); #play starts playing; #contacts=0
  // hides the contacts; #size and #click below.
  const hash = new URLSearchParams(location.hash.slice(1));
  if (hash.has("t")) state.t = Math.min(state.end, Math.max(0, Number(hash.get("t"))));
  if (hash.has("contacts")) document.getElementById("showContacts").checked = state.showContacts = hash.get("contacts") !== "0";
  if (hash.has("size")) {  // #size=800x400: views of a fixed size (screenshots, tests), whatever the window
    const [w, h] = hash.get("size").split("x").map(Number);
    document.getElementById("views").style.height = `${h}px`;
    for (const v of views) v.element.style.flex = `0 0 ${w}px`;
  }
  window.addEventListener("resize", () => { resize(camera); render(camera, scale); });
  resize(camera);
  render(camera, scale);
  if (hash.has("click")) {  // #click=x,y: a click at that page pixel of the first view (tests)
    const [x, y] = hash.get("click").split(",").map(Number);
    pick(views[0], camera, x, y);
    writeTestState(camera);
  }
  if (hash.has("play")) play.click();
  const tick = (now) => {
    if (state.playing) {
      if (state.last !== null) state.t = Math.min(state.end, state.t + ((now - state.last) / 1000) * state.speed);
      state.last = now;
      if (state.t >= state.end) play.click();
      render(camera, scale);
    }
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

start();
