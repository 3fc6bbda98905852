// cropsight studio: the field map panel. The server builds the map of the whole pass with the
// studio's model (tracking on, as `detect broccoli --track --map`) in a background job; this file
// follows the job and draws the map as SVG: every head at its field position as a disc of its
// diameter, the camera's path, the open frame's heads highlighted; a click on a head opens a frame
// that detected it. It uses studio.js's api() and openFrame() and changes nothing else of the page.
'use strict';

const FieldMap = { map: null, uv: null };  // the map, and field (x, y) → drawing (u, v)
const SVG_NS = 'http://www.w3.org/2000/svg';

function svgElement(name, attributes) {
  const e = document.createElementNS(SVG_NS, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  return e;
}

async function buildFieldMap() {
  try { await api('/api/map', {}); } catch (e) { $('map-state').textContent = e.message; return; }
  pollFieldMap();
}

async function pollFieldMap() {
  const m = await api('/api/map');
  $('map-progress').value = m.progress;
  document.body.dataset.map = m.state;
  if (m.state === 'running') { $('map-state').textContent = `building… ${Math.round(100 * m.progress)} %`; setTimeout(pollFieldMap, 300); return; }
  if (m.state === 'failed') { $('map-state').textContent = `no field map: ${m.message}`; return; }
  if (m.state !== 'done') { $('map-state').textContent = m.state === 'idle' ? '' : m.state; return; }
  FieldMap.map = m;
  const harvestable = m.heads.filter((h) => h.harvestable).length;
  $('map-state').textContent = `${m.heads.length} heads, ${harvestable} harvestable (${m.seconds.toFixed(1)} s)` +
    (m.poses ? '' : ' · no poses.csv: the camera\'s motion is estimated from the heads, positions are relative to the first frame');
  drawFieldMap();
}

// The frame a click on a head opens: the middle one of the frames that detected it.
function headFrame(h) { return h.frames.length ? h.frames[Math.floor(h.frames.length / 2)] : h.first_frame; }

// The pass runs along the map's longer side, drawn left to right; metres on both axes alike.
function drawFieldMap() {
  const m = FieldMap.map, svg = $('map-svg');
  svg.replaceChildren();
  if (!m) return;
  const points = [...m.heads.map((h) => [h.x, h.y]), ...m.camera.map((c) => [c[0], c[1]])];
  const xs = points.map((p) => p[0]), ys = points.map((p) => p[1]);
  const swap = Math.max(...ys) - Math.min(...ys) > Math.max(...xs) - Math.min(...xs);
  const uv = (x, y) => (swap ? [y, x] : [x, y]);
  FieldMap.uv = uv;
  const us = points.map((p) => uv(...p)[0]), vs = points.map((p) => uv(...p)[1]);
  const pad = 0.15, u0 = Math.min(...us) - pad, v0 = Math.min(...vs) - pad;
  const width = Math.max(...us) + pad - u0, height = Math.max(...vs) + pad - v0;
  svg.setAttribute('viewBox', `${u0} ${v0} ${width} ${height}`);
  const path = m.camera.map((c) => uv(c[0], c[1]).join(',')).join(' ');
  if (m.camera.length) svg.appendChild(svgElement('polyline', { points: path, class: 'map-camera-path' }));
  svg.appendChild(svgElement('circle', { r: 0.03, class: 'map-camera', id: 'map-camera' }));
  for (const h of m.heads) {
    const [u, v] = uv(h.x, h.y);
    const c = svgElement('circle', { cx: u, cy: v, r: h.diameter_mm > 0 ? h.diameter_mm / 2000 : 0.03, class: 'map-head' });
    c.dataset.id = h.id;
    c.dataset.frame = headFrame(h);
    c.classList.toggle('harvestable', h.harvestable);
    const title = svgElement('title', {});
    title.textContent = `head ${h.id}: ${Math.round(h.diameter_mm)} mm${h.harvestable ? ', harvestable' : ''}; ` +
      `detected on ${h.frames.length} frame${h.frames.length === 1 ? '' : 's'} (${h.first_frame}–${h.last_frame}); click to open frame ${headFrame(h)}`;
    c.appendChild(title);
    c.addEventListener('click', () => openFrame(headFrame(h)));
    svg.appendChild(c);
  }
  highlightFieldMap();
}

function highlightFieldMap() {
  const m = FieldMap.map;
  if (!m) return;
  const f = Number(document.body.dataset.frame);
  const current = new Set(m.heads.filter((h) => h.frames.includes(f)).map((h) => String(h.id)));
  document.querySelectorAll('#map-svg .map-head').forEach((c) => c.classList.toggle('current', current.has(c.dataset.id)));
  const cam = m.camera[f], marker = $('map-camera');
  if (cam && marker) {
    const [u, v] = FieldMap.uv(cam[0], cam[1]);
    marker.setAttribute('cx', u);
    marker.setAttribute('cy', v);
  }
}

$('map-build').addEventListener('click', buildFieldMap);
$('map-cancel').addEventListener('click', () => api('/api/map/cancel', {}).then(pollFieldMap));
document.addEventListener('keydown', (ev) => {
  if ((ev.target.tagName === 'INPUT' && ev.target.type === 'number') || ev.ctrlKey || ev.metaKey || ev.altKey || ev.key.toLowerCase() !== 'm') return;
  ev.preventDefault();
  buildFieldMap();
});
// studio.js marks the open frame on <body data-frame>; the highlight follows it.
new MutationObserver(highlightFieldMap).observe(document.body, { attributes: true, attributeFilter: ['data-frame'] });
pollFieldMap().catch(() => {});
