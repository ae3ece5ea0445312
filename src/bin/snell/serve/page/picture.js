// The picture and the status line: the URL of what the controls ask for, the newest frame
// shown (only the newest: frames the page could not keep up with are skipped), the scene's
// exposure and curve followed in the controls, and the status and error over the picture.

import { $, img, overlay, state, fmt } from './state.js';

let loading = false;    // a picture is on its way
let shownKey = '';      // what the picture shows now
let pendingKey = '';    // what it should show next

function pictureUrl() {
  const view = $('view').value;
  const status = state.status;
  if (!status) return null;
  if (view.startsWith('lpe:')) {
    return `/lpe/${view.slice(4)}.png?g=${status.generation}&exposure=${$('exposure').value}&tone=${$('tone').value}`;
  }
  if (view === 'denoised') {
    return status.frame ? `/denoised.png?g=${status.frame.id}&exposure=${$('exposure').value}&tone=${$('tone').value}` : null;
  }
  // The views read from the film change with every frame; the others with the scene.
  if (view === 'variance' || view === 'spp') {
    return status.frame ? `/view/${view}.png?id=${status.frame.id}` : null;
  }
  if (view !== 'picture') return `/view/${view}.png?g=${status.generation}`;
  if (!status.frame) return null;
  return `/frame.jpg?id=${status.frame.id}&exposure=${$('exposure').value}&tone=${$('tone').value}`;
}

export function showPicture() {
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
    const status = state.status;
    img.dataset.frame = status && status.frame ? String(status.frame.id) : '';
    img.dataset.loaded = String(Number(img.dataset.loaded || 0) + 1);
    overlay.setAttribute('viewBox', `0 0 ${next.naturalWidth} ${next.naturalHeight}`);
    loading = false;
    if (pendingKey && pendingKey !== shownKey) showPicture();
  };
  next.onerror = async () => {
    loading = false;
    // Say why (a light path view of a Whitted preview, for one).
    const r = await fetch(url);
    if (!r.ok) {
      const error = $('error');
      error.textContent = await r.text();
      error.hidden = false;
    }
  };
  next.src = url;
}

// The exposure slider moved: its figure, and the picture tone mapped with it.
export function exposureChanged() {
  $('exposure-value').textContent = fmt($('exposure').value, 1);
  showPicture();
}

// The exposure and curve the scene renders its PNG with, as last applied to the controls:
// the page starts from them and follows the file when they change there; between changes
// the controls are the user's.
let sceneTone = '';
function followSceneTone() {
  const tone = state.status.tone;
  if (!tone) return;
  const key = `${tone.exposure} ${tone.curve}`;
  if (key === sceneTone) return;
  sceneTone = key;
  const e = $('exposure');
  const v = Number(tone.exposure);
  e.min = String(Math.min(-5, Math.floor(v)));
  e.max = String(Math.max(5, Math.ceil(v)));
  e.value = String(v);
  $('exposure-value').textContent = fmt(v, 1);
  $('tone').value = tone.curve;
}

// Shows the server's latest status (state.status): the scene, the progress, an error over
// the picture, and the picture itself.
export function showStatus() {
  const status = state.status;
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
