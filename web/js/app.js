// exacity serve's page: the sketch editor, generation with its progress, the generated layers
// and the 3D view (docs/serve.md). Every sketch edit is sent to the server, which
// checks it as the CLI does; a refusal shows the CLI's message and the page goes back to the
// server's sketch, so what is drawn is always what a generation uses.
import * as api from './api.js';
import {SketchHistory} from './history.js';
import {SketchMap} from './sketch_map.js';
import {SettingsPanel} from './settings_panel.js';
import {CityLayers} from './city_layers.js';
import {zoneColours, rgba} from './colours.js';

const $ = id => document.getElementById(id);
const history = new SketchHistory();
let explore = null;  // made when first shown: three.js loads only then
let cityLayers = null;
let lastGood = null;
for (const b of document.querySelectorAll('button.zone')) b.style.setProperty('--zone', rgba(zoneColours[b.dataset.tool], 1));

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
let lastRefusal = '';
// Set once the server refuses this page's token (it was restarted, so its token is another):
// what is drawn stays here, to be saved to a file, since no edit can reach the server now.
let serverLost = false;
function send(doc) {
  const after = refusals;
  const sent = sending.then(() => (after === refusals ? sendNow(doc) : false));
  sending = sent.catch(() => {});
  return sent;
}

async function sendNow(doc) {
  const r = await api.putSketch(doc);
  if (r.status === 403) {
    serverLost = true;
    document.body.dataset.server = 'lost';
    lastRefusal = r.message;
    say(r.message, true, 'Not saved: the server does not know this page (restarted?). What is drawn stays here: ' +
                         'Save downloads it, to Open in the page at the address exacity serve printed.');
    return false;
  }
  if (!r.ok) {
    ++refusals;
    lastRefusal = r.message;
    await backToServer(r.message);
    return false;
  }
  lastGood = JSON.parse(r.text);
  say('Saved.');
  showLikeIfChanged();
  if ($('auto-generate').checked) generateAfterEdit();
  return true;
}

// With "after each edit" ticked, each edit the server took is generated: at once, or when
// the job running ends (one generation then covers every edit made meanwhile). The setting
// is kept in the browser.
let generateWhenIdle = false;
async function generateAfterEdit() {
  // A generation that has answered is only validating a city this one replaces: the server
  // stops it for this one.
  if (lastState === 'running' && !answered) {
    generateWhenIdle = true;
    return;
  }
  const r = await api.startGenerate();
  if (r.status === 409) generateWhenIdle = true;
  else if (!r.ok) say(r.message, true);
}
$('auto-generate').checked = localStorage.getItem('exacity.autoGenerate') === 'true';
$('auto-generate').addEventListener('change', () => localStorage.setItem('exacity.autoGenerate', $('auto-generate').checked));

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
    showLikeIfChanged();
  }
  say(message, true, 'Not saved: the map shows the sketch the server has.');
}

const map = new SketchMap('map', {
  edited: () => recordEdit(),
  selected: f => panel.select(f),
});
// For the browser test: the sketch as the page would send it, and the grid's labels.
window.exacityPage = {sketch: () => map.sketch(),
                      // Resolves once the map is drawn with every tile in (after zooming out).
                      drawn: (zoomOut = false) => new Promise(resolve => {
                        map.map.once('rendercomplete', () => resolve());
                        if (zoomOut) map.map.getView().setResolution(map.map.getView().getResolution() * 2);
                        map.map.render();
                      }),
                      lonLat: c => map.lonLat.toLonLat(c),
                      // The GeoTIFF basemap's colour at sketch points as drawn, null where it has none.
                      geotiffAt: points => points.map(c => {
                        const data = map.geotiff.getSource() && map.geotiff.getData(map.map.getPixelFromCoordinate(c));
                        return data ? [...data] : null;
                      }),
                      gridLabels: () => map.gridLabels.getSource().getFeatures().map(f => ({
                        label: f.get('label'), axis: f.get('axis'), at: map.map.getPixelFromCoordinate(f.getGeometry().getCoordinates())})),
                      // Moves the map's view by (dx, dy) pixels; resolves once the grid is drawn again.
                      pan: (dx, dy) => new Promise(resolve => {
                        const view = map.map.getView(), [x, y] = view.getCenter(), r = view.getResolution();
                        map.map.once('moveend', () => resolve());
                        view.setCenter([x + dx * r, y - dy * r]);
                      })};
// The sketch with `exacity` as its settings, sent; resolves to the refusal's message, or null
// when the server took them.
async function applySettings(exacity) {
  const doc = map.sketch();
  doc.exacity = exacity;
  if (!(await send(doc))) return lastRefusal;
  map.setSettings(exacity);
  history.push(JSON.stringify(map.sketch()));
  panel.show(exacity);
  return null;
}
const panel = new SettingsPanel({
  apply: applySettings,
  featureEdited: () => recordEdit(),
  typo: (what, why) => say(what, true, `${why}. Not applied: fix the box and apply again.`),
});

// Sends an edit that is in the undo history as `text`; one the server did not take leaves it,
// so undo never brings back a sketch the server refused.
async function sendEdit(doc, text) {
  if (!(await send(doc)) && !serverLost) history.forget(text);
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

// The model library the sketch names (GET /api/models): its manifest, and each model's kind
// and the zone types it stands in; the built-in trees and lamps otherwise.
async function showLibrary() {
  const library = await api.getJson('/api/models');
  if (!library) return;
  const builtin = library.builtin.length ? `built-in ${library.builtin.map(kind => kind + 's').join(' and ')}` : 'no built-in models';
  $('library-name').textContent = library.file ? `${library.file} (${library.models.length} models; ${builtin})` :
                                                 `none: ${builtin} (Models… loads a library)`;
  $('library-models').hidden = !library.models.length;
  $('library-models').tBodies[0].replaceChildren(...library.models.map(m => {
    const row = document.createElement('tr');
    for (const text of [m.name, m.kind, m.zones.join(', ')]) row.insertCell().textContent = text;
    row.title = `weight ${m.weight}, ${m.size.map(v => v.toFixed(1)).join(' × ')} m` + (m.lot ? `, lot ${m.lot.join(' × ')} m` : '');
    return row;
  }));
}

// Basemap: tiles from an XYZ URL the user names, under a sketch with a place on Earth (its
// CRS's lon/lat from the server); nothing is fetched until a URL is named. Or a GeoTIFF of
// the work folder, which the server warps into the sketch's coordinates.
let lonlat = null;
async function showPlace() {
  lonlat = await api.getJson('/api/lonlat');
  $('basemap-where').textContent = lonlat?.epsg ? `The sketch is in EPSG:${lonlat.epsg}: name a tile server or a GeoTIFF to draw under it.` :
                                                  'The sketch has no place on Earth (no CRS): no tiles, but a GeoTIFF without a CRS in its coordinates.';
  $('basemap-url').disabled = $('basemap-show').disabled = !lonlat?.epsg;
  if (map.basemap.getSource()) map.setBasemap($('basemap-url').value.trim(), lonlat);
  if (map.geotiff.getSource()) await showGeoTiff();  // placed again over the new sketch, or dropped
}
// The GeoTIFF named, placed by the server: its refusal (no such file, no CRS, far away) said.
// The basemaps shown are kept in the browser, so a reload draws them again.
async function showGeoTiff() {
  const name = $('geotiff-name').value.trim();
  const r = await api.placeBasemap(name);
  if (!r.ok) {
    map.setGeoTiff(null);
    localStorage.removeItem('exacity.geotiff');
    return say(r.message, true);
  }
  const placed = JSON.parse(r.text);
  map.setGeoTiff(placed);
  localStorage.setItem('exacity.geotiff', name);
  say(`Basemap ${placed.file} under the sketch${placed.crs ? `, warped into ${placed.crs}` : ''}.`);
}
function showTiles() {
  const url = $('basemap-url').value.trim();
  if (!/^https?:\/\/.*\{z\}.*\{x\}.*\{y\}/.test(url)) return say('A basemap URL has {z}, {x} and {y} in it, such as https://tile.example.org/{z}/{x}/{y}.png', true);
  map.setBasemap(url, lonlat);
  localStorage.setItem('exacity.basemap', url);
  say(`Basemap ${url} under the sketch.`);
}
async function showSavedBasemaps() {
  const url = localStorage.getItem('exacity.basemap'), name = localStorage.getItem('exacity.geotiff');
  if (url) $('basemap-url').value = url;
  if (url && lonlat?.epsg) showTiles();
  if (name) {
    $('geotiff-name').value = name;
    await showGeoTiff();
  }
}
$('geotiff-show').addEventListener('click', showGeoTiff);
$('basemap-show').addEventListener('click', showTiles);
$('basemap-hide').addEventListener('click', () => {
  map.setBasemap(null);
  map.setGeoTiff(null);
  localStorage.removeItem('exacity.basemap');
  localStorage.removeItem('exacity.geotiff');
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
  await showPlace();  // before the view moves to it: a basemap of the sketch before is dropped
  map.load(lastGood, true);
  showCount(lastGood);
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  showLibrary();
});

// Save: the sketch as the server holds it, downloaded; as drawn when the server no longer knows this page.
$('save').addEventListener('click', async () => {
  const doc = map.sketch();
  if (doc.features.length && !(await send(doc)) && !serverLost) return;
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
  const r = await api.postFiles('/api/models', files);
  if (!r.ok) return say(r.message, true);
  lastGood = JSON.parse(r.text);
  map.setSettings(lastGood.exacity);
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  say(`Model library ${lastGood.exacity.models} loaded (${files.length} files).`);
  showLibrary();
});

// Like a place…: a real place's files (an OSM extract, or footprints with a shapefile's
// companions), which the server measures as generate --like does; the sketch then names it,
// and the panel shows what was measured and the settings it gives each zone type.
$('like').addEventListener('click', () => $('like-file').click());
$('like-file').addEventListener('change', async e => {
  const files = [...e.target.files];
  e.target.value = '';
  if (!files.length) return;
  say(`Measuring ${files.map(f => f.name).join(', ')}…`);
  const r = await api.postFiles('/api/like', files);
  if (!r.ok) return say(r.message, true, 'Not taken: the sketch looks like the place it named before, if any.');
  lastGood = JSON.parse(r.text);
  map.setSettings(lastGood.exacity);
  panel.show(lastGood.exacity);
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  say(`${lastGood.exacity.like} measured: Generate builds the zone types like it.`);
  await showLike();  // measured again: a file of the same name may hold another place
});
$('like-clear').addEventListener('click', async () => {
  const exacity = {...(lastGood?.exacity || {})};
  delete exacity.like;
  if ((await applySettings(exacity)) === null) say('The sketch looks like no place now.');
});

// What the place the sketch names measures (GET /api/like), per built-up zone type: its
// mapped buildings' footprint median and p90, and the generated ones' after a generation
// that looked like it (report.json's footprints_by_zone); the settings it gives each.
let likeShown;  // the place whose figures are shown
let lastReport = null;
async function showLikeIfChanged() {
  const like = lastGood?.exacity?.like ?? null;
  if (like !== likeShown) await showLike();
}
async function showLike() {
  const r = await api.getLike();
  likeShown = r.ok ? JSON.parse(r.text).file : lastGood?.exacity?.like ?? null;
  $('like-panel').hidden = !likeShown;
  if (!r.ok) {
    $('like-name').textContent = r.message;
    $('like-name').className = 'error';
    $('like-figures').tBodies[0].replaceChildren();
    $('like-set').replaceChildren();
    return;
  }
  const {file, measured} = JSON.parse(r.text);
  if (!measured) return;
  $('like-name').className = '';
  $('like-name').textContent = `${file}: ${measured.footprints.toLocaleString('en')} footprints; zones from ${measured.zones_from}`;
  const generated = lastReport?.like?.file === file ? lastReport.footprints_by_zone || {} : {};
  const m2 = v => (typeof v === 'number' ? Math.round(v).toLocaleString('en') : '–');
  const rows = [], set = [];
  for (const zone of ['residential', 'commercial', 'industrial'].filter(z => z in measured.zones)) {
    const z = measured.zones[zone];
    const area = z.measured?.area_m2, g = generated[zone]?.generated;
    const row = document.createElement('tr');
    row.dataset.zone = zone;
    for (const text of [zone, z.buildings, area ? `${m2(area.median)} / ${m2(area.p90)}` : 'too few',
                        g?.footprints ? `${m2(g.median_m2)} / ${m2(g.p90_m2)}` : '–'])
      row.insertCell().textContent = text;
    rows.push(row);
    const item = document.createElement('li');
    item.dataset.zone = zone;
    if (z.kept_defaults) item.textContent = `${zone}: defaults kept (${z.kept_defaults})`;
    else item.textContent = `${zone}: ` + (Object.entries(z.set).map(([k, v]) => `${k.replace(/_/g, ' ')} ${JSON.stringify(v)}`).join(', ') || 'nothing set') +
                            (z.kept_as_the_sketch_sets ? `; the sketch's own ${z.kept_as_the_sketch_sets.join(', ')} kept` : '');
    set.push(item);
  }
  $('like-figures').tBodies[0].replaceChildren(...rows);
  $('like-set').replaceChildren(...set);
}

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

// Time left: the job's time so far over the share of it done. A generation's stages are
// weighed by their seconds in the last report (the stage clock's timings_s), equally without
// one; a render's share is its samples done.
let stageSeconds = {};
let jobClock = null;  // while a job runs: its start, its share done, the stages seen
function shareDone(event) {
  const known = Object.values(stageSeconds);
  if (!event.count) return 0;
  if (jobClock.job !== 'generate' || !known.length) return (event.index - 1 + (event.fraction || 0)) / event.count;
  const mean = known.reduce((a, b) => a + b, 0) / known.length;
  const weight = name => stageSeconds[name] ?? mean;
  const names = Object.keys(stageSeconds);
  // Stages not yet seen in this run are the last report's that have not come, and any others.
  const before = jobClock.seen.slice(0, -1).reduce((a, n) => a + weight(n), 0);
  const later = names.filter(n => !jobClock.seen.includes(n)).reduce((a, n) => a + weight(n), 0);
  const unnamed = Math.max(0, event.count - jobClock.seen.length - names.filter(n => !jobClock.seen.includes(n)).length) * mean;
  const now = weight(event.stage);
  return (before + now * (event.fraction || 0)) / (before + now + later + unnamed);
}

function showTimeLeft() {
  const box = $('time-left');
  if (!jobClock) return (box.textContent = '');
  const elapsed = (Date.now() - jobClock.start) / 1000, done = jobClock.done;
  if (done < 0.005 || elapsed < 0.5) return (box.textContent = 'estimating…');
  const left = elapsed * (1 - done) / done;
  box.textContent = `about ${left < 90 ? Math.max(1, Math.round(left)) + ' s' : Math.round(left / 60) + ' min'} left`;
}
setInterval(showTimeLeft, 1000);

function showProgress(event) {
  if (!jobClock) jobClock = {start: Date.now(), job: 'generate', seen: [], done: 0};
  if (event.stage && jobClock.seen.at(-1) !== event.stage) jobClock.seen.push(event.stage);
  jobClock.done = shareDone(event);
  if (event.count) $('progress').value = (event.index - 1 + (event.fraction || 0)) / event.count;
  $('stage').textContent = `${event.index}/${event.count} ${event.stage}`;
  showTimeLeft();
}

async function showCity() {
  cityLayers = cityLayers || new CityLayers(map.city);
  const report = await cityLayers.load();
  lastReport = report;
  stageSeconds = report?.timings_s || {};
  if (report?.like) await showLike();
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

// Every output the server has, to download: the city's files once generated (those the
// status lists: glTF, CityJSON, OBJ, PLY, OSM, GeoPackage, the SVG map), the still once
// rendered (docs/serve.md, The API).
let rendered = false;
let cityFiles = [];
async function showDownloads() {
  cityFiles = (await api.getJson('/api/status'))?.files || cityFiles;
  const files = [['/api/sketch', 'sketch.geojson'], ...cityFiles.map(name => [`/api/files/${name}`, name]),
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

// A generation answers once what the page shows is written (the layers, the tiles, the
// report), then validates; the page shows the city at the answer and the validation's
// verdict when the job ends.
async function showGenerated() {
  const report = await showCity();
  await showDownloads();
  document.body.dataset.city = 'shown';
  return report;
}

let stageEvent = {index: 0, count: 1, stage: ''};
// Each (re)connection of the event stream starts with the status as it is; only a job seen
// running and then ending changes the page.
let lastState = null;
let answered = false;  // the running generation has answered (its city is shown)
let shownAtAnswer = false;  // and this page showed it then
// What a job's answer and end show, one after the other in the events' order (showing the
// answer fetches the layers, and the end may come meanwhile).
let showing = Promise.resolve();
const inTurn = f => (showing = showing.then(f, f));
api.listen({
  stage: e => { stageEvent = e; showProgress(e); },
  progress: e => showProgress({...stageEvent, fraction: e.fraction, stage: e.stage}),
  answered: e => {
    if (lastState !== 'running' || e.job !== 'generate') return;
    answered = shownAtAnswer = true;
    $('generate').disabled = false;
    if (generateWhenIdle) {
      generateWhenIdle = false;
      generateAfterEdit();
    }
    inTurn(async () => {
      await showGenerated();
      say('City generated; validating it…');
    });
  },
  state: s => {
    const ended = lastState === 'running' && s.state !== 'running';
    if (s.state === 'running' && lastState !== 'running') jobClock = {start: Date.now(), job: s.job, seen: [], done: 0};
    if (s.state !== 'running') jobClock = null;
    showTimeLeft();
    lastState = s.state;
    answered = s.state === 'running' && Boolean(s.answered);
    const shown = shownAtAnswer;
    if (s.state === 'running' && !s.answered) shownAtAnswer = false;
    document.body.dataset.job = s.state;
    if (ended && generateWhenIdle) {
      generateWhenIdle = false;
      generateAfterEdit();
    }
    $('generate').disabled = s.state === 'running' && !answered;
    $('render-view').disabled = s.state === 'running';
    $('cancel').disabled = s.state !== 'running';
    if (ended) inTurn(() => showEnd(s, shown));
  },
});

// A job's end: its message, and for a generation the city (or, shown at its answer, the
// report with validation's verdict).
async function showEnd(s, shown) {
  if (s.state === 'failed') say(`${s.job} failed: ${s.error}`, true);
  if (s.state === 'cancelled') say(`${s.job} ${s.error}`);
  if (s.job === 'generate' && shown && s.state !== 'done') {
    // The city shown stays; the report says why it was not validated.
    cityLayers?.showReport(await api.getJson('/api/report'));
    $('stage').textContent = `${s.job} ${s.state}`;
    return;
  }
  if (s.state !== 'done') {
    $('progress').value = 0;
    $('stage').textContent = `${s.job} ${s.state}`;
    return;
  }
  $('progress').value = 1;
  $('stage').textContent = `${s.job} done`;
  if (s.job === 'generate') {
    const report = shown ? await api.getJson('/api/report') : await showGenerated();
    if (shown) cityLayers.showReport(lastReport = report);
    say(report?.validation?.ok ? 'City generated and validated.' : 'City generated.');
    document.body.dataset.city = 'validated';
  } else if (s.job === 'render') {
    $('render-image').src = '/api/render/still.png?v=' + Date.now();
    $('render-result').hidden = false;
    rendered = true;
    showDownloads();
    say('Rendered.');
  }
}

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

for (const b of document.querySelectorAll('[data-mode]'))
  b.addEventListener('click', () => {
    if (!explore) return;
    explore.setMode(b.dataset.mode);
    for (const o of document.querySelectorAll('[data-mode]')) o.classList.toggle('active', o === b);
    explore.renderer.domElement.focus();
  });
$('fit-view').addEventListener('click', () => {
  if (!explore) return;
  explore.fit();
  for (const o of document.querySelectorAll('[data-mode]')) o.classList.toggle('active', o.dataset.mode === 'orbit');
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
  lastGood = doc;
  await Promise.all([panel.build(), showLibrary(), showPlace(), showLikeIfChanged()]);
  await showSavedBasemaps();
  history.push(JSON.stringify(map.sketch()));
  updateButtons();
  const status = await api.getJson('/api/status');
  rendered = status.render;
  if (status.city) {
    await showCity();
    await showDownloads();
    document.body.dataset.city = 'shown';
  }
  document.body.dataset.ready = 'yes';
})();
