// The server's JSON API (docs/serve.md, The API). Refusals come back as {ok: false, message}
// holding the server's one-line message, which is the CLI's for a sketch.

async function answer(response) {
  const text = await response.text();
  if (!response.ok) return {ok: false, status: response.status, message: text};
  return {ok: true, status: response.status, text};
}

export async function getSketch() {
  const r = await answer(await fetch('/api/sketch', {cache: 'no-store'}));
  return r.ok ? JSON.parse(r.text) : null;
}

export async function putSketch(doc) {
  return answer(await fetch('/api/sketch', {method: 'PUT', headers: {'Content-Type': 'application/geo+json'},
                                            body: JSON.stringify(doc, null, 1)}));
}

export async function putHeightmap(file) {
  return answer(await fetch('/api/heightmap', {method: 'PUT', headers: {'Content-Type': 'application/octet-stream'},
                                               body: await file.arrayBuffer()}));
}

// Files in one form, each named by its path below their folder (a folder chosen whole gives
// paths starting with the folder's own name, dropped here): a model library's to
// /api/models, a real place's to /api/like.
export async function postFiles(url, files) {
  const form = new FormData();
  for (const f of files) form.append('file', f, f.webkitRelativePath ? f.webkitRelativePath.split('/').slice(1).join('/') : f.name);
  return answer(await fetch(url, {method: 'POST', body: form}));
}

// The server may require a JSON content type on its JSON routes: these send an empty object.
const emptyJson = {method: 'POST', headers: {'Content-Type': 'application/json'}, body: '{}'};

export async function cancelJob() {
  return answer(await fetch('/api/cancel', emptyJson));
}

export async function startGenerate() {
  return answer(await fetch('/api/generate', emptyJson));
}

export async function startRender(request) {
  return answer(await fetch('/api/render', {method: 'POST', headers: {'Content-Type': 'application/json'},
                                            body: JSON.stringify(request)}));
}

// Where the server places a GeoTIFF of the work folder: {file, extent, size, crs}, or its refusal.
export async function placeBasemap(name) {
  return answer(await fetch(`/api/basemap?file=${encodeURIComponent(name)}`, {cache: 'no-store'}));
}

// The place the sketch looks like, measured: {file, measured}, or the server's refusal.
export async function getLike() {
  return answer(await fetch('/api/like', {cache: 'no-store'}));
}

export async function getJson(url) {
  const r = await answer(await fetch(url, {cache: 'no-store'}));
  return r.ok ? JSON.parse(r.text) : null;
}

// The job events (stage, progress, answered, state) as server-sent events.
export function listen(handlers) {
  const events = new EventSource('/api/events');
  for (const name of ['stage', 'progress', 'answered', 'state'])
    events.addEventListener(name, e => handlers[name] && handlers[name](JSON.parse(e.data)));
  return events;
}
