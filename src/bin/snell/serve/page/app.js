// snell serve's page, its entry module: it follows the server's status over server-sent
// events and wires the page's controls to the modules that do the work, one per concern:
// state.js (what they share), picture.js (the picture and the status line), explain.js
// (the hover and why a pixel has its colour), camera.js (orbit, zoom, copy and reset).
// Plain JavaScript modules, no build step, nothing from outside.

import { $, img, state } from './state.js';
import { showPicture, showStatus, exposureChanged } from './picture.js';
import { hover, hoverGone } from './explain.js';
import { pressed, moved, released, wheel, copyCamera, resetCamera } from './camera.js';

const events = new EventSource('/events');
events.addEventListener('status', (e) => {
  state.status = JSON.parse(e.data);
  showStatus();
});
events.onerror = () => { $('progress').textContent = 'the server is not answering (is snell serve still running?)'; };

$('view').addEventListener('change', showPicture);
$('tone').addEventListener('change', showPicture);
$('exposure').addEventListener('input', exposureChanged);

img.addEventListener('mousemove', hover);
img.addEventListener('mouseleave', hoverGone);

img.addEventListener('mousedown', pressed);
window.addEventListener('mousemove', moved);
window.addEventListener('mouseup', released);
img.addEventListener('wheel', wheel, { passive: false });
$('copy-camera').addEventListener('click', copyCamera);
$('reset-camera').addEventListener('click', resetCamera);
