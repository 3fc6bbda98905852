// cropsight studio, image page (images.html): boxes and polygons with classes on a folder of
// images, pre-filled from the model. Plain JavaScript, no build step and no network beyond the
// studio itself. One image is open at a time; its shapes live here until saved, which the server
// writes as COCO, VOC and YOLO (docs/studio.md, "Images").
'use strict';

const IS = {
  info: null, index: 0, w: 0, h: 0, zoom: 1,
  shapes: [], proposals: [], labelled: false, selected: -1, tool: 'select', cls: 0, minScore: 0,
  undo: [], redo: [], dirty: false, saving: null, saveTimer: 0, poly: null, drag: null, hover: null,
};
window.imagesStudio = IS;  // read by the browser test; the page never trusts it for anything
// $ and api() come from common.js.

// ---- shapes: {label, x1, y1, x2, y2, poly: null | [[x, y], ...], source: 'model' | 'user', score}
function fromWire(s, source) {
  if (s.polygon) {
    const poly = [];
    for (let k = 0; k < s.polygon.length; k += 2) poly.push([s.polygon[k], s.polygon[k + 1]]);
    return withBounds({ label: s.label, poly, source, score: s.score });
  }
  const [x1, y1, x2, y2] = s.box;
  return { label: s.label, x1, y1, x2, y2, poly: null, source, score: s.score };
}
function toWire(s) {
  return s.poly ? { label: s.label, polygon: s.poly.flat() } : { label: s.label, box: [s.x1, s.y1, s.x2, s.y2] };
}
function withBounds(s) {
  const xs = s.poly.map((p) => p[0]), ys = s.poly.map((p) => p[1]);
  return Object.assign(s, { x1: Math.min(...xs), y1: Math.min(...ys), x2: Math.max(...xs), y2: Math.max(...ys) });
}
function clampX(x) { return Math.max(0, Math.min(IS.w, x)); }
function clampY(y) { return Math.max(0, Math.min(IS.h, y)); }

// ---- images -------------------------------------------------------------------------------
async function refreshInfo() {
  const local = IS.info ? IS.info.classes : [];
  IS.info = await api('/api/info');
  for (const c of local) if (!IS.info.classes.includes(c)) IS.info.classes.push(c);  // added here, not yet saved
  const n = IS.info.labelled.length;
  $('progress-labelled').textContent = `${n} of ${IS.info.frames} images labelled`;
  document.querySelectorAll('#image-list li').forEach((li) => li.classList.toggle('labelled', IS.info.labelled.includes(Number(li.dataset.index))));
  listClasses();
}

async function openImage(i) {
  i = Math.max(0, Math.min(IS.info.frames - 1, i));
  if (IS.dirty) await save();
  document.body.dataset.ready = '0';
  const [labels, proposals] = await Promise.all([api(`/api/image/${i}/labels`), api(`/api/image/${i}/proposals`)]);
  IS.index = i; IS.w = labels.width; IS.h = labels.height; IS.labelled = labels.labelled;
  IS.proposals = proposals.shapes.map((s) => fromWire(s, 'model'));
  // The user's saved labels always win; an image nobody saved starts from the model's boxes.
  IS.shapes = labels.labelled ? labels.shapes.map((s) => fromWire(s, 'user')) : prefill();
  IS.selected = -1; IS.poly = null; IS.drag = null; IS.undo = []; IS.redo = []; IS.dirty = false;
  setSaveState(labels.labelled ? 'saved' : 'model pre-labels (not saved)');
  $('image-number').value = i;
  document.querySelectorAll('#image-list li').forEach((li) => li.classList.toggle('current', Number(li.dataset.index) === i));
  await showImage();
  render();
  document.body.dataset.image = String(i);
  document.body.dataset.ready = '1';
}
function prefill() { return IS.proposals.filter((s) => s.score >= IS.minScore).map((s) => ({ ...s })); }

function showImage() {
  IS.zoom = Math.min(1.5, 900 / IS.w, 720 / IS.h);
  const stack = $('stack');
  stack.style.setProperty('--w', IS.w); stack.style.setProperty('--h', IS.h); stack.style.setProperty('--zoom', IS.zoom);
  const canvas = $('overlay');
  canvas.width = Math.round(IS.w * IS.zoom); canvas.height = Math.round(IS.h * IS.zoom);
  const img = $('background');
  return new Promise((resolve) => { img.onload = resolve; img.onerror = resolve; img.src = `/api/image/${IS.index}/pixels`; });
}

// ---- drawing ------------------------------------------------------------------------------
const classColours = ['#00e5ff', '#ff4df0', '#b6ff3b', '#ffd23f', '#ff7a45', '#8c9eff', '#ffffff'];
function colourOf(label) { const k = IS.info.classes.indexOf(label); return classColours[(k < 0 ? 0 : k) % classColours.length]; }

function render() {
  const ctx = $('overlay').getContext('2d');
  const z = IS.zoom;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, ctx.canvas.width, ctx.canvas.height);
  ctx.font = '12px system-ui, sans-serif';
  IS.shapes.forEach((s, k) => {
    ctx.strokeStyle = colourOf(s.label);
    ctx.lineWidth = k === IS.selected ? 3 : 1.5;
    ctx.setLineDash(s.source === 'model' ? [6, 4] : []);
    ctx.beginPath();
    if (s.poly) { s.poly.forEach(([x, y], j) => (j ? ctx.lineTo(x * z, y * z) : ctx.moveTo(x * z, y * z))); ctx.closePath(); }
    else ctx.rect(s.x1 * z, s.y1 * z, (s.x2 - s.x1) * z, (s.y2 - s.y1) * z);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = ctx.strokeStyle;
    ctx.fillText(s.label + (s.source === 'model' ? ` ${s.score.toFixed(2)}` : ''), s.x1 * z + 2, Math.max(12, s.y1 * z - 3));
    if (k === IS.selected && !s.poly)
      for (const [x, y] of corners(s)) ctx.fillRect(x * z - 3, y * z - 3, 6, 6);
  });
  if (IS.poly) {
    ctx.strokeStyle = colourOf(currentClass()); ctx.lineWidth = 1.5;
    ctx.beginPath();
    IS.poly.forEach(([x, y], j) => (j ? ctx.lineTo(x * z, y * z) : ctx.moveTo(x * z, y * z)));
    if (IS.hover) ctx.lineTo(IS.hover[0] * z, IS.hover[1] * z);
    ctx.stroke();
    for (const [x, y] of IS.poly) ctx.fillRect(x * z - 2, y * z - 2, 4, 4);
  }
  listShapes();
}
function corners(s) { return [[s.x1, s.y1], [s.x2, s.y1], [s.x2, s.y2], [s.x1, s.y2]]; }

function listShapes() {
  const ul = $('shapes');
  ul.replaceChildren();
  IS.shapes.forEach((s, k) => {
    const li = document.createElement('li');
    li.className = (k === IS.selected ? 'selected ' : '') + (s.source === 'model' ? 'model' : '');
    const size = `${Math.round(s.x2 - s.x1)}×${Math.round(s.y2 - s.y1)}`;
    li.textContent = `${k + 1}. ${s.label} ${s.poly ? `polygon (${s.poly.length})` : 'box'} ${size}` + (s.source === 'model' ? ` · model ${s.score.toFixed(2)}` : '');
    li.onclick = () => { IS.selected = k; render(); };
    ul.appendChild(li);
  });
}
function currentClass() { return IS.info.classes[IS.cls] || 'object'; }
function listClasses() {
  const ol = $('classes');
  ol.replaceChildren();
  IS.info.classes.forEach((c, k) => {
    const li = document.createElement('li');
    li.textContent = c; li.className = k === IS.cls ? 'current' : '';
    li.style.color = colourOf(c);
    li.onclick = () => setClass(k);
    ol.appendChild(li);
  });
}
// Class k becomes the one new shapes get, and the selected shape's.
function setClass(k) {
  if (k < 0 || k >= IS.info.classes.length) return;
  IS.cls = k;
  const s = IS.shapes[IS.selected];
  if (s && s.label !== IS.info.classes[k]) { snapshot(); s.label = IS.info.classes[k]; s.source = 'user'; edited(); }
  listClasses(); render();
}
function addClass() {
  const name = $('new-class').value.trim();
  if (!name) return;
  if (!IS.info.classes.includes(name)) IS.info.classes.push(name);
  $('new-class').value = '';
  setClass(IS.info.classes.indexOf(name));
}

// ---- editing ------------------------------------------------------------------------------
function snapshot() { IS.undo.push(JSON.stringify(IS.shapes)); if (IS.undo.length > 100) IS.undo.shift(); IS.redo = []; }
function edited() {
  IS.dirty = true;
  setSaveState('unsaved changes');
  clearTimeout(IS.saveTimer);
  IS.saveTimer = setTimeout(() => save(), 1500);  // autosave
  render();
}
function undo() { if (!IS.undo.length) return; IS.redo.push(JSON.stringify(IS.shapes)); IS.shapes = JSON.parse(IS.undo.pop()); IS.selected = -1; edited(); }
function redo() { if (!IS.redo.length) return; IS.undo.push(JSON.stringify(IS.shapes)); IS.shapes = JSON.parse(IS.redo.pop()); IS.selected = -1; edited(); }
function deleteSelected() {
  if (IS.selected < 0) return;
  snapshot(); IS.shapes.splice(IS.selected, 1); IS.selected = -1; edited();
}

// Image coordinates of a mouse event, rounded to whole pixels (corners), clamped to the image.
function pointOf(ev) {
  const r = $('overlay').getBoundingClientRect();
  return [clampX(Math.round((ev.clientX - r.left) * IS.w / r.width)), clampY(Math.round((ev.clientY - r.top) * IS.h / r.height))];
}
function near(a, b, cssPixels) { return Math.hypot(a[0] - b[0], a[1] - b[1]) * IS.zoom <= cssPixels; }
function inside(s, [x, y]) {
  if (x < s.x1 || x > s.x2 || y < s.y1 || y > s.y2) return false;
  if (!s.poly) return true;
  let odd = false;
  for (let i = 0, j = s.poly.length - 1; i < s.poly.length; j = i++) {
    const [ax, ay] = s.poly[i], [bx, by] = s.poly[j];
    if ((ay > y) !== (by > y) && x < (bx - ax) * (y - ay) / (by - ay) + ax) odd = !odd;
  }
  return odd;
}
// The box corner under `p` (the selected box first), as [shape, corner index].
function cornerAt(p) {
  const order = IS.shapes.map((s, k) => k).sort((a, b) => (b === IS.selected) - (a === IS.selected));
  for (const k of order) {
    const s = IS.shapes[k];
    if (s.poly) continue;
    const c = corners(s).findIndex((q) => near(q, p, 7));
    if (c >= 0) return [k, c];
  }
  return null;
}
function shapeAt(p) {
  let best = -1, area = Infinity;
  IS.shapes.forEach((s, k) => { const a = (s.x2 - s.x1) * (s.y2 - s.y1); if (inside(s, p) && a < area) { best = k; area = a; } });
  return best;
}

function onDown(ev) {
  if (ev.button !== 0 || IS.info.read_only) return;
  const p = pointOf(ev);
  if (IS.tool === 'polygon') return polygonClick(p);
  if (IS.tool === 'box') { IS.drag = { kind: 'new', from: p, to: p }; return; }
  const corner = cornerAt(p);
  if (corner) { snapshot(); IS.selected = corner[0]; IS.drag = { kind: 'corner', k: corner[0], c: corner[1], moved: false }; render(); return; }
  IS.selected = shapeAt(p);
  if (IS.selected >= 0) { snapshot(); IS.drag = { kind: 'move', k: IS.selected, last: p, moved: false }; }
  render();
}
function onMove(ev) {
  if (!IS.info) return;
  const p = pointOf(ev);
  if (IS.poly) { IS.hover = p; render(); }
  const d = IS.drag;
  if (!d) return;
  if (d.kind === 'new') { d.to = p; render(); drawRubberBand(d); return; }
  const s = IS.shapes[d.k];
  d.moved = true;
  if (d.kind === 'corner') {
    const [cx, cy] = [[0, 0], [1, 0], [1, 1], [0, 1]][d.c];
    if (cx) s.x2 = p[0]; else s.x1 = p[0];
    if (cy) s.y2 = p[1]; else s.y1 = p[1];
  } else {
    const dx = p[0] - d.last[0], dy = p[1] - d.last[1];
    d.last = p;
    if (s.poly) { s.poly = s.poly.map(([x, y]) => [clampX(x + dx), clampY(y + dy)]); withBounds(s); }
    else { s.x1 += dx; s.x2 += dx; s.y1 += dy; s.y2 += dy; }
  }
  render();
}
function drawRubberBand(d) {
  const ctx = $('overlay').getContext('2d'), z = IS.zoom;
  ctx.strokeStyle = colourOf(currentClass()); ctx.lineWidth = 1.5;
  ctx.strokeRect(d.from[0] * z, d.from[1] * z, (d.to[0] - d.from[0]) * z, (d.to[1] - d.from[1]) * z);
}
function onUp(ev) {
  const d = IS.drag;
  if (!d) return;
  IS.drag = null;
  if (d.kind === 'new') {
    const to = pointOf(ev);
    const s = { label: currentClass(), x1: Math.min(d.from[0], to[0]), y1: Math.min(d.from[1], to[1]),
      x2: Math.max(d.from[0], to[0]), y2: Math.max(d.from[1], to[1]), poly: null, source: 'user', score: 1 };
    if (s.x2 - s.x1 < 2 || s.y2 - s.y1 < 2) { render(); return; }  // a click, not a box
    snapshot(); IS.shapes.push(s); IS.selected = IS.shapes.length - 1; edited();
    return;
  }
  if (!d.moved) { IS.undo.pop(); return; }  // a click that selected: nothing to undo
  const s = IS.shapes[d.k];
  if (!s.poly) [s.x1, s.x2, s.y1, s.y2] = [Math.min(s.x1, s.x2), Math.max(s.x1, s.x2), Math.min(s.y1, s.y2), Math.max(s.y1, s.y2)];
  s.source = 'user';
  edited();
}
function polygonClick(p) {
  if (!IS.poly) { IS.poly = [p]; render(); return; }
  if (IS.poly.length >= 3 && near(p, IS.poly[0], 8)) return closePolygon();
  IS.poly.push(p); render();
}
function closePolygon() {
  const poly = IS.poly;
  IS.poly = null; IS.hover = null;
  if (!poly || poly.length < 3) { render(); return; }
  snapshot();
  IS.shapes.push(withBounds({ label: currentClass(), poly, source: 'user', score: 1 }));
  IS.selected = IS.shapes.length - 1;
  edited();
}

// ---- saving -------------------------------------------------------------------------------
function setSaveState(text) { const e = $('save-state'); e.textContent = text; e.classList.toggle('dirty', text !== 'saved'); }

async function save() {
  clearTimeout(IS.saveTimer);
  if (IS.info.read_only) { setSaveState('read-only: not saved'); return; }
  if (IS.saving) await IS.saving;
  const index = IS.index;
  const body = { shapes: IS.shapes.map(toWire) };
  setSaveState('saving…');
  IS.saving = api(`/api/image/${index}/labels`, body)
    .then(() => { if (IS.index === index) { IS.dirty = false; IS.labelled = true; } return refreshInfo(); })
    // 'saved' once the counter of labelled images has caught up, so that the two never disagree.
    .then(() => { if (IS.index === index && !IS.dirty) setSaveState('saved'); })
    .catch((e) => setSaveState(`save failed: ${e.message}`));
  await IS.saving;
  IS.saving = null;
}

// ---- wiring -------------------------------------------------------------------------------
function setTool(t) {
  if (IS.poly && t !== 'polygon') { IS.poly = null; render(); }
  IS.tool = t;
  for (const name of ['select', 'box', 'polygon']) $(`tool-${name}`).classList.toggle('active', name === t);
}
function nextUnlabelled() {
  const n = IS.info.frames;
  for (let k = 1; k <= n; ++k) {
    const i = (IS.index + k) % n;
    if (!IS.info.labelled.includes(i)) return openImage(i);
  }
  return null;
}

function keys(ev) {
  if (ev.target.tagName === 'INPUT') return;  // typing a class name or an image number
  const k = ev.key.toLowerCase();
  if ((ev.ctrlKey || ev.metaKey) && k === 'z') { ev.preventDefault(); ev.shiftKey ? redo() : undo(); return; }
  if ((ev.ctrlKey || ev.metaKey) && k === 'y') { ev.preventDefault(); redo(); return; }
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const actions = {
    arrowleft: () => openImage(IS.index - 1), arrowright: () => openImage(IS.index + 1), n: nextUnlabelled,
    s: save, v: () => setTool('select'), b: () => setTool('box'), g: () => setTool('polygon'),
    delete: deleteSelected, backspace: () => (IS.poly ? (IS.poly.pop(), render()) : deleteSelected()),
    enter: closePolygon, escape: () => { IS.poly = null; IS.selected = -1; render(); },
  };
  if (/^[1-9]$/.test(k)) { ev.preventDefault(); setClass(Number(k) - 1); return; }
  if (actions[k]) { ev.preventDefault(); actions[k](); }
}

async function start() {
  IS.info = await api('/api/info');
  $('folder').textContent = IS.info.folder + (IS.info.read_only ? ' (read-only)' : '');
  $('model').textContent = `model ${IS.info.model}`;
  $('outputs').textContent = `Saved labels go to ${IS.info.outputs} in the image folder (COCO, VOC, YOLO).`;
  const list = $('image-list');
  IS.info.images.forEach((name, i) => {
    const li = document.createElement('li');
    li.dataset.index = i; li.textContent = name; li.title = name;
    li.onclick = () => openImage(i);
    list.appendChild(li);
  });
  const overlay = $('overlay');
  overlay.addEventListener('mousedown', onDown);
  window.addEventListener('mousemove', onMove);
  window.addEventListener('mouseup', onUp);
  document.addEventListener('keydown', keys);
  $('prev').onclick = () => openImage(IS.index - 1);
  $('next').onclick = () => openImage(IS.index + 1);
  $('image-number').onchange = (e) => openImage(Number(e.target.value));
  $('next-unlabelled').onclick = nextUnlabelled;
  $('min-score').oninput = (e) => {
    IS.minScore = Number(e.target.value);
    $('min-score-value').textContent = IS.minScore.toFixed(2);
    if (!IS.labelled && !IS.dirty) { IS.shapes = prefill(); IS.selected = -1; render(); }
  };
  $('min-score').onchange = (e) => e.target.blur();  // the keys are the page's again
  for (const t of ['select', 'box', 'polygon']) $(`tool-${t}`).onclick = () => setTool(t);
  $('undo').onclick = undo; $('redo').onclick = redo; $('save').onclick = save; $('delete').onclick = deleteSelected;
  $('add-class').onclick = addClass;
  $('new-class').addEventListener('keydown', (e) => { if (e.key === 'Enter') addClass(); });
  window.addEventListener('beforeunload', (ev) => { if (IS.dirty) { save(); ev.preventDefault(); } });
  await refreshInfo();
  await openImage(0);
}

start().catch((e) => { document.body.dataset.error = e.message; $('hint').textContent = `error: ${e.message}`; });
