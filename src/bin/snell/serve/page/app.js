// snell serve's page: follows the server's status over server-sent events, shows the newest
// frame (only the newest: frames it could not keep up with are skipped), explains the pixel
// clicked, orbits the camera on drag. Plain JavaScript, no build step, nothing from outside.
'use strict';

const $ = (id) => document.getElementById(id);
const img = $('frame');
const overlay = $('overlay');
const SVG = 'http://www.w3.org/2000/svg';

let status = null;      // the server's latest status
let loading = false;    // a picture is on its way
let shownKey = '';      // what the picture shows now
let pendingKey = '';    // what it should show next
let drag = null;        // an orbit under way
let camera = null;      // the camera the page has moved to during a drag
let lastSent = 0;       // when the camera was last sent
let sendTimer = 0;
let hoverTimer = 0;

// ---- The picture -------------------------------------------------------------------
function pictureUrl() {
  const view = $('view').value;
  if (!status) return null;
  if (view !== 'picture') return `/view/${view}.png?g=${status.generation}`;
  if (!status.frame) return null;
  return `/frame.jpg?id=${status.frame.id}&exposure=${$('exposure').value}&tone=${$('tone').value}`;
}

function showPicture() {
  const url = pictureUrl();
  if (!url || url === shownKey) return;
  if (loading) { pendingKey = url; return; }
  loading = true;
  pendingKey = '';
  const next = new Image();
  next.onload = () => {
    img.src = next.src;
    img.width = next.naturalWidth;
    img.height = next.naturalHeight;
    shownKey = url;
    img.dataset.frame = status && status.frame ? String(status.frame.id) : '';
    img.dataset.loaded = String(Number(img.dataset.loaded || 0) + 1);
    overlay.setAttribute('viewBox', `0 0 ${next.naturalWidth} ${next.naturalHeight}`);
    loading = false;
    if (pendingKey && pendingKey !== shownKey) showPicture();
  };
  next.onerror = () => { loading = false; };
  next.src = url;
}

function fmt(n, digits) { return Number(n).toFixed(digits); }

// The exposure and curve the scene renders its PNG with, as last applied to the controls:
// the page starts from them and follows the file when they change there; between changes
// the controls are the user's.
let sceneTone = '';
function followSceneTone() {
  if (!status.tone) return;
  const key = `${status.tone.exposure} ${status.tone.curve}`;
  if (key === sceneTone) return;
  sceneTone = key;
  const e = $('exposure');
  const v = Number(status.tone.exposure);
  e.min = String(Math.min(-5, Math.floor(v)));
  e.max = String(Math.max(5, Math.ceil(v)));
  e.value = String(v);
  $('exposure-value').textContent = fmt(v, 1);
  $('tone').value = status.tone.curve;
}

function showStatus() {
  $('scene').textContent = status.scene;
  followSceneTone();
  const f = status.frame;
  if (f) {
    const rays = f.rays_per_second >= 1e6 ? `${fmt(f.rays_per_second / 1e6, 1)} M rays/s` : `${fmt(f.rays_per_second / 1e3, 0)} k rays/s`;
    $('progress').textContent = `${status.integrator} · ${f.width} × ${f.height} · ${f.spp} / ${status.target_spp} spp · ${rays} · ${fmt(f.elapsed, 2)} s${f.done ? ' · done' : ''}`;
  }
  const error = $('error');
  if (status.error) {
    error.textContent = status.error;
    error.hidden = false;
  } else {
    error.hidden = true;
    error.textContent = '';
  }
  $('reset-camera').disabled = !status.camera_moved;
  showPicture();
}

const events = new EventSource('/events');
events.addEventListener('status', (e) => {
  status = JSON.parse(e.data);
  showStatus();
});
events.onerror = () => { $('progress').textContent = 'the server is not answering (is snell serve still running?)'; };

$('view').addEventListener('change', showPicture);
$('tone').addEventListener('change', showPicture);
$('exposure').addEventListener('input', () => {
  $('exposure-value').textContent = fmt($('exposure').value, 1);
  showPicture();
});

// ---- Pixels under the pointer ----------------------------------------------------------
function pixelAt(e) {
  if (!status || !status.size) return null;
  const r = img.getBoundingClientRect();
  const [w, h] = status.size;
  const x = Math.floor((e.clientX - r.left) / r.width * w);
  const y = Math.floor((e.clientY - r.top) / r.height * h);
  return x >= 0 && y >= 0 && x < w && y < h ? [x, y] : null;
}

img.addEventListener('mousemove', (e) => {
  if (drag) return;
  clearTimeout(hoverTimer);
  const p = pixelAt(e);
  const box = $('frame-box').getBoundingClientRect();
  const hover = $('hover');
  hover.style.left = `${e.clientX - box.left + 14}px`;
  hover.style.top = `${e.clientY - box.top + 14}px`;
  if (!p) { hover.hidden = true; return; }
  hoverTimer = setTimeout(async () => {
    const r = await fetch(`/pick?x=${p[0]}&y=${p[1]}`);
    if (!r.ok) return;
    const pick = await r.json();
    hover.textContent = pick.object
      ? `${pick.object} · ${pick.material} · (${p[0]}, ${p[1]})`
      : `background · (${p[0]}, ${p[1]})`;
    hover.hidden = false;
  }, 80);
});
img.addEventListener('mouseleave', () => { clearTimeout(hoverTimer); $('hover').hidden = true; });

// ---- Why this colour ---------------------------------------------------------------------
function swatch(c) {
  const s = document.createElement('span');
  s.className = 'swatch';
  const enc = (v) => Math.round(255 * Math.min(1, Math.max(0, v)) ** (1 / 2.2));
  s.style.background = `rgb(${enc(c[0])}, ${enc(c[1])}, ${enc(c[2])})`;
  return s;
}

function vec(v) { return `(${v.map((x) => fmt(x, 3)).join(', ')})`; }

function value(v) {
  if (Array.isArray(v) && v.every((x) => typeof x === 'number')) return vec(v);
  if (typeof v === 'number') return String(Math.round(v * 1e5) / 1e5);
  if (v === null) return '—';
  return String(v);
}

function kv(parent, k, v) {
  const d = document.createElement('div');
  d.className = 'kv';
  const key = document.createElement('span');
  key.className = 'k';
  key.textContent = `${k}: `;
  d.append(key, value(v));
  parent.append(d);
}

// A summary line for an object of the explain data.
function title(o, name) {
  if (o.kind && 'depth' in o) {
    const where = o.hit ? `hits ${o.hit.object} (${o.hit.material})` : 'leaves the scene';
    return `${o.kind} ray, depth ${o.depth}: ${where}`;
  }
  if ('object' in o && 'bsdf' in o) return `vertex ${o.depth}: ${o.object} (${o.material}), ${o.bsdf}`;
  if ('blocked_by' in o || 'crossings' in o) return o.blocked_by ? `shadow: blocked by ${o.blocked_by}` : 'shadow';
  if ('light' in o && 'contribution' in o && 'direction' in o) return `light ${o.light}${o.what ? ` (${o.what})` : ''}`;
  return name;
}

function tree(parent, o, name, open) {
  const d = document.createElement('details');
  d.open = open;
  const s = document.createElement('summary');
  const what = document.createElement('span');
  what.className = 'what';
  what.textContent = title(o, name);
  s.append(what);
  const color = o.color || o.contribution;
  if (Array.isArray(color)) { s.append(' '); s.append(swatch(color)); s.append(vec(color)); }
  d.append(s);
  for (const [k, v] of Object.entries(o)) {
    // Drawn on the picture, said in the title, or nothing to say.
    if (k === 'screen' || v === null || (Array.isArray(v) && v.length === 0)) continue;
    if (Array.isArray(v) && v.length && typeof v[0] === 'object' && v[0] !== null) {
      v.forEach((item, i) => tree(d, item, `${k} ${i}`, k === 'children' || k === 'vertices'));
    } else if (v && typeof v === 'object' && !Array.isArray(v)) {
      tree(d, v, k, k === 'hit' || k === 'tree' || k === 'path');
    } else {
      kv(d, k, v);
    }
  }
  parent.append(d);
}

// The hit points of the explain data, each with the point of the ray it came from.
function points(o, from, out) {
  if (Array.isArray(o)) { o.forEach((v) => points(v, from, out)); return; }
  if (!o || typeof o !== 'object') return;
  let here = from;
  if (Array.isArray(o.screen)) {
    out.push([from, o.screen]);
    here = o.screen;
  }
  for (const [k, v] of Object.entries(o)) {
    if (k === 'screen') continue;
    // A hit's children leave from the hit.
    const next = k === 'children' && o.hit && Array.isArray(o.hit.screen) ? o.hit.screen : here;
    points(v, next, out);
  }
}

function draw(doc, pixel) {
  overlay.replaceChildren();
  const start = [pixel[0] + 0.5, pixel[1] + 0.5];
  const mark = document.createElementNS(SVG, 'rect');
  mark.setAttribute('class', 'pixel');
  mark.setAttribute('x', pixel[0] - 2);
  mark.setAttribute('y', pixel[1] - 2);
  mark.setAttribute('width', 5);
  mark.setAttribute('height', 5);
  overlay.append(mark);
  const segs = [];
  points(doc.tree || doc.path, start, segs);
  for (const [a, b] of segs) {
    const line = document.createElementNS(SVG, 'line');
    line.setAttribute('class', 'ray');
    line.setAttribute('x1', a[0]); line.setAttribute('y1', a[1]);
    line.setAttribute('x2', b[0]); line.setAttribute('y2', b[1]);
    overlay.append(line);
  }
  for (const [, b] of segs) {
    const dot = document.createElementNS(SVG, 'circle');
    dot.setAttribute('class', 'hit');
    dot.setAttribute('cx', b[0]); dot.setAttribute('cy', b[1]); dot.setAttribute('r', 3);
    overlay.append(dot);
  }
}

async function explain(p) {
  const r = await fetch(`/explain?x=${p[0]}&y=${p[1]}`);
  const box = $('tree');
  if (!r.ok) { box.textContent = await r.text(); return; }
  const doc = await r.json();
  $('explain-hint').textContent = `Pixel (${p[0]}, ${p[1]}), ${doc.integrator === 'path' ? `the path of sample ${doc.sample}` : 'the ray through its centre'}: colour ${vec(doc.color)}.`;
  box.replaceChildren();
  tree(box, doc.tree || doc.path, doc.tree ? 'tree' : 'path', true);
  box.dataset.pixel = `${p[0]},${p[1]}`;
  draw(doc, p);
}

// ---- Camera ------------------------------------------------------------------------------
const sub = (a, b) => a.map((x, i) => x - b[i]);
const add = (a, b) => a.map((x, i) => x + b[i]);
const scale = (a, k) => a.map((x) => x * k);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => scale(a, 1 / Math.hypot(...a));

// `v` turned by `angle` about the unit axis `k` (Rodrigues).
function rotate(v, k, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  return add(add(scale(v, c), scale(cross(k, v), s)), scale(k, dot(k, v) * (1 - c)));
}

function orbit(cam, dx, dy) {
  const up = norm(cam.up);
  let off = sub(cam.position, cam.look_at);
  off = rotate(off, up, -dx * 0.006);
  const right = norm(cross(up, off));
  const pitched = rotate(off, right, dy * 0.006);
  // Not over the pole, where the roll would flip.
  if (Math.abs(dot(norm(pitched), up)) < 0.995) off = pitched;
  return { ...cam, position: add(cam.look_at, off) };
}

function sendCamera(final) {
  clearTimeout(sendTimer);
  const now = performance.now();
  if (!final && now - lastSent < 80) {
    sendTimer = setTimeout(() => sendCamera(true), 80);
    return;
  }
  lastSent = now;
  fetch('/camera', {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ position: camera.position, look_at: camera.look_at, up: camera.up, fov: camera.fov }),
  });
}

img.addEventListener('mousedown', (e) => {
  if (e.button !== 0 || !status || !status.camera) return;
  e.preventDefault();
  drag = { x: e.clientX, y: e.clientY, moved: false, start: status.camera };
});
window.addEventListener('mousemove', (e) => {
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  if (!drag.moved && Math.hypot(dx, dy) < 4) return;
  drag.moved = true;
  $('hover').hidden = true;
  camera = orbit(drag.start, dx, dy);
  sendCamera(false);
});
window.addEventListener('mouseup', (e) => {
  if (!drag) return;
  const was = drag;
  drag = null;
  if (was.moved) { sendCamera(true); return; }
  const p = pixelAt(e);
  if (p) explain(p);
});
img.addEventListener('wheel', (e) => {
  if (!status || !status.camera) return;
  e.preventDefault();
  const cam = camera && status.camera_moved ? camera : status.camera;
  const off = sub(cam.position, cam.look_at);
  const k = Math.exp(Math.max(-1, Math.min(1, e.deltaY * 0.0015)));
  if (Math.hypot(...off) * k < 1e-3) return;
  camera = { ...cam, position: add(cam.look_at, scale(off, k)) };
  sendCamera(false);
}, { passive: false });

function cameraToml(c) {
  const v = (a) => `[${a.map((x) => Number(x.toPrecision(6))).join(', ')}]`;
  return `[camera]\nposition = ${v(c.position)}\nlook_at = ${v(c.look_at)}\nup = ${v(c.up)}\nfov = ${Number(c.fov.toPrecision(6))}\n`;
}

$('copy-camera').addEventListener('click', async () => {
  if (!status || !status.camera) return;
  const text = cameraToml(status.camera);
  const box = $('camera-toml');
  box.value = text;
  box.hidden = false;
  try {
    await navigator.clipboard.writeText(text);
    $('copy-camera').textContent = 'Copied';
  } catch {
    box.select();
    $('copy-camera').textContent = 'Select and copy below';
  }
  setTimeout(() => { $('copy-camera').textContent = 'Copy camera'; }, 1500);
});
$('reset-camera').addEventListener('click', () => {
  camera = null;
  fetch('/camera/reset', { method: 'POST' });
});
