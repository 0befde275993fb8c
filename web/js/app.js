// exacity serve's page: the sketch editor, generation with its progress, the generated layers
// and the 3D view (docs/serve.md). Every sketch edit is sent to the server, which
// checks it as the CLI does; a refusal shows the CLI's message and the page goes back to the
// server's sketch, so what is drawn is always what a generation uses.
import * as api from './api.js';
import {SketchHistory} from './history.js';
import {SketchMap} from './sketch_map.js';
import {SettingsPanel} from './settings_panel.js';
import {CityLayers} from './city_layers.js';

const $ = id => document.getElementById(id);
const history = new SketchHistory();
let explore = null;  // made when first shown: three.js loads only then
let cityLayers = null;
let lastGood = null;

// The message line (one line, the whole text on hover or unfolded by a click), and under it
// what the page did about it.
function say(text, error = false, note = '') {
  $('message').textContent = text;
  $('message').title = text;
  $('message').className = error ? 'error' : '';
  $('message-note').textContent = note;
}
$('message').addEventListener('click', () => $('message').classList.toggle('unfolded'));
$('message').addEventListener('keydown', e => e.key === 'Enter' && $('message').classList.toggle('unfolded'));

// The sketch's feature count, for the browser test, and the first-use hint while there are none.
function showCount(doc) {
  document.body.dataset.features = doc.features.length;
  $('hint').hidden = doc.features.length > 0;
}

// Sends the sketch; on refusal, says why and goes back to the server's sketch. Resolves to
// whether the server took it. One at a time, in order: two edits in flight on two connections
// could otherwise land the older last. An edit made on top of a refused one is not sent: the
// page has gone back to the server's sketch since.
let sending = Promise.resolve();
let refusals = 0;
function send(doc) {
  const after = refusals;
  const sent = sending.then(() => (after === refusals ? sendNow(doc) : false));
  sending = sent.catch(() => {});
  return sent;
}

async function sendNow(doc) {
  const r = await api.putSketch(doc);
  if (!r.ok) {
    ++refusals;
    await backToServer(r.message);
    return false;
  }
  lastGood = JSON.parse(r.text);
  say('Saved.');
  return true;
}

// After a refusal the map shows the sketch the server holds (the refused edit, and any made on
// top of it, leave the undo history once their sends end: sendEdit); the settings form keeps
// what was typed there, to be fixed and applied again.
async function backToServer(message) {
  const doc = await api.getSketch();
  if (doc) {
    lastGood = doc;
    map.load(doc, false);
    showCount(doc);
    panel.keep(doc.exacity);
    history.push(JSON.stringify(map.sketch()));
    updateButtons();
  }
  say(message, true, 'Not saved: the map shows the sketch the server has.');
}

const map = new SketchMap('map', {
  edited: () => recordEdit(),
  selected: f => panel.select(f),
});
// For the browser test: the sketch as the page would send it, and the grid's labels.
window.exacityPage = {sketch: () => map.sketch(),
                      gridLabels: () => map.gridLabels.getSource().getFeatures().map(f => ({label: f.get('label'), axis: f.get('axis')}))};
const panel = new SettingsPanel({
  apply: async exacity => {
    const doc = map.sketch();
    doc.exacity = exacity;
    if (!(await send(doc))) return false;
    map.setSettings(exacity);
    history.push(JSON.stringify(map.sketch()));
    panel.show(exacity);
    return true;
  },
  featureEdited: () => recordEdit(),
  typo: (what, why) => say(what, true, `${why}. Not applied: fix the box and apply again.`),
});

// Sends an edit that is in the undo history as `text`; one the server did not take leaves it,
// so undo never brings back a sketch the server refused.
async function sendEdit(doc, text) {
  if (!(await send(doc))) history.forget(text);
  updateButtons();
}

function recordEdit() {
  const doc = map.sketch();
  const text = JSON.stringify(doc);
  showCount(doc);
  history.push(text);
  updateButtons();
  // An empty sketch is one the CLI refuses too: say so, without sending.
  if (!doc.features.length) return say('Draw a zone to start.');
  sendEdit(doc, text);
}

function restore(text) {
  if (text === null) return;
  const doc = JSON.parse(text);
  map.load(doc, false);
  showCount(doc);
  panel.show(doc.exacity);
  updateButtons();
  if (doc.features.length) sendEdit(doc, text);
}

function updateButtons() {
  $('undo').disabled = !history.canUndo();
  $('redo').disabled = !history.canRedo();
}

function setTool(tool) {
  for (const b of document.querySelectorAll('[data-tool]')) b.classList.toggle('active', b.dataset.tool === tool);
  map.setTool(tool);
}

for (const b of document.querySelectorAll('[data-tool]')) b.addEventListener('click', () => setTool(b.dataset.tool));
$('undo').addEventListener('click', () => restore(history.undo()));
$('redo').addEventListener('click', () => restore(history.redo()));
$('delete').addEventListener('click', () => map.deleteSelected());

document.addEventListener('keydown', e => {
  if (e.target.closest('input, textarea, select')) return;
  const ctrl = e.ctrlKey || e.metaKey;
  if (e.key === 'Enter') map.finishDrawing();
  else if (e.key === 'Escape') map.abortDrawing();
  else if (e.key === 'Delete' || e.key === 'Backspace') map.deleteSelected() && e.preventDefault();
  else if (ctrl && e.key.toLowerCase() === 'z' && !e.shiftKey) restore(history.undo());
  else if (ctrl && (e.key.toLowerCase() === 'y' || (e.key.toLowerCase() === 'z' && e.shiftKey))) restore(history.redo());
  else return;
  e.preventDefault();
});

// Open: a GeoJSON sketch from this computer, shown once the server has taken it.
$('open').addEventListener('click', () => $('open-file').click());
$('open-file').addEventListener('change', async e => {
  const file = e.target.files[0];
  e.target.value = '';
  if (!file) return;
  let doc;
  try {
    doc = JSON.parse(await file.text());
  } catch (x) {
    return say(`${file.name}: not JSON (${x.message})`, true);
  }
  if (!(await send(doc))) return;
  map.load(lastGood, true);
  showCount(lastGood);
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
});

// Save: the sketch as the server holds it, downloaded.
$('save').addEventListener('click', async () => {
  const doc = map.sketch();
  if (doc.features.length && !(await send(doc))) return;
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([JSON.stringify(doc, null, 1)], {type: 'application/geo+json'}));
  link.download = 'sketch.geojson';
  link.click();
  URL.revokeObjectURL(link.href);
});

$('heightmap').addEventListener('click', () => $('heightmap-file').click());
$('heightmap-file').addEventListener('change', async e => {
  const file = e.target.files[0];
  e.target.value = '';
  if (!file) return;
  const r = await api.putHeightmap(file);
  if (!r.ok) return say(r.message, true);
  lastGood = JSON.parse(r.text);
  map.setSettings(lastGood.exacity);
  map.showHeightmap();
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  say(`Heightmap ${file.name} loaded.`);
});

// Models…: a model library's files, which the server checks as the CLI does; the sketch
// then names it.
$('models').addEventListener('click', () => $('models-file').click());
$('models-file').addEventListener('change', async e => {
  const files = [...e.target.files];
  e.target.value = '';
  if (!files.length) return;
  const r = await api.postModels(files);
  if (!r.ok) return say(r.message, true);
  lastGood = JSON.parse(r.text);
  map.setSettings(lastGood.exacity);
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  say(`Model library ${lastGood.exacity.models} loaded (${files.length} files).`);
});

$('cancel').addEventListener('click', async () => {
  const r = await api.cancelJob();
  if (!r.ok) say(r.message, true);
});

// Generate, with a progress bar driven by the server's stage events.
$('generate').addEventListener('click', async () => {
  const r = await api.startGenerate();
  if (!r.ok) return say(r.message, true);
  say('Generating…');
});

function showProgress(event) {
  if (event.count) $('progress').value = (event.index - 1 + (event.fraction || 0)) / event.count;
  $('stage').textContent = `${event.index}/${event.count} ${event.stage}`;
}

async function showCity() {
  cityLayers = cityLayers || new CityLayers(map.city);
  const report = await cityLayers.load();
  map.layer.setOpacity(0.5);  // the sketch stays editable over the city, without hiding its streets
  if (explore) await loadExplore();
  return report;
}

function cityBounds() {
  const zones = cityLayers?.data.zones;
  const box = [Infinity, Infinity, -Infinity, -Infinity];
  const grow = c => (typeof c[0] === 'number' ? (box[0] = Math.min(box[0], c[0]), box[1] = Math.min(box[1], c[1]),
                     box[2] = Math.max(box[2], c[0]), box[3] = Math.max(box[3], c[1])) : c.forEach(grow));
  for (const f of zones?.features || []) grow(f.geometry.coordinates);
  return Number.isFinite(box[0]) ? box : [0, 0, 100, 100];
}

async function loadExplore() {
  if (!cityLayers) return;
  await explore.load(cityBounds(), cityLayers.data);
}

// Every output the server has, to download: the city's files once generated, the still once
// rendered (docs/serve.md, The API).
let rendered = false;
function showDownloads() {
  const files = [['/api/sketch', 'sketch.geojson'], ['/api/city.glb', 'city.glb'], ['/api/map.svg', 'map.svg'],
                 ['/api/report', 'report.json'],
                 ...Object.keys(cityLayers?.data || {}).map(n => [`/api/layers/${n}.geojson`, `${n}.geojson`])];
  if (rendered) files.push(['/api/render/still.png', 'still.png'], ['/api/render/still.json', 'still.json']);
  $('downloads').replaceChildren(...files.map(([url, name]) => {
    const item = document.createElement('li'), link = document.createElement('a');
    link.href = url;
    link.download = name;
    link.textContent = name;
    item.append(link);
    return item;
  }));
}

let stageEvent = {index: 0, count: 1, stage: ''};
// Each (re)connection of the event stream starts with the status as it is; only a job seen
// running and then ending changes the page.
let lastState = null;
api.listen({
  stage: e => { stageEvent = e; showProgress(e); },
  progress: e => showProgress({...stageEvent, fraction: e.fraction, stage: e.stage}),
  state: async s => {
    const ended = lastState === 'running' && s.state !== 'running';
    lastState = s.state;
    document.body.dataset.job = s.state;
    $('generate').disabled = s.state === 'running';
    $('render-view').disabled = s.state === 'running';
    $('cancel').disabled = s.state !== 'running';
    if (!ended) return;
    if (s.state === 'failed') say(`${s.job} failed: ${s.error}`, true);
    if (s.state === 'cancelled') say(`${s.job} ${s.error}`);
    if (s.state !== 'done') {
      $('progress').value = 0;
      $('stage').textContent = `${s.job} ${s.state}`;
      return;
    }
    $('progress').value = 1;
    $('stage').textContent = `${s.job} done`;
    if (s.job === 'generate') {
      await showCity();
      showDownloads();
      say('City generated.');
      document.body.dataset.city = 'shown';
    } else if (s.job === 'render') {
      $('render-image').src = '/api/render/still.png?v=' + Date.now();
      $('render-result').hidden = false;
      rendered = true;
      showDownloads();
      say('Rendered.');
    }
  },
});

// Map and Explore.
for (const b of document.querySelectorAll('[data-view]'))
  b.addEventListener('click', async () => {
    const view = b.dataset.view;
    for (const o of document.querySelectorAll('[data-view]')) o.classList.toggle('active', o === b);
    $('map-view').hidden = view !== 'map';
    $('explore-view').hidden = view !== 'explore';
    if (view === 'map') return map.map.updateSize();
    if (!explore) {
      const {ExploreView} = await import('./explore.js');
      explore = new ExploreView($('three'), $('minimap'));
      window.exacityExplore = explore;  // for the browser test, which orbits it
      await loadExplore();
    }
    explore.resize();
  });

$('render-image').addEventListener('click', () => $('render-result').classList.toggle('large'));

$('render-view').addEventListener('click', async () => {
  if (!explore) return;
  const w = explore.container.clientWidth, h = explore.container.clientHeight;
  const scale = Math.min(1, 480 / w);
  const r = await api.startRender({camera: explore.spec(), size: `${Math.max(8, Math.round(w * scale))}x${Math.max(8, Math.round(h * scale))}`,
                                   spp: Number(new URLSearchParams(location.search).get('spp') || 8), fov: 45, minimap: true});
  if (!r.ok) return say(r.message, true);
  say('Rendering…');
});

// Start: the server's sketch, and its city if one is there.
(async () => {
  const doc = await api.getSketch();
  map.load(doc, true);
  showCount(doc);
  panel.show(doc.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  const status = await api.getJson('/api/status');
  rendered = status.render;
  if (status.city) {
    await showCity();
    showDownloads();
    document.body.dataset.city = 'shown';
  }
  document.body.dataset.ready = 'yes';
})();
