// cropsight studio: what both pages (index.html for depth sequences, images.html for image
// folders) use — an element by id, and the studio's JSON API, whose errors become exceptions
// carrying the server's one-line message.
'use strict';

const $ = (id) => document.getElementById(id);

async function api(path, body) {
  const init = body === undefined ? {} : { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) };
  const res = await fetch(path, init);
  const json = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(json.error || res.statusText);
  return json;
}
