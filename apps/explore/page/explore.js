// pelage explore: the page. It draws the server's mesh with the latest type texture
// (apps/explore/pattern_texture.h) through a palette of the preset's colours, builds
// its panel from the preset's own keys, and sends every change to the server, which
// checks it with the preset parser and grows it. Colour-only changes repaint at once.
import * as THREE from './three/build/three.module.js';
import { OrbitControls } from './three/examples/jsm/controls/OrbitControls.js';

const MAX_TYPES = 8;

// The preset parser's ranges (sim/mosaic/cell_types.cpp), for the controls' own checks;
// the server checks every change again with the parser itself. `slider` is the range a
// slider covers (the value may go beyond it by typing).
const SIMULATION = {
  initial_spacing: { min: 0, max: 1, minOpen: true, slider: [0.002, 0.05], note: 'of the body length' },
  initial_cells: { min: 0, max: 1e9, integer: true, slider: [100, 200000] },
  initial_density: { min: 0, minOpen: true, slider: [100, 200000] },
  w_r: { min: 0, minOpen: true, slider: [0.5, 10], note: 'repulsion radius' },
  w_d: { min: 0, minOpen: true, slider: [0.005, 0.5], note: 'step size' },
  w_a: { min: 0, max: 1, slider: [0, 1], note: 'anisotropy weight' },
  rho: { min: 0, minOpen: true, slider: [1, 60], note: 'steps per time unit' },
  end_time: { min: 0, slider: [0, 300] },
  target_cells: { min: 0, max: 1e9, integer: true, slider: [0, 500000] },
  relax: { choices: ['local', 'global'] },
  local_steps: { min: 1, max: 100000, integer: true, slider: [1, 16] },
  division_distribution: { choices: ['poisson', 'exponential'] },
  child_radius_factor: { min: 0, minOpen: true, max: 1, slider: [0.001, 0.1] },
  initial_relax_steps: { min: 0, max: 100000, integer: true, slider: [0, 200] },
  initial_relax_alpha: { min: 0, max: 1, maxOpen: true, slider: [0, 0.99] },
  initial_relax_tolerance: { min: 0, slider: [0, 0.1] },
  initial_weight: { min: 0, minOpen: true, slider: [0.1, 10] },
};
const TYPE_KEYS = {
  division_time: { min: 0, minOpen: true, slider: [1, 300], never: true },
  initial_probability: { min: 0, max: 1, slider: [0, 1] },
  eumelanin: { min: 0, slider: [0, 2] },
  pheomelanin: { min: 0, slider: [0, 2] },
};
// Blocks shown as JSON to edit where a preset has them.
const JSON_BLOCKS = ['regions', 'masks', 'growth'];

const state = {
  preset: null,
  seed: 1,
  version: 0,
  meshVersion: 0,
  textureVersion: 0,
  job: 0,
  changedAt: null,   // when the change being sent was made (performance.now())
  sentAt: null,      // ... the last simulating one, until its first pattern shows
  sentJob: null,
  timings: [],       // change → first pattern shown, ms, per simulating change
};
window.pelage = state;  // for tests and the curious

// --- 3D view ---
const canvas = document.getElementById('canvas');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x2b2e33);
const camera = new THREE.PerspectiveCamera(32, 1, 0.01, 100);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = true;
let texture = null;
const palette = [];
for (let i = 0; i < MAX_TYPES; ++i) palette.push(new THREE.Vector3(0.5, 0.5, 0.5));
const material = new THREE.ShaderMaterial({
  uniforms: {
    types: { value: null },
    palette: { value: palette },
    light: { value: new THREE.Vector3(0.4, 0.8, 0.45).normalize() },
  },
  vertexShader: `
    varying vec2 vUv;
    varying vec3 vNormal;
    void main() {
      vUv = uv;
      vNormal = normalize(normal);
      gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
    }`,
  // The texel's type (nearest filtering: the sample of the fragment's own triangle)
  // through the palette (linear RGB), lit by a sun and a sky, shown as sRGB.
  fragmentShader: `
    uniform sampler2D types;
    uniform vec3 palette[${MAX_TYPES}];
    uniform vec3 light;
    varying vec2 vUv;
    varying vec3 vNormal;
    void main() {
      int t = int(floor(texture2D(types, vUv).r * 255.0 + 0.5));
      vec3 albedo = vec3(0.35);
      for (int i = 0; i < ${MAX_TYPES}; ++i)
        if (i == t) albedo = palette[i];
      vec3 n = normalize(vNormal);
      float sun = max(dot(n, light), 0.0);
      float sky = 0.5 + 0.5 * n.y;
      vec3 c = albedo * (0.75 * sun + 0.45 * sky);
      gl_FragColor = vec4(pow(clamp(c, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
    }`,
});
let mesh = null;

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}
// Drawn only when something changed (the view moved, a texture or colour arrived): a
// page drawn in software would otherwise take a core from the simulation.
let framePending = false;
function redraw() {
  if (framePending) return;
  framePending = true;
  requestAnimationFrame(frame);
}
function frame() {
  framePending = false;
  resize();
  const moving = controls.update();  // true while the view glides to a stop
  renderer.render(scene, camera);
  if (moving) redraw();
}
controls.addEventListener('change', redraw);
state.controls = controls;  // for tests and the curious
state.redraw = redraw;
window.addEventListener('resize', redraw);
redraw();

// The whole mesh in view, as `pelage look` frames it: seen from the front right and a
// little above, the camera as near as leaves 8 % of the canvas's half-size free around
// every vertex. A vertex q (from the target) at depth d − q·dir fits when
// |q·right| ≤ 0.92 tanH (d − q·dir), and likewise upwards: the nearest such d, closed form.
function fitView(g) {
  resize();
  const s = g.boundingSphere;
  const dir = new THREE.Vector3(1.6, 0.6, 2.6).normalize();
  const right = new THREE.Vector3().crossVectors(camera.up, dir).normalize();
  const up = new THREE.Vector3().crossVectors(dir, right);
  const tanV = 0.92 * Math.tan(camera.fov / 2 * Math.PI / 180), tanH = tanV * camera.aspect;
  const pos = g.attributes.position, q = new THREE.Vector3();
  let distance = 1.05 * s.radius;  // outside the mesh, whatever its shape
  for (let i = 0; i < pos.count; ++i) {
    q.fromBufferAttribute(pos, i).sub(s.center);
    distance = Math.max(distance, q.dot(dir) + Math.max(Math.abs(q.dot(right)) / tanH,
                                                        Math.abs(q.dot(up)) / tanV));
  }
  controls.target.copy(s.center);
  camera.position.copy(s.center).addScaledVector(dir, distance);
  camera.near = s.radius / 100;
  camera.far = distance + s.radius * 100;
  camera.updateProjectionMatrix();
}

async function loadMesh() {
  const r = await fetch('api/mesh');
  if (!r.ok) return;
  const version = Number(r.headers.get('X-Pelage-Version'));
  const buf = await r.arrayBuffer();
  const n = new Uint32Array(buf, 0, 1)[0];
  const pos = new Float32Array(buf, 4, 9 * n);
  const nrm = new Float32Array(buf, 4 + 36 * n, 9 * n);
  const uv = new Float32Array(buf, 4 + 72 * n, 6 * n);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(nrm, 3));
  g.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
  g.computeBoundingSphere();
  if (mesh) { scene.remove(mesh); mesh.geometry.dispose(); }
  mesh = new THREE.Mesh(g, material);
  scene.add(mesh);
  fitView(g);
  state.mesh = mesh;  // for tests
  state.meshVersion = version;
  redraw();
}

async function loadTexture(status) {
  const r = await fetch('api/texture');
  if (!r.ok) return;
  const version = Number(r.headers.get('X-Pelage-Version'));
  const bytes = new Uint8Array(await r.arrayBuffer());
  const size = status.texture_size;
  if (!texture || texture.image.width !== size) {
    if (texture) texture.dispose();
    texture = new THREE.DataTexture(bytes, size, size, THREE.LuminanceFormat,
                                    THREE.UnsignedByteType);
    texture.magFilter = THREE.NearestFilter;
    texture.minFilter = THREE.NearestFilter;
    texture.generateMipmaps = false;
    texture.flipY = false;
    material.uniforms.types.value = texture;
  } else {
    texture.image.data = bytes;
  }
  texture.needsUpdate = true;
  state.textureVersion = version;
  redraw();
  if (state.sentAt !== null && status.texture_job === state.sentJob) {
    // Shown once the browser has drawn it.
    const sent = state.sentAt;
    state.sentAt = null;
    requestAnimationFrame(() => requestAnimationFrame(() => {
      state.timings.push(performance.now() - sent);
      showTiming();
    }));
  }
}

// --- Colours: the preset's are linear RGB, a colour input's are sRGB ---
const toSrgb = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055);
const toLinear = (c) => (c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4));
function hexOf(rgb) {
  return '#' + rgb.map((c) => Math.round(255 * Math.min(1, Math.max(0, toSrgb(c))))
    .toString(16).padStart(2, '0')).join('');
}
function linearOf(hex) {
  return [1, 3, 5].map((i) => Number(toLinear(parseInt(hex.substr(i, 2), 16) / 255).toFixed(4)));
}
function applyPalette() {
  const types = state.preset ? state.preset.types : [];
  for (let i = 0; i < MAX_TYPES; ++i) {
    const c = types[i] ? (types[i].colour || types[i].color) : null;
    if (c) palette[i].set(c[0], c[1], c[2]);
  }
  redraw();
}

// --- The panel, built from the preset ---
const controlsDiv = document.getElementById('controls');
const errorDiv = document.getElementById('error');

// The parser's check of one number; '' when it passes.
function rangeMessage(v, spec) {
  if (typeof v !== 'number' || !Number.isFinite(v)) return 'expected a number';
  if (spec.integer && !Number.isInteger(v)) return 'must be an integer';
  if (spec.min !== undefined && (spec.minOpen ? !(v > spec.min) : v < spec.min))
    return `must be ${spec.minOpen ? '>' : '>='} ${spec.min}`;
  if (spec.max !== undefined && (spec.maxOpen ? !(v < spec.max) : v > spec.max))
    return `must be ${spec.maxOpen ? '<' : '<='} ${spec.max}`;
  return '';
}

function row(label, id) {
  const r = document.createElement('div');
  r.className = 'row';
  const l = document.createElement('label');
  l.textContent = label;
  if (id) l.htmlFor = id;
  r.appendChild(l);
  return r;
}

// A number with a slider: `get`/`set` read and write the preset.
function numberControl(parent, label, id, spec, get, set) {
  const r = row(label, id);
  const value = get();
  const slider = document.createElement('input');
  slider.type = 'range';
  slider.id = id + '-slider';
  const [lo, hi] = spec.slider;
  slider.min = lo; slider.max = hi;
  slider.step = spec.integer ? 1 : (hi - lo) / 1000;
  slider.value = typeof value === 'number' ? value : lo;
  const box = document.createElement('input');
  box.type = 'number';
  box.id = id;
  box.step = 'any';
  box.value = value;
  const hint = document.createElement('div');
  hint.className = 'hint';
  const take = (text, from) => {
    let v = text === 'never' && spec.never ? 'never' : Number(text);
    if (spec.integer && typeof v === 'number') v = Math.round(v);
    const message = v === 'never' ? '' : rangeMessage(v, spec);
    box.classList.toggle('invalid', message !== '');
    hint.textContent = message ? `${label}: ${message}` : '';
    if (message) return;
    if (from !== box) box.value = v;
    if (from !== slider && typeof v === 'number') slider.value = v;
    set(v);
    changed();
  };
  slider.addEventListener('input', () => take(slider.value, slider));
  box.addEventListener('change', () => take(box.value, box));
  r.appendChild(slider);
  r.appendChild(box);
  parent.appendChild(r);
  parent.appendChild(hint);
}

function choiceControl(parent, label, id, choices, get, set) {
  const r = row(label, id);
  const s = document.createElement('select');
  s.id = id;
  for (const c of choices) {
    const o = document.createElement('option');
    o.value = o.textContent = c;
    s.appendChild(o);
  }
  s.value = get();
  s.addEventListener('change', () => { set(s.value); changed(); });
  r.appendChild(s);
  parent.appendChild(r);
}

function jsonControl(parent, label, id, get, set) {
  const h = document.createElement('h3');
  h.textContent = label;
  parent.appendChild(h);
  const t = document.createElement('textarea');
  t.id = id;
  t.rows = 6;
  t.value = JSON.stringify(get(), null, 1);
  t.addEventListener('change', () => {
    try {
      set(JSON.parse(t.value));
      t.classList.remove('invalid');
      changed();
    } catch (e) {
      t.classList.add('invalid');
      errorDiv.textContent = `${label}: not valid JSON (${e.message})`;
    }
  });
  parent.appendChild(t);
}

function matrixControl(parent, label, id, matrix) {
  const h = document.createElement('h3');
  h.textContent = label;
  parent.appendChild(h);
  const grid = document.createElement('div');
  grid.className = 'matrix';
  grid.style.gridTemplateColumns = `repeat(${matrix.length}, auto)`;
  matrix.forEach((rowValues, i) => rowValues.forEach((v, j) => {
    const box = document.createElement('input');
    box.type = 'number';
    box.id = `${id}-${i}-${j}`;
    box.step = 0.05; box.min = 0; box.max = 1;
    box.value = v;
    box.title = `${label}[${i}][${j}]`;
    box.addEventListener('change', () => {
      const x = Number(box.value);
      const message = rangeMessage(x, { min: 0, max: 1 });
      box.classList.toggle('invalid', message !== '');
      if (message) { errorDiv.textContent = `${label}[${i}][${j}]: ${message}`; return; }
      matrix[i][j] = x;
      changed();
    });
    grid.appendChild(box);
  }));
  parent.appendChild(grid);
}

function anisotropyControl(parent, sim) {
  const h = document.createElement('h3');
  h.textContent = 'anisotropy';
  parent.appendChild(h);
  const a = sim.anisotropy;
  const kinds = ['none', 'direction x', 'direction y', 'direction z', 'along body_axis',
                 'around body_axis'];
  const original = a && a.field && a.field.controls ? a.field : null;
  if (original) kinds.push('controls (the preset\'s)');
  const kindOf = () => {
    if (!sim.anisotropy) return 'none';
    const f = sim.anisotropy.field;
    const d = sim.anisotropy.direction || (f && f.direction);
    if (d) return d[0] ? 'direction x' : d[1] ? 'direction y' : 'direction z';
    if (f && f.along) return 'along body_axis';
    if (f && f.around) return 'around body_axis';
    if (f && f.controls) return 'controls (the preset\'s)';
    return 'none';
  };
  choiceControl(parent, 'field', 'sim-anisotropy-field', kinds, kindOf, (k) => {
    const magnitude = sim.anisotropy ? sim.anisotropy.magnitude : 1;
    if (k === 'none') { delete sim.anisotropy; sim.w_a = 0; return; }
    let field;
    if (k.startsWith('direction')) {
      field = { direction: [k.endsWith('x') ? 1 : 0, k.endsWith('y') ? 1 : 0, k.endsWith('z') ? 1 : 0] };
    } else if (k === 'along body_axis') field = { along: 'body_axis' };
    else if (k === 'around body_axis') field = { around: 'body_axis' };
    else field = original;
    sim.anisotropy = { field, magnitude: magnitude === undefined ? 1 : magnitude };
  });
  if (sim.anisotropy && typeof sim.anisotropy.magnitude !== 'object')
    numberControl(parent, 'magnitude', 'sim-anisotropy-magnitude',
                  { min: 0, slider: [0, 2] }, () => sim.anisotropy.magnitude ?? 1,
                  (v) => { sim.anisotropy.magnitude = v; });
}

function buildPanel() {
  const p = state.preset;
  controlsDiv.innerHTML = '';
  const types = document.createElement('div');
  const h = document.createElement('h2');
  h.textContent = 'cell types';
  types.appendChild(h);
  p.types.forEach((t, i) => {
    const title = document.createElement('h3');
    title.textContent = `type ${t.name}`;
    types.appendChild(title);
    const key = t.colour ? 'colour' : 'color';
    const r = row('colour', `type-${i}-colour`);
    const c = document.createElement('input');
    c.type = 'color';
    c.id = `type-${i}-colour`;
    c.value = hexOf(t[key]);
    c.addEventListener('input', () => { t[key] = linearOf(c.value); applyPalette(); changed(); });
    r.appendChild(c);
    types.appendChild(r);
    for (const [k, spec] of Object.entries(TYPE_KEYS)) {
      if (!(k in t) && k !== 'division_time' && k !== 'initial_probability') continue;
      if (typeof t[k] === 'object' && t[k] !== null)
        jsonControl(types, `${t.name} ${k}`, `type-${i}-${k}`, () => t[k], (v) => { t[k] = v; });
      else
        numberControl(types, k.replace('_', ' '), `type-${i}-${k}`, spec, () => t[k] ?? 0,
                      (v) => { t[k] = v; });
    }
  });
  controlsDiv.appendChild(types);

  const m = document.createElement('div');
  const mh = document.createElement('h2');
  mh.textContent = 'adhesion and mutation';
  m.appendChild(mh);
  for (const key of ['adhesion', 'repulsiveness', 'mutation']) {
    if (!(key in p)) continue;
    if (Array.isArray(p[key])) matrixControl(m, key, key, p[key]);
    else jsonControl(m, key, key, () => p[key], (v) => { p[key] = v; });
  }
  controlsDiv.appendChild(m);

  const s = document.createElement('div');
  const sh = document.createElement('h2');
  sh.textContent = 'simulation';
  s.appendChild(sh);
  const sim = p.simulation;
  for (const [k, spec] of Object.entries(SIMULATION)) {
    if (!(k in sim) && k !== 'w_a' && k !== 'relax') continue;
    const id = `sim-${k}`;
    if (spec.choices) {
      choiceControl(s, k, id, spec.choices, () => sim[k] ?? spec.choices[0], (v) => { sim[k] = v; });
    } else if (typeof sim[k] === 'object' && sim[k] !== null) {
      jsonControl(s, k, id, () => sim[k], (v) => { sim[k] = v; });
    } else {
      numberControl(s, k + (spec.note ? ` (${spec.note})` : ''), id, spec, () => sim[k] ?? 0,
                    (v) => { sim[k] = v; });
    }
  }
  anisotropyControl(s, sim);
  controlsDiv.appendChild(s);

  for (const key of JSON_BLOCKS)
    if (key in p) jsonControl(controlsDiv, key, `block-${key}`, () => p[key], (v) => { p[key] = v; });
}

// --- Talking to the server ---
let sendTimer = null;
function changed() {
  // A dragged slider sends at most every 150 ms; the server cancels the stale run.
  if (sendTimer) return;
  state.changedAt = performance.now();  // the wait the user sees starts here
  sendTimer = setTimeout(() => { sendTimer = null; send(); }, 150);
}

async function send() {
  const seed = Number(document.getElementById('seed').value);
  const sentAt = state.changedAt ?? performance.now();
  state.changedAt = null;
  const r = await fetch('api/preset', {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ preset: state.preset, seed }),
  });
  const j = await r.json();
  if (!r.ok) {
    errorDiv.textContent = j.error;
    return;
  }
  errorDiv.textContent = '';
  if (j.simulating) {
    state.sentAt = sentAt;
    state.sentJob = j.job;
  }
}

function showStats(status) {
  const s = status.stats;
  const table = document.getElementById('stats');
  document.getElementById('stats-stage').textContent =
    s ? `(${status.stats_stage === 'full' ? 'full scale' : 'preview'})` : '(growing…)';
  table.innerHTML = '';
  if (!s) return;
  const rows = [
    ['spot fraction by area', s.spot_fraction_by_area, 3, 'stat-spot-fraction'],
    ['spots', s.spot_count, 0, 'stat-spots'],
    ['neighbours per spot', s.spot_neighbours_mean, 2, 'stat-neighbours'],
    ['complexity', s.spot_complexity, 3, 'stat-complexity'],
    ['background components', s.background_components, 0, 'stat-background'],
    ['cells', s.cells, 0, 'stat-cells'],
  ];
  if ('stripe_alignment_median' in s)
    rows.push(['stripe alignment (median °)', s.stripe_alignment_median, 1, 'stat-stripes']);
  for (const [name, v, digits, id] of rows) {
    const tr = document.createElement('tr');
    tr.innerHTML = `<td>${name}</td><td id="${id}">${Number(v).toFixed(digits)}</td>`;
    table.appendChild(tr);
  }
}

function showTiming() {
  const t = state.timings;
  document.getElementById('timing').textContent = t.length
    ? `last change to first pattern: ${(t[t.length - 1] / 1000).toFixed(2)} s` : '';
}

async function poll() {
  for (;;) {
    let status;
    try {
      const r = await fetch(`api/status?after=${state.version}`);
      status = await r.json();
    } catch (e) {
      document.getElementById('stage').textContent = 'the server has stopped';
      await new Promise((res) => setTimeout(res, 2000));
      continue;
    }
    state.version = status.version;
    state.status = status;
    if (status.mesh_version !== state.meshVersion) await loadMesh();
    if (status.texture_version !== state.textureVersion) await loadTexture(status);
    if (!state.preset && status.preset) {
      state.preset = status.preset;
      document.getElementById('seed').value = status.seed;
      applyPalette();
      buildPanel();
    }
    document.getElementById('mesh-name').textContent = status.mesh;
    const stage = status.error ? `error: ${status.error}`
      : status.running ? `${status.stage === 'preview' ? 'preview scale' : 'full scale'}` +
        `${status.phase ? ': ' + status.phase : ''} — ${status.texture_cells || 0} cells`
      : `done — ${status.texture_cells} cells`;
    document.getElementById('stage').textContent = stage;
    document.getElementById('progress').style.width = `${100 * status.progress}%`;
    document.getElementById('render').disabled = !status.result_ready;
    document.getElementById('save').disabled = !status.result_ready;
    showStats(status);
  }
}

async function loadPresets() {
  const r = await fetch('api/presets');
  const j = await r.json();
  const select = document.getElementById('preset-select');
  const none = document.createElement('option');
  none.value = ''; none.textContent = '(current)';
  select.appendChild(none);
  for (const name of j.names) {
    const o = document.createElement('option');
    o.value = o.textContent = name;
    select.appendChild(o);
  }
  select.addEventListener('change', () => {
    if (!select.value) return;
    state.preset = JSON.parse(JSON.stringify(j.presets[select.value]));
    applyPalette();
    buildPanel();
    send();
  });
}

document.getElementById('seed').addEventListener('change', () => changed());

let renderPoll = null;
document.getElementById('render').addEventListener('click', async () => {
  const w = 480, h = 270;
  const r = await fetch('api/render', {
    method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ width: w, height: h, spp: 64 }),
  });
  const j = await r.json();
  const status = document.getElementById('render-status');
  if (!r.ok) { status.textContent = j.error; return; }
  let shown = -1;
  clearInterval(renderPoll);
  renderPoll = setInterval(async () => {
    const s = await (await fetch('api/render/status')).json();
    if (s.version !== shown && s.version > 0) {
      shown = s.version;
      const img = document.getElementById('render-image');
      img.src = `api/render.png?v=${s.version}`;
      img.style.display = 'block';
    }
    status.textContent = s.error ? s.error
      : `${s.spp} samples per pixel${s.rendering ? '…' : ''}`;
    if (!s.rendering) clearInterval(renderPoll);
  }, 400);
});

document.getElementById('save').addEventListener('click', async () => {
  const name = document.getElementById('save-name').value;
  const r = await fetch('api/save', {
    method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ name }),
  });
  const j = await r.json();
  document.getElementById('saved').textContent = r.ok
    ? `saved ${j.files.join(', ')}; render with pelage render ${j.files[2]}` : j.error;
  if (!r.ok) document.getElementById('saved').style.color = '#f77';
});

loadPresets();
poll();
