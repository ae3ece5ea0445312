// Pixels explained: the pixel under the pointer, the hover that names what is there (from
// `/pick`), and a click's `/explain` answer shown as a tree of rays beside the picture, its
// hit points drawn over the picture (a bidirectional sample's two subpaths and where its
// light paths land).

import { $, img, overlay, SVG, state, fmt } from './state.js';
import { explainPaths } from './paths.js';

let hoverTimer = 0;

// The pixel of the picture under a mouse event, or null off the picture.
export function pixelAt(e) {
  const status = state.status;
  if (!status || !status.size) return null;
  const r = img.getBoundingClientRect();
  const [w, h] = status.size;
  const x = Math.floor((e.clientX - r.left) / r.width * w);
  const y = Math.floor((e.clientY - r.top) / r.height * h);
  return x >= 0 && y >= 0 && x < w && y < h ? [x, y] : null;
}

// The pointer moved over the picture: once it rests, say what is under it.
export function hover(e) {
  if (state.drag) return;
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
}

export function hoverGone() { clearTimeout(hoverTimer); $('hover').hidden = true; }

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

// What a bidirectional strategy is: `s` vertices of the light's subpath joined to `t` of
// the eye's.
function strategy(o) {
  if (o.s === 0) return "the eye's path found the light";
  if (o.s === 1) return "a light sampled from the eye's path";
  if (o.t === 1) return "the light's path joined to the eye";
  return 'the two paths joined';
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
  if ('s' in o && 't' in o && 'weight' in o) return `(s=${o.s}, t=${o.t}) ${strategy(o)}, weight ${fmt(o.weight, 3)}`;
  if ('what' in o && 'point' in o) return `${name}: ${o.what}`;
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
      v.forEach((item, i) => tree(d, item, `${k} ${i}`, k === 'children' || k === 'vertices' || k === 'strategies'));
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

function line(a, b, cls) {
  const l = document.createElementNS(SVG, 'line');
  l.setAttribute('class', cls);
  l.setAttribute('x1', a[0]); l.setAttribute('y1', a[1]);
  l.setAttribute('x2', b[0]); l.setAttribute('y2', b[1]);
  overlay.append(l);
}

function dot(at, cls, r) {
  const d = document.createElementNS(SVG, 'circle');
  d.setAttribute('class', cls);
  d.setAttribute('cx', at[0]); d.setAttribute('cy', at[1]); d.setAttribute('r', r);
  overlay.append(d);
}

// A subpath as a chain of segments from `start` (null: its first vertex), each vertex the
// camera does not see leaving a gap.
function chain(vertices, start, cls) {
  let from = start;
  for (const v of vertices) {
    const at = Array.isArray(v.screen) ? v.screen : null;
    if (from && at) line(from, at, cls);
    if (at) dot(at, cls === 'ray' ? 'hit' : 'light-hit', 3);
    from = at;
  }
}

// What the picture shows of a bidirectional sample, in words: each part that is there.
function bdptDrawn(doc) {
  const parts = ["the eye's subpath (yellow)"];
  if (doc.light_path.length) parts.push(`the light's (blue; a light sampled from the eye's path is a point of its own)`);
  if (doc.strategies.some((s) => Array.isArray(s.lands_at))) parts.push('where its light paths joined to the eye land (rings)');
  return parts.join(', ');
}

// A bidirectional sample: the eye's subpath from the pixel, the light's from the light, and
// a ring where each of its light paths joined to the eye lands.
function drawBdpt(doc, start) {
  chain(doc.camera_path.slice(1), start, 'ray');
  chain(doc.light_path, null, 'light-ray');
  for (const st of doc.strategies) if (Array.isArray(st.lands_at)) dot(st.lands_at, 'lands', 4);
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
  if (doc.integrator === 'bdpt') { drawBdpt(doc, start); return; }
  const segs = [];
  points(doc.tree || doc.path, start, segs);
  for (const [a, b] of segs) line(a, b, 'ray');
  for (const [, b] of segs) dot(b, 'hit', 3);
}

// Asks the server why pixel `p` has its colour, and shows the answer.
export async function explain(p) {
  const r = await fetch(`/explain?x=${p[0]}&y=${p[1]}`);
  const box = $('tree');
  if (!r.ok) { box.textContent = await r.text(); return; }
  const doc = await r.json();
  const what = {
    path: () => `the path of sample ${doc.sample}`,
    bdpt: () => `bidirectional sample ${doc.sample}: ${bdptDrawn(doc)}`,
  }[doc.integrator]?.() || 'the ray through its centre';
  $('explain-hint').textContent = `Pixel (${p[0]}, ${p[1]}), ${what}: colour ${vec(doc.color)}.${doc.note ? ` (${doc.note})` : ''}`;
  box.replaceChildren();
  if (doc.integrator === 'bdpt') {
    const { strategies, camera_path, light_path } = doc;
    tree(box, { strategies, camera_path, light_path }, 'sample', true);
    if (!strategies.length) {
      const none = document.createElement('p');
      none.textContent = 'No strategy carried light: the sample adds nothing to any pixel.';
      box.append(none);
    }
  } else {
    tree(box, doc.tree || doc.path, doc.tree ? 'tree' : 'path', true);
  }
  box.dataset.pixel = `${p[0]},${p[1]}`;
  draw(doc, p);
  explainPaths(p);
}
