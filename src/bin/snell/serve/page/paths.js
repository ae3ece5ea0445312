// A clicked pixel's light by the kind of path that brought it (`/paths`): a bar of the
// kinds' shares, and a few sampled paths of each kind drawn over a view of the scene from
// above and one from the side, each vertex's BSDF, pdf, MIS weight and throughput on hover.

import { $, SVG, fmt } from './state.js';

// One colour per kind, in the server's order (snell::lpe::pixel::KINDS).
const COLORS = ['#f2c94c', '#e86f3a', '#b05cd6', '#3fa35b', '#3a8ee8', '#36c3c3'];

function el(name, attrs, parent) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.append(e);
  return e;
}

// The bar: one segment per kind with light, as wide as its share, and a legend.
function bar(doc, box) {
  const b = document.createElement('div');
  b.className = 'paths-bar';
  const legend = document.createElement('ul');
  legend.className = 'paths-legend';
  doc.kinds.forEach((k, i) => {
    if (k.share <= 0.0005) return;
    const seg = document.createElement('span');
    seg.className = 'paths-segment';
    seg.style.width = `${100 * k.share}%`;
    seg.style.background = COLORS[i];
    seg.dataset.kind = k.name;
    seg.dataset.share = String(k.share);
    seg.title = `${k.name} (${k.expr}): ${fmt(100 * k.share, 1)} %`;
    b.append(seg);
    const li = document.createElement('li');
    const sw = document.createElement('span');
    sw.className = 'swatch';
    sw.style.background = COLORS[i];
    li.append(sw, `${fmt(100 * k.share, 1)} % ${k.name} `);
    const code = document.createElement('code');
    code.textContent = k.expr;
    li.append(code);
    legend.append(li);
  });
  box.append(b, legend);
}

// What hovering a vertex says.
function vertexText(v) {
  const lines = [`vertex ${v.depth}: ${v.object} (${v.material}), ${v.bsdf}`,
    `throughput (${v.throughput.map((x) => fmt(x, 3)).join(', ')})`];
  if (v.bounce) lines.push(`bounce: ${v.bounce.lobe}, pdf ${fmt(v.bounce.pdf, 4)}`);
  if (v.light) lines.push(`light sample: pdf ${fmt(v.light.light_pdf, 4)}, BSDF pdf ${fmt(v.light.bsdf_pdf, 4)}, MIS weight ${fmt(v.light.mis_weight, 3)}${v.light.blocked ? `, ${v.light.blocked}` : ''}`);
  if (v.emission) lines.push(`emission: MIS weight ${fmt(v.emission.mis_weight, 3)}`);
  lines.push(`adds (${v.contribution.map((x) => fmt(x, 4)).join(', ')})`);
  return lines.join('\n');
}

// One view of the scene: axes `a` (right) and `b` (up) of world space.
function view(doc, title, a, b, box) {
  const W = 220, H = 220, pad = 10;
  const pts = [doc.camera];
  for (const o of doc.objects) pts.push(o.min, o.max);
  for (const l of doc.lights) pts.push(l);
  for (const p of doc.paths) for (const v of p.vertices) pts.push(v.point);
  const lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (const p of pts) {
    lo[0] = Math.min(lo[0], p[a]); hi[0] = Math.max(hi[0], p[a]);
    lo[1] = Math.min(lo[1], p[b]); hi[1] = Math.max(hi[1], p[b]);
  }
  const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-6);
  const X = (p) => pad + (p[a] - lo[0]) / span * (W - 2 * pad);
  const Y = (p) => H - pad - (p[b] - lo[1]) / span * (H - 2 * pad);
  const fig = document.createElement('figure');
  const cap = document.createElement('figcaption');
  cap.textContent = title;
  const svg = el('svg', { class: 'paths-view', viewBox: `0 0 ${W} ${H}`, width: W, height: H });
  for (const o of doc.objects) {
    const r = el('rect', {
      class: 'paths-object',
      x: Math.min(X(o.min), X(o.max)), y: Math.min(Y(o.min), Y(o.max)),
      width: Math.max(1, Math.abs(X(o.max) - X(o.min))), height: Math.max(1, Math.abs(Y(o.max) - Y(o.min))),
    }, svg);
    el('title', {}, r).textContent = o.name;
  }
  for (const l of doc.lights) el('circle', { class: 'paths-light', cx: X(l), cy: Y(l), r: 4 }, svg);
  el('circle', { class: 'paths-camera', cx: X(doc.camera), cy: Y(doc.camera), r: 4 }, svg);
  for (const p of doc.paths) {
    const color = COLORS[p.kind];
    const chain = [doc.camera, ...p.vertices.map((v) => v.point)];
    el('polyline', {
      class: 'paths-path', stroke: color,
      points: chain.map((q) => `${X(q)},${Y(q)}`).join(' '),
    }, svg);
    for (const v of p.vertices) {
      if (v.light && !v.light.blocked && v.light.distance) {
        const d = Math.min(v.light.distance, span);
        const to = v.point.map((x, i) => x + v.light.direction[i] * d);
        el('line', { class: 'paths-shadow', stroke: color, x1: X(v.point), y1: Y(v.point), x2: X(to), y2: Y(to) }, svg);
      }
      const c = el('circle', { class: 'paths-vertex', fill: color, cx: X(v.point), cy: Y(v.point), r: 3 }, svg);
      el('title', {}, c).textContent = vertexText(v);
    }
  }
  fig.append(svg, cap);
  box.append(fig);
}

// Asks the server how pixel `p`'s light is made, and shows it.
export async function explainPaths(p) {
  const box = $('paths');
  box.replaceChildren();
  const r = await fetch(`/paths?x=${p[0]}&y=${p[1]}`);
  if (!r.ok) {
    const note = document.createElement('p');
    note.className = 'hint';
    note.textContent = await r.text();
    box.append(note);
    return;
  }
  const doc = await r.json();
  const h = document.createElement('h3');
  h.textContent = `Its light, by kind of path (the path tracer's, ${doc.samples} samples)`;
  box.append(h);
  if (doc.kinds.every((k) => k.share <= 0)) {
    const note = document.createElement('p');
    note.className = 'hint';
    note.textContent = 'No path brought this pixel any light: it is black to the path tracer.';
    box.append(note);
  }
  bar(doc, box);
  const views = document.createElement('div');
  views.className = 'paths-views';
  view(doc, 'from above (x right, z up)', 0, 2, views);
  view(doc, 'from the side (x right, y up)', 0, 1, views);
  box.append(views);
  box.dataset.pixel = `${p[0]},${p[1]}`;
}
