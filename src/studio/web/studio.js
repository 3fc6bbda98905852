// cropsight studio: the page. Plain JavaScript, no build step and no network beyond the studio
// itself (docs/studio.md). One frame is open at a time; its labels live in a Uint16Array (0 = not
// a head, k = head k) until they are saved to the server, which writes the label image.
'use strict';

const S = {
  info: null, frame: 0, w: 0, h: 0, zoom: 1.5,
  cands: [], candAt: null, outline: null,   // candidates of the frame, pixel → candidate + 1, outline pixels
  labels: null, nextId: 1, dirty: false, saving: null,
  undo: [], redo: [], tool: 'select', brush: 3, filter: -Infinity, showColor: false,
  stroke: null, saveTimer: 0, clicks: 0, loaded: false,
};
window.studio = S;  // read by the browser test; the page never trusts it for anything
// $ and api() come from common.js.

// Runs [start, length, ...] ↔ ascending pixel indices.
function fromRuns(runs) {
  let n = 0;
  for (let k = 1; k < runs.length; k += 2) n += runs[k];
  const out = new Int32Array(n);
  let i = 0;
  for (let k = 0; k < runs.length; k += 2) for (let p = runs[k]; p < runs[k] + runs[k + 1]; ++p) out[i++] = p;
  return out;
}
function toRuns(pixels) {
  const runs = [];
  for (let k = 0; k < pixels.length;) {
    let e = k + 1;
    while (e < pixels.length && pixels[e] === pixels[e - 1] + 1) ++e;
    runs.push(pixels[k], e - k);
    k = e;
  }
  return runs;
}

// ---- frames -------------------------------------------------------------------------------
async function refreshInfo() {
  S.info = await api('/api/info');
  const n = S.info.labelled.length;
  $('progress-labelled').textContent = `${n} of ${S.info.frames} frames labelled`;
  document.querySelectorAll('#frame-list li').forEach((li) => {
    li.classList.toggle('labelled', S.info.labelled.includes(Number(li.dataset.frame)));
  });
}

async function openFrame(f) {
  f = Math.max(0, Math.min(S.info.frames - 1, f));
  if (S.dirty) await save();
  S.loaded = false;
  document.body.dataset.ready = '0';
  const [cands, labels] = await Promise.all([api(`/api/frame/${f}/candidates`), api(`/api/frame/${f}/labels`)]);
  S.frame = f;
  S.cands = cands.candidates.map((c, i) => ({ index: i, score: c.score, head: c.head, diameter: c.diameter_mm, pixels: fromRuns(c.runs) }));
  $('threshold').textContent = `threshold ${cands.threshold.toFixed(2)}`;
  indexCandidates();
  S.labels = new Uint16Array(S.w * S.h);
  S.nextId = 1;
  if (labels.labelled) {
    for (const runs of labels.heads) setPixels(fromRuns(runs), S.nextId++);
  } else {
    for (const c of S.cands) if (c.head) setPixels(c.pixels, S.nextId++);  // the model's pre-labels
  }
  S.undo = []; S.redo = []; S.dirty = false;
  setSaveState(labels.labelled ? 'saved' : 'model pre-labels (not saved)');
  $('frame-number').value = f;
  document.querySelectorAll('#frame-list li').forEach((li) => li.classList.toggle('current', Number(li.dataset.frame) === f));
  await showBackground();
  render();
  listCandidates();
  S.loaded = true;
  document.body.dataset.frame = String(f);
  document.body.dataset.ready = '1';
}

function showBackground() {
  const img = $('background');
  const kind = S.showColor && S.info.has_color ? 'color' : 'depth';
  return new Promise((resolve) => {
    img.onload = resolve;
    img.onerror = resolve;
    img.src = `/api/frame/${S.frame}/${kind}.png`;
  });
}

function indexCandidates() {
  S.candAt = new Int32Array(S.w * S.h);
  for (const c of S.cands) for (const p of c.pixels) S.candAt[p] = c.index + 1;
  S.outline = [];
  for (const c of S.cands) {
    for (const p of c.pixels) {
      const x = p % S.w, y = (p - x) / S.w;
      const same = (q) => S.candAt[q] === c.index + 1;
      if (x === 0 || y === 0 || x === S.w - 1 || y === S.h - 1 || !same(p - 1) || !same(p + 1) || !same(p - S.w) || !same(p + S.w))
        S.outline.push(p);
    }
  }
}

function setPixels(pixels, id) { for (const p of pixels) S.labels[p] = id; }

// Share of a candidate's pixels labelled as a head: above one half it counts as marked head.
function labelledShare(c) {
  let n = 0;
  for (const p of c.pixels) if (S.labels[p]) ++n;
  return c.pixels.length ? n / c.pixels.length : 0;
}

// ---- drawing ------------------------------------------------------------------------------
// Bright, cold tints that read over the depth map's warm near end (leaves and heads are near).
const headColours = [[0, 255, 255], [255, 0, 255], [255, 255, 255], [120, 255, 0], [0, 140, 255], [255, 120, 255]];
function render() {
  const canvas = $('overlay');
  const ctx = canvas.getContext('2d');
  const img = ctx.createImageData(S.w, S.h);
  const d = img.data;
  for (let p = 0; p < S.labels.length; ++p) {
    const id = S.labels[p];
    if (!id) continue;
    const c = headColours[id % headColours.length];
    d.set([c[0], c[1], c[2], 140], 4 * p);
  }
  for (const p of S.outline) {
    const c = S.cands[S.candAt[p] - 1];
    if (c.score < S.filter) continue;
    const head = labelledShare(c) > 0.5;
    d.set(head ? [0, 255, 90, 255] : [235, 235, 235, 150], 4 * p);
  }
  ctx.putImageData(img, 0, 0);
}

function listCandidates() {
  const heads = new Set(S.labels).size - (S.labels.includes(0) ? 1 : 0);
  $('frame-heads').textContent = `${heads} head${heads === 1 ? '' : 's'} on this frame`;
  const ul = $('candidates');
  ul.replaceChildren();
  const sorted = [...S.cands].sort((a, b) => b.score - a.score).filter((c) => c.score >= S.filter);
  for (const c of sorted) {
    const li = document.createElement('li');
    const head = labelledShare(c) > 0.5;
    li.className = head ? 'head' : '';
    li.textContent = `${c.score.toFixed(2)} ${head ? 'head' : 'not head'} · ${Math.round(c.diameter)} mm (${c.pixels.length} px)`;
    li.onclick = () => toggleCandidate(c);
    ul.appendChild(li);
  }
}

// ---- editing ------------------------------------------------------------------------------
function edited() {
  S.dirty = true;
  S.redo = [];
  setSaveState('unsaved changes');
  clearTimeout(S.saveTimer);
  S.saveTimer = setTimeout(() => save(), 1500);  // autosave
  render();
  listCandidates();
}
function snapshot() { S.undo.push(S.labels.slice()); if (S.undo.length > 50) S.undo.shift(); }

function toggleCandidate(c) {
  snapshot();
  if (labelledShare(c) > 0.5) setPixels(c.pixels, 0);
  else setPixels(c.pixels, S.nextId++);
  edited();
}

function pixelOf(ev) {
  const r = $('overlay').getBoundingClientRect();
  const x = Math.floor((ev.clientX - r.left) * S.w / r.width), y = Math.floor((ev.clientY - r.top) * S.h / r.height);
  return x >= 0 && y >= 0 && x < S.w && y < S.h ? [x, y] : null;
}

function dab(x, y, id) {
  const r = S.brush;
  for (let dy = -r; dy <= r; ++dy)
    for (let dx = -r; dx <= r; ++dx) {
      const u = x + dx, v = y + dy;
      if (dx * dx + dy * dy <= r * r && u >= 0 && v >= 0 && u < S.w && v < S.h) S.labels[v * S.w + u] = id;
    }
}
function strokeTo(x, y) {
  const s = S.stroke;
  const steps = Math.max(1, Math.ceil(Math.hypot(x - s.x, y - s.y)));
  for (let k = 1; k <= steps; ++k) dab(Math.round(s.x + (x - s.x) * k / steps), Math.round(s.y + (y - s.y) * k / steps), s.id);
  s.x = x; s.y = y;
  render();
}

function onDown(ev) {
  const at = pixelOf(ev);
  if (!at || S.info.read_only) return;
  ++S.clicks;
  const p = at[1] * S.w + at[0];
  if (S.tool === 'select') {
    const c = S.cands[S.candAt[p] - 1];
    if (c && c.score >= S.filter) toggleCandidate(c);
    return;
  }
  snapshot();
  const id = S.tool === 'erase' ? 0 : (headNear(at[0], at[1], S.brush + 2) || S.nextId++);
  S.stroke = { x: at[0], y: at[1], id };
  dab(at[0], at[1], id);
  render();
}
// The head a paint stroke starting at (x, y) extends: the nearest labelled pixel within `r`
// (on or beside a head), else none and the stroke starts a new head.
function headNear(x, y, r) {
  let best = 0, bestD = Infinity;
  for (let dy = -r; dy <= r; ++dy)
    for (let dx = -r; dx <= r; ++dx) {
      const u = x + dx, v = y + dy, d = dx * dx + dy * dy;
      if (u < 0 || v < 0 || u >= S.w || v >= S.h || d > r * r || d >= bestD) continue;
      const id = S.labels[v * S.w + u];
      if (id) { best = id; bestD = d; }
    }
  return best;
}
function onMove(ev) { const at = S.stroke && pixelOf(ev); if (at) strokeTo(at[0], at[1]); }
function onUp() { if (S.stroke) { S.stroke = null; edited(); } }

function undo() { if (!S.undo.length) return; S.redo.push(S.labels); S.labels = S.undo.pop(); afterHistory(); }
function redo() { if (!S.redo.length) return; S.undo.push(S.labels); S.labels = S.redo.pop(); afterHistory(); }
function afterHistory() {
  S.dirty = true;
  setSaveState('unsaved changes');
  clearTimeout(S.saveTimer);
  S.saveTimer = setTimeout(() => save(), 1500);
  render();
  listCandidates();
}

// ---- saving -------------------------------------------------------------------------------
function setSaveState(text) { const e = $('save-state'); e.textContent = text; e.classList.toggle('dirty', text !== 'saved'); }

async function save() {
  clearTimeout(S.saveTimer);
  if (S.info.read_only) { setSaveState('read-only: not saved'); return; }
  if (S.saving) await S.saving;
  const heads = new Map();
  for (let p = 0; p < S.labels.length; ++p) {
    const id = S.labels[p];
    if (id) { if (!heads.has(id)) heads.set(id, []); heads.get(id).push(p); }
  }
  const frame = S.frame;
  setSaveState('saving…');
  S.saving = api(`/api/frame/${frame}/labels`, { heads: [...heads.values()].map(toRuns) })
    .then(() => { if (S.frame === frame) S.dirty = false; return refreshInfo(); })
    // 'saved' once the counter of labelled frames has caught up, so that the two never disagree.
    .then(() => { if (S.frame === frame && !S.dirty) setSaveState('saved'); })
    .catch((e) => setSaveState(`save failed: ${e.message}`));
  await S.saving;
  S.saving = null;
}

// ---- training -----------------------------------------------------------------------------
async function train() {
  if (S.dirty) await save();
  try { await api('/api/train', { with_general: $('train-general').checked }); } catch (e) { $('train-state').textContent = e.message; return; }
  pollTraining();
}
async function pollTraining() {
  const t = await api('/api/train');
  $('train-progress').value = t.progress;
  $('train-state').textContent = t.state + (t.message ? `: ${t.message}` : '') +
    (t.state === 'done' ? ` (${t.train_frames.length} frames${t.with_general ? ` + ${t.general_frames} general` : ''}, ${t.seconds.toFixed(1)} s)` : '');
  document.body.dataset.training = t.state;
  $('keep').disabled = $('discard').disabled = t.state !== 'done';
  if (t.state === 'done') showFigures(t);
  if (t.state === 'running') setTimeout(pollTraining, 400);
}
function showFigures(t) {
  const f = (v) => (v === null ? '–' : v.toFixed(3));
  const rows = [['', 'new model', 'current model'], ['held-out frames', t.trained.frames, t.current.frames],
    ['κ', f(t.trained.kappa), f(t.current.kappa)], ['precision', f(t.trained.precision), f(t.current.precision)],
    ['recall', f(t.trained.recall), f(t.current.recall)], ['AP50', f(t.trained.ap50), f(t.current.ap50)]];
  const table = $('figures');
  table.replaceChildren();
  for (const r of rows) {
    const tr = document.createElement('tr');
    for (const v of r) { const td = document.createElement(tr.childElementCount ? 'td' : 'th'); td.textContent = v; tr.appendChild(td); }
    table.appendChild(tr);
  }
}

// ---- wiring -------------------------------------------------------------------------------
function setTool(t) {
  S.tool = t;
  for (const name of ['select', 'paint', 'erase']) $(`tool-${name}`).classList.toggle('active', name === t);
}
async function leastCertain() {
  const u = await api('/api/uncertain');
  const next = u.least_certain_first.find((e) => !S.info.labelled.includes(e.frame) && e.frame !== S.frame);
  if (next) await openFrame(next.frame);
}

function keys(ev) {
  if (ev.target.tagName === 'INPUT' && ev.target.type === 'number') return;
  const k = ev.key.toLowerCase();
  if ((ev.ctrlKey || ev.metaKey) && k === 'z') { ev.preventDefault(); ev.shiftKey ? redo() : undo(); return; }
  if ((ev.ctrlKey || ev.metaKey) && k === 'y') { ev.preventDefault(); redo(); return; }
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const actions = {
    arrowleft: () => openFrame(S.frame - 1), arrowright: () => openFrame(S.frame + 1), u: leastCertain,
    s: save, v: () => setTool('select'), p: () => setTool('paint'), e: () => setTool('erase'), t: train,
    c: () => { $('show-color').checked = !$('show-color').checked; S.showColor = $('show-color').checked; showBackground(); },
    '[': () => setBrush(S.brush - 1), ']': () => setBrush(S.brush + 1),
  };
  if (actions[k]) { ev.preventDefault(); actions[k](); }
}
function setBrush(r) { S.brush = Math.max(1, Math.min(20, r)); $('brush').value = S.brush; $('brush-value').textContent = S.brush; }

async function start() {
  S.info = await api('/api/info');
  S.w = S.info.width; S.h = S.info.height;
  const stack = $('stack');
  stack.style.setProperty('--w', S.w); stack.style.setProperty('--h', S.h); stack.style.setProperty('--zoom', S.zoom);
  $('overlay').width = S.w; $('overlay').height = S.h;
  $('sequence').textContent = S.info.sequence + (S.info.read_only ? ' (read-only)' : '');
  $('model').textContent = `model ${S.info.model}`;
  const list = $('frame-list');
  for (let f = 0; f < S.info.frames; ++f) {
    const li = document.createElement('li');
    li.dataset.frame = f; li.textContent = `frame ${f}`;
    li.onclick = () => openFrame(f);
    list.appendChild(li);
  }
  const overlay = $('overlay');
  overlay.addEventListener('mousedown', onDown);
  window.addEventListener('mousemove', onMove);
  window.addEventListener('mouseup', onUp);
  document.addEventListener('keydown', keys);
  $('prev').onclick = () => openFrame(S.frame - 1);
  $('next').onclick = () => openFrame(S.frame + 1);
  $('frame-number').onchange = (e) => openFrame(Number(e.target.value));
  $('least-certain').onclick = leastCertain;
  $('score-filter').oninput = (e) => {
    const v = Number(e.target.value);
    S.filter = v <= Number(e.target.min) ? -Infinity : v;
    $('score-filter-value').textContent = S.filter === -Infinity ? 'all' : v.toFixed(1);
    render(); listCandidates();
  };
  $('show-color').onchange = (e) => { S.showColor = e.target.checked; showBackground(); };
  for (const t of ['select', 'paint', 'erase']) $(`tool-${t}`).onclick = () => setTool(t);
  $('brush').oninput = (e) => setBrush(Number(e.target.value));
  $('undo').onclick = undo; $('redo').onclick = redo; $('save').onclick = save;
  $('train').onclick = train;
  const general = $('train-general');
  general.disabled = !S.info.general_passes;
  $('train-general-label').title = S.info.general_passes
    ? `train on ${S.info.general_frames} labelled frames of ${S.info.general_passes} general passes too (--general-data)`
    : 'to enable: start the studio with --general-data DIR[,DIR...], the general model\'s training passes (docs/studio.md)';
  $('train-cancel').onclick = () => api('/api/train/cancel', {}).then(pollTraining);
  $('keep').onclick = () => api('/api/train/keep', {}).then((r) => { $('train-state').textContent = `kept: ${r.model}`; $('keep').disabled = $('discard').disabled = true; })
    .catch((e) => { $('train-state').textContent = e.message; });
  $('discard').onclick = () => api('/api/train/discard', {}).then(pollTraining);
  window.addEventListener('beforeunload', (ev) => { if (S.dirty) { save(); ev.preventDefault(); } });
  await refreshInfo();
  await openFrame(0);
  pollTraining();
}

start().catch((e) => { document.body.dataset.error = e.message; $('hint').textContent = `error: ${e.message}`; });
