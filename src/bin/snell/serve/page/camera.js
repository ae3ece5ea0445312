// Moving the camera: a drag orbits it around the point looked at, the wheel moves it in
// and out, each move sent to the server (at most every 80 ms while it goes on); a press
// that does not move is a click, explained. The copy button gives the camera as a
// `[camera]` table to paste into the scene; the reset button goes back to the file's.

import { $, state } from './state.js';
import { pixelAt, explain } from './explain.js';

let camera = null;      // the camera the page has moved to during a drag
let lastSent = 0;       // when the camera was last sent
let sendTimer = 0;

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

// ---- The mouse: press on the picture, move and release anywhere, the wheel --------------
export function pressed(e) {
  const status = state.status;
  if (e.button !== 0 || !status || !status.camera) return;
  e.preventDefault();
  state.drag = { x: e.clientX, y: e.clientY, moved: false, start: status.camera };
}

export function moved(e) {
  const drag = state.drag;
  if (!drag) return;
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  if (!drag.moved && Math.hypot(dx, dy) < 4) return;
  drag.moved = true;
  $('hover').hidden = true;
  camera = orbit(drag.start, dx, dy);
  sendCamera(false);
}

export function released(e) {
  if (!state.drag) return;
  const was = state.drag;
  state.drag = null;
  if (was.moved) { sendCamera(true); return; }
  const p = pixelAt(e);
  if (p) explain(p);
}

export function wheel(e) {
  const status = state.status;
  if (!status || !status.camera) return;
  e.preventDefault();
  const cam = camera && status.camera_moved ? camera : status.camera;
  const off = sub(cam.position, cam.look_at);
  const k = Math.exp(Math.max(-1, Math.min(1, e.deltaY * 0.0015)));
  if (Math.hypot(...off) * k < 1e-3) return;
  camera = { ...cam, position: add(cam.look_at, scale(off, k)) };
  sendCamera(false);
}

// ---- The buttons --------------------------------------------------------------------------
function cameraToml(c) {
  const v = (a) => `[${a.map((x) => Number(x.toPrecision(6))).join(', ')}]`;
  return `[camera]\nposition = ${v(c.position)}\nlook_at = ${v(c.look_at)}\nup = ${v(c.up)}\nfov = ${Number(c.fov.toPrecision(6))}\n`;
}

export async function copyCamera() {
  const status = state.status;
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
}

export function resetCamera() {
  camera = null;
  fetch('/camera/reset', { method: 'POST' });
}
