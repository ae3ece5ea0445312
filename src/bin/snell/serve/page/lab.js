// The sampling lab's page: sends the form to /lab/bsdf and draws the answer's histograms.

const form = document.getElementById('lab-form');
const result = document.getElementById('lab-result');

// Bins as a picture: `value(i)` gives each bin's colour as [r, g, b] in 0..1.
function draw(canvas, rows, cols, value) {
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(cols, rows);
  for (let i = 0; i < rows * cols; i++) {
    const [r, g, b] = value(i);
    img.data.set([r * 255, g * 255, b * 255, 255], 4 * i);
  }
  // Drawn small, then scaled up without smoothing: one block a bin.
  const small = document.createElement('canvas');
  small.width = cols;
  small.height = rows;
  small.getContext('2d').putImageData(img, 0, 0);
  ctx.imageSmoothingEnabled = false;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.drawImage(small, 0, 0, canvas.width, canvas.height);
}

async function run(event) {
  event.preventDefault();
  const query = new URLSearchParams();
  for (const [key, value] of new FormData(form)) {
    if (value !== '') query.set(key, value);
  }
  history.replaceState(null, '', '/lab?' + query);
  result.textContent = 'sampling…';
  const answer = await fetch('/lab/bsdf?' + query);
  if (!answer.ok) {
    result.textContent = 'The material cannot be tested: ' + (await answer.text());
    result.dataset.done = 'error';
    return;
  }
  const t = await answer.json();
  const [rows, cols] = t.bins;
  const most = Math.max(1, ...t.observed, ...t.expected);
  const grey = (v) => { const g = Math.sqrt(v / most); return [g, g, g]; };
  draw(document.getElementById('lab-observed'), rows, cols, (i) => grey(t.observed[i]));
  draw(document.getElementById('lab-expected'), rows, cols, (i) => grey(t.expected[i]));
  draw(document.getElementById('lab-difference'), rows, cols, (i) => {
    const e = t.expected[i];
    const z = Math.max(-1, Math.min(1, (t.observed[i] - e) / Math.sqrt(Math.max(e, 1)) / 4));
    return z >= 0 ? [z, 0, 0] : [0, 0, -z];
  });
  const binned = t.samples - t.specular - t.absorbed;
  result.textContent = `${t.title}, light leaving at ${t.angle}° from the normal: ` +
    `${binned} of ${t.samples} samples binned (${t.specular} on mirror or smooth-glass lobes, ` +
    `${t.absorbed} absorbed); chi² = ${t.chi2.toFixed(1)} with ${t.dof} degrees of freedom, ` +
    `p = ${t.p.toFixed(3)}: ` +
    (t.passed ? 'the samples follow the density.' : 'the samples do NOT follow the density.') +
    (t.inconsistent ? ' ' + t.inconsistent : '');
  result.dataset.done = t.passed ? 'passed' : 'failed';
}

form.addEventListener('submit', run);

// A link with the form's values (/lab?type=plastic&roughness=0.3&angle=40) fills the form and
// runs the test, so a teacher can hand out an experiment as a link.
const asked = new URLSearchParams(location.search);
if (asked.has('type')) {
  for (const [key, value] of asked) {
    const field = form.elements.namedItem(key);
    if (field) field.value = value;
  }
  form.requestSubmit();
}
