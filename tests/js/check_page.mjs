// The page of exacity serve in a real browser (Debian's chromium driven by puppeteer-core):
// the first-use hint, draw a zone and a road with the mouse, read the pointer's coordinates,
// move the zone with Ctrl-drag, delete the road with Del, undo, have edits and settings
// refused (the page back at the server's sketch, the message on one line), reload, generate,
// find the generated layers and the downloads, orbit the 3D view, see its tiles' levels
// switch from far to near, walk and fly, pick a building, render it, upload a model library
// (listed with its models), look like a real place (its file uploaded, measured, generated
// like it), draw an XYZ basemap and a GeoTIFF under a sketch in UTM, cancel a generation (its time left shown); the settings' forms
// made from the server's table, a value refused next to its field; the page's colours the
// server's; no console error throughout but the refusals asked for. Usage: node check_page.mjs EXACITY_BINARY OUT_DIR
// (screenshots go to OUT_DIR). Exits 1 on the first failed check. DEBUG_PAGE=1 logs every
// request the page makes, with its time.
import {spawn} from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import puppeteer from 'puppeteer-core';
// The page's own copy of geotiff.js (an OpenLayers dependency), to write a test GeoTIFF.
import {writeArrayBuffer} from '../../web/node_modules/geotiff/dist-module/geotiff.js';

const [binary, out] = process.argv.slice(2);
if (!binary || !out) {
  console.error('usage: node check_page.mjs EXACITY_BINARY OUT_DIR');
  process.exit(2);
}
fs.rmSync(out, {recursive: true, force: true});
fs.mkdirSync(out, {recursive: true});

const started = Date.now();
function check(ok, what) {
  if (!ok) throw new Error(`check failed: ${what}`);
  console.log(`ok (${((Date.now() - started) / 1000).toFixed(1)} s): ${what}`);
}

// The server, on a free port of 127.0.0.1, with a work folder of its own.
const server = spawn(binary, ['serve', '--port', '0', '--work', path.join(out, 'work')], {stdio: ['ignore', 'pipe', 'pipe']});
let serverLog = '';
server.stderr.on('data', d => { serverLog += d; });
// The address it prints may carry a token (?token=...), which the page's first load turns
// into a cookie; the test's own requests send it as a bearer token.
const [base, token] = await new Promise((resolve, reject) => {
  let text = '';
  server.stdout.on('data', d => {
    text += d;
    const m = text.match(/serving (http:\/\/127\.0\.0\.1:\d+\/)(\?token=(\w+))?/);
    if (m) resolve([m[1], m[3]]);
  });
  server.on('exit', code => reject(new Error(`exacity serve exited with ${code}: ${serverLog}`)));
  setTimeout(() => reject(new Error('exacity serve did not start in 30 s')), 30000);
});
const serverExit = new Promise(resolve => server.on('exit', (code, signal) => resolve({code, signal})));

const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  // --no-sandbox: CI runs as root; SwiftShader gives the headless browser WebGL for three.js.
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1280,800'],
});
const errors = [];
let failed = false;
try {
  const page = await browser.newPage();
  await page.setViewport({width: 1280, height: 800});
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', e => errors.push(String(e)));
  page.on('response', r => { if (r.status() >= 400) errors.push(`HTTP ${r.status()}: ${r.url()}`); });
  // A request that failed is an error, but for two: the event stream, which the page holds
  // open until it closes, and a whole answer (200, its headers in) that chromium reports as
  // aborted when the page's stream reader (three.js's FileLoader) finished the body first;
  // that body was whole, since the 3D view below is built from it.
  page.on('requestfailed', r => {
    const whole = r.failure()?.errorText === 'net::ERR_ABORTED' && r.response()?.status() === 200;
    if (!r.url().includes('/api/events') && !whole) errors.push(`request failed: ${r.url()} (${r.failure()?.errorText})`);
  });
  page.on('request', r => { if (process.env.DEBUG_PAGE) console.log(Date.now() - started, 'request', r.url()); });
  page.on('requestfinished', r => { if (process.env.DEBUG_PAGE) console.log(Date.now() - started, 'finished', r.url()); });
  page.on('requestfailed', r => { if (process.env.DEBUG_PAGE) console.log(Date.now() - started, 'failed', r.url(), r.failure()?.errorText, r.response()?.status(), JSON.stringify(r.response()?.headers())); });
  const get = url => fetch(new URL(url, base), {headers: token ? {Authorization: `Bearer ${token}`} : {}});
  const sketch = async () => (await get('/api/sketch')).json();
  const ready = () => page.waitForSelector('body[data-ready="yes"]', {timeout: 30000});
  const features = n => page.waitForSelector(`body[data-features="${n}"]`, {timeout: 30000});
  // The page's features as it would send them, and the server's, to the millimetre.
  const rounded = features => JSON.stringify(features, (k, v) => (typeof v === 'number' ? Math.round(v * 1000) : v));
  const pageFeatures = async () => rounded((await page.evaluate(() => window.exacityPage.sketch())).features);
  const serverFeatures = async () => rounded((await sketch()).features);
  const message = () => page.$eval('#message', m => m.textContent);
  // The server has taken the page's latest edit.
  const saved = async n => {
    for (let i = 0; i < 100; ++i) {
      if ((await sketch()).features.length === n) return;
      await new Promise(r => setTimeout(r, 100));
    }
    throw new Error(`the server's sketch never had ${n} features`);
  };

  // Two samples a pixel: the still's look is serve_test's and render_test's business.
  await page.goto(base + (token ? `?token=${token}&spp=2` : '?spp=2'), {waitUntil: 'load'});
  await ready();
  // What some elements showed over time (the tiles' loading line, the time left), since a
  // check after the fact would miss a state that came and went.
  const watch = () => page.evaluate(() => {
    window.exacitySeen = {};
    for (const id of ['tiles-loading', 'time-left', 'message']) {
      const e = document.getElementById(id), seen = window.exacitySeen[id] = [];
      new MutationObserver(() => seen.push(e.hidden ? '(hidden)' : e.textContent))
          .observe(e, {attributes: true, childList: true, characterData: true, subtree: true});
    }
  });
  const seen = id => page.evaluate(id => window.exacitySeen[id], id);
  const few = list => [...new Set(list)].slice(0, 6).join(' | ');
  // The page draws in the program's colours (GET /api/palette), none of its own.
  const palette = await (await get('/api/palette')).json();
  const buttonColour = await page.$eval('button[data-tool="residential"]', b => getComputedStyle(b).borderLeftColor);
  check(buttonColour === `rgb(${[1, 3, 5].map(i => parseInt(palette.sketch_zones.residential.slice(i, i + 2), 16)).join(', ')})`,
        `the residential tool in the program's colour (${buttonColour}, ${palette.sketch_zones.residential})`);
  // The settings' forms, one per zone type, made from the table the CLI reads.
  const table = await (await get('/api/settings')).json();
  const formField = (zone, key) => `.zone-form[data-zone="${zone}"] .setting[data-key="${key}"]`;
  const areaField = await page.$eval(`${formField('residential', 'block_area')} input`, i => ({
    min: i.min, max: i.max, placeholder: i.placeholder, unit: i.parentElement.querySelector('.unit').textContent,
    title: i.parentElement.title}));
  const area = table.zones.residential.find(r => r.key === 'block_area');
  check(areaField.min === String(area.min) && areaField.max === String(area.max) && areaField.placeholder === '12000' &&
        areaField.unit === 'm²' && areaField.title === area.description,
        `the residential form's block area field is the table's: ${JSON.stringify(areaField)}`);
  check(await page.$eval(`${formField('commercial', 'block_area')} input`, i => i.placeholder) === '15000',
        'the commercial form shows its own default');
  for (const zone of ['residential', 'commercial', 'industrial'])
    check(await page.$$eval(`.zone-form[data-zone="${zone}"] .setting`, rows => rows.map(r => r.dataset.key).join()) ===
          table.zones[zone].map(r => r.key).join(), `the ${zone} form has every key of the table, in its order`);
  check(await page.$eval(`${formField('residential', 'layout')} select`, s => [...s.options].map(o => o.textContent).join()) ===
        'default (growth),growth,grammar,voronoi,streets', 'the layout field offers the layouts the CLI knows');
  const box = await (await page.$('#map')).boundingBox();
  const at = (dx, dy) => [box.x + box.width / 2 + dx, box.y + box.height / 2 + dy];
  const visible = selector => page.$eval(selector, e => e.checkVisibility());
  check(await visible('#hint') && /Residential/.test(await page.$eval('#hint', h => h.textContent)),
        'the empty page says what to click first');
  check(await page.$eval('#hint', h => {
    const r = h.getBoundingClientRect();
    return document.elementFromPoint(r.x + r.width / 2, r.y + r.height / 2).closest('#map') !== null;
  }), 'a click on the hint reaches the map under it');

  // A residential zone: four clicks and a double-click on the last corner.
  await page.click('[data-tool="residential"]');
  for (const [dx, dy] of [[-150, -100], [150, -100], [150, 100]]) {
    await page.mouse.click(...at(dx, dy));
    await new Promise(r => setTimeout(r, 150));
  }
  await page.mouse.click(...at(-150, 100), {count: 2});
  await features(1);
  await saved(1);
  let s = await sketch();
  check(s.features[0].properties.zone === 'residential' && s.features[0].geometry.type === 'Polygon',
        'a residential zone drawn by clicking reaches the server');
  check(!(await visible('#hint')), 'the hint goes once there is a feature');
  // The map's corner shows the pointer's coordinates: over the first corner clicked, that
  // corner's as the server has it.
  await page.mouse.move(...at(-150, -100));
  const pointer = await page.$eval('.ol-mouse-position', e => e.textContent);
  const [px, py] = (/^x (-?[\d.]+) m, y (-?[\d.]+) m$/.exec(pointer) || []).slice(1).map(Number);
  const corner = s.features[0].geometry.coordinates[0][0];
  check(Math.abs(px - corner[0]) <= 0.05 && Math.abs(py - corner[1]) <= 0.05,
        `the pointer's coordinates shown (${pointer}) are the corner's (${corner})`);

  // A highway across it, closed with Enter.
  await page.click('[data-tool="highway"]');
  await page.mouse.click(...at(-220, 0));
  await new Promise(r => setTimeout(r, 150));
  await page.mouse.click(...at(220, 10));
  await page.keyboard.press('Enter');
  await features(2);
  await saved(2);
  s = await sketch();
  check(s.features[1].properties.road === 'highway' && s.features[1].properties.width === 24, 'a highway drawn');

  // Ctrl-drag moves the zone.
  await page.click('[data-tool="select"]');
  const before = s.features[0].geometry.coordinates[0][0];
  await page.keyboard.down('Control');
  await page.mouse.move(...at(-100, -60));
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(...at(-100 + 4 * i, -60));
  await page.mouse.up();
  await page.keyboard.up('Control');
  await new Promise(r => setTimeout(r, 500));
  s = await sketch();
  const after = s.features[0].geometry.coordinates[0][0];
  check(Math.abs(after[0] - before[0] - 80) < 8 && Math.abs(after[1] - before[1]) < 2,
        `Ctrl-drag moved the zone by 40 px east (${before} to ${after})`);

  // Click the road, Del deletes it; Ctrl-Z brings it back.
  await page.mouse.click(...at(200, 9));
  await page.waitForSelector('#feature-panel:not([hidden])', {timeout: 30000});
  await page.keyboard.press('Delete');
  await features(1);
  await saved(1);
  check((await sketch()).features[0].properties.zone === 'residential', 'Del deleted the selected road');
  await page.keyboard.down('Control');
  await page.keyboard.press('z');
  await page.keyboard.up('Control');
  await features(2);
  await saved(2);
  check((await sketch()).features.some(f => f.properties.road === 'highway'), 'undo brought the road back');

  // The road's width, edited in the side panel.
  await page.mouse.click(...at(200, 9));
  await page.waitForSelector('#feature-panel:not([hidden]) #width-row:not([hidden])', {timeout: 30000});
  await page.$eval('#road-width', i => { i.value = '16'; i.dispatchEvent(new Event('change')); });
  for (let i = 0; i < 50 && (await sketch()).features[1].properties.width !== 16; ++i) await new Promise(r => setTimeout(r, 100));
  check((await sketch()).features[1].properties.width === 16,
        `the road's width edited in the panel (${JSON.stringify((await sketch()).features[1].properties)}, ${await page.$eval('#message', m => m.textContent)})`);
  // A road has no zone type to set (the server refuses a feature with both).
  check(!(await visible('#zone-row')) && await visible('#road-row'), 'a selected road offers no Zone field');

  // A refused edit (a width the CLI refuses): the message is shown, and the page goes back to
  // the server's sketch, so later edits are taken (they were all refused, silently lost).
  await page.$eval('#road-width', i => { i.value = '900'; i.dispatchEvent(new Event('change')); });
  await page.waitForSelector('#message.error', {timeout: 30000});
  check(/width/.test(await message()) && /server/.test(await page.$eval('#message-note', n => n.textContent)),
        `the refused width's message is shown: ${await message()}`);
  check(await pageFeatures() === await serverFeatures(), 'after the refusal the page shows the server\'s sketch');
  check((await sketch()).features[1].properties.width === 16, 'the refused width is not the server\'s');
  // Two edits at once, the first refused: the second, made on top of it, is not sent, and
  // neither stays in the undo history.
  await page.mouse.click(...at(200, 9));
  await page.waitForSelector('#feature-panel:not([hidden]) #width-row:not([hidden])', {timeout: 30000});
  await page.$eval('#road-width', i => {
    for (const width of ['900', '20']) {
      i.value = width;
      i.dispatchEvent(new Event('change'));
    }
  });
  await page.waitForFunction(() => /width/.test(document.getElementById('message').textContent), {timeout: 30000});
  await new Promise(r => setTimeout(r, 500));
  check((await sketch()).features[1].properties.width === 16 && await pageFeatures() === await serverFeatures(),
        'the edit made on top of a refused one is dropped: the page shows the server\'s sketch');
  await page.click('[data-tool="park"]');
  for (const [dx, dy] of [[-300, 120], [-200, 120], [-200, 180]]) {
    await page.mouse.click(...at(dx, dy));
    await new Promise(r => setTimeout(r, 150));
  }
  await page.mouse.click(...at(-300, 180), {count: 2});
  await features(3);
  await saved(3);
  check((await sketch()).features[2].properties.zone === 'park', 'a zone drawn after the refusal reaches the server');
  check(await pageFeatures() === await serverFeatures() && await message() === 'Saved.',
        'the page and the server agree again');
  await page.keyboard.down('Control');
  await page.keyboard.press('z');
  await page.keyboard.up('Control');
  await features(2);
  await saved(2);
  check(await pageFeatures() === await serverFeatures() && (await sketch()).features[1].properties.width === 16,
        'undo takes the park away, not back to the refused width');
  // The refused widths left the undo history: the undo before goes to the width drawn.
  const widthIs = async w => {
    for (let i = 0; i < 50 && (await sketch()).features[1].properties.width !== w; ++i) await new Promise(r => setTimeout(r, 100));
    return (await sketch()).features[1].properties.width === w;
  };
  await page.keyboard.down('Control');
  await page.keyboard.press('z');
  await page.keyboard.up('Control');
  check(await widthIs(24), `the undo before that goes back to the width drawn, past the refused ones (${(await sketch()).features[1].properties.width})`);
  await page.keyboard.down('Control');
  await page.keyboard.press('y');
  await page.keyboard.up('Control');
  check(await widthIs(16), 'redo brings the edited width back');
  await page.click('[data-tool="select"]');

  // The zone's type, edited in the side panel.
  await page.mouse.click(...at(-60, -60));
  await page.waitForSelector('#feature-panel:not([hidden]) #zone-row:not([hidden])', {timeout: 30000});
  await page.select('#zone-type', 'commercial');
  for (let i = 0; i < 50 && (await sketch()).features[0].properties.zone !== 'commercial'; ++i) await new Promise(r => setTimeout(r, 100));
  check((await sketch()).features[0].properties.zone === 'commercial', 'the zone\'s type edited in the panel');

  // A value typed in a form: one the CLI refuses is refused with its one line beside the
  // field, the sketch as it was; one it takes is the sketch's.
  const kept = JSON.stringify(await sketch());
  await page.click('.zone-form[data-zone="residential"] summary');
  const typeInto = (selector, value) => page.$eval(selector, (i, v) => { i.value = v; i.dispatchEvent(new Event('change')); }, value);
  await typeInto(`${formField('residential', 'block_area')} input`, '50');
  await page.waitForFunction(s => document.querySelector(s).textContent !== '', {timeout: 30000}, `${formField('residential', 'block_area')} .field-error`);
  const fieldError = await page.$eval(`${formField('residential', 'block_area')} .field-error`, e => e.textContent);
  check(/^value 50(\.0)? is out of range; use a value from 100(\.0)? to/.test(fieldError) && JSON.stringify(await sketch()) === kept,
        `the refused value's line is beside its field, the sketch as it was: ${fieldError}`);
  check(await page.$eval(`${formField('residential', 'block_area')} input`, i => i.value) === '50', 'the refused value stays typed');
  await typeInto(`${formField('residential', 'block_area')} input`, '20000');
  // Taken once the page shows it in the JSON view, which it fills from the server's answer.
  await page.waitForFunction(() => /"block_area":20000/.test(document.querySelector('textarea[data-zone="residential"]').value), {timeout: 30000});
  check((await sketch()).exacity.zones.residential.block_area === 20000 &&
        await page.$eval(`${formField('residential', 'block_area')} .field-error`, e => e.textContent) === '' &&
        JSON.parse(await page.$eval('textarea[data-zone="residential"]', t => t.value)).block_area === 20000,
        'a value taken is the sketch\'s, its error gone, and the JSON view shows it');
  await typeInto(`${formField('residential', 'block_area')} input`, '');
  await page.waitForFunction(() => document.querySelector('textarea[data-zone="residential"]').value === '', {timeout: 30000});
  check(JSON.stringify(await sketch()) === kept, 'an emptied field goes back to the default');

  // A setting the CLI refuses is refused with its message, and the sketch stays as it was.
  // The browser logs the refusals' 400s as console errors: those are expected.
  await page.click('#advanced-settings summary');
  await page.$eval('textarea[data-zone="residential"]', t => { t.value = '{"block_area": -5}'; });
  await page.click('#apply-settings');
  await page.waitForFunction(() => /block_area/.test(document.getElementById('message').textContent), {timeout: 30000});
  const refusal = await message();
  check(/block_area/.test(refusal) && refusal.includes('sketch.geojson'), `the settings refused with the CLI's message: ${refusal}`);
  check(JSON.stringify(await sketch()) === kept, 'the refused settings left the sketch as it was');
  check(await page.$eval('textarea[data-zone="residential"]', t => t.value) === '{"block_area": -5}' &&
        await page.$eval('#settings-note', n => n.textContent) === 'not applied',
        'the typed settings stay in their box, marked not applied');
  check(await pageFeatures() === await serverFeatures(), 'the page still shows the server\'s sketch');
  // A key the CLI does not know: its message names every key there is, on one line here, the
  // whole of it on hover and unfolded by a click.
  await page.$eval('textarea[data-zone="residential"]', t => { t.value = '{"block_aera": 5000}'; });
  await page.click('#apply-settings');
  await page.waitForFunction(() => /block_aera/.test(document.getElementById('message').textContent), {timeout: 30000});
  const folded = await page.$eval('#message', m => ({height: m.clientHeight, line: parseFloat(getComputedStyle(m).lineHeight) ||
                                                     1.2 * parseFloat(getComputedStyle(m).fontSize), title: m.title,
                                                     text: m.textContent, cut: m.scrollWidth > m.clientWidth}));
  check(folded.height < 1.5 * folded.line && folded.title === folded.text && folded.cut,
        `the long refusal takes one line, all of it on hover (${folded.height} px, ${folded.text.length} characters)`);
  await page.click('#message');
  const unfolded = await page.$eval('#message', m => m.clientHeight);
  check(unfolded > 2 * folded.line, `a click unfolds it (${unfolded} px)`);
  await page.click('#message');
  // Broken JSON in a parameter box: the page says where, and sends nothing.
  const requests = [];
  const onRequest = r => requests.push(r.method() + ' ' + r.url());
  page.on('request', onRequest);
  await page.$eval('textarea[data-zone="commercial"]', t => { t.value = '{"block_area" 5000}'; });
  await page.click('#apply-settings');
  page.off('request', onRequest);
  const typo = await message() + ' / ' + await page.$eval('#message-note', n => n.textContent);
  check(/^commercial parameters are not JSON \/ .*position 14/.test(typo) && !requests.some(r => r.startsWith('PUT')),
        `broken JSON is named with its place, and not sent: ${typo}`);
  check(await page.$eval('textarea[data-zone="commercial"]', t => document.activeElement === t && t.selectionStart === 14),
        'the cursor is where the JSON broke');
  check(JSON.stringify(await sketch()) === kept, 'the sketch is still as it was');
  check(errors.filter(e => e.startsWith('HTTP 400: ')).length === 5 && errors.every(e => /400/.test(e)),
        `only the five refusals were errors (${errors.join(' | ')})`);
  errors.length = 0;

  // A heightmap loaded from a file: the sketch points at it, and the map shows it.
  const [chooser] = await Promise.all([page.waitForFileChooser(), page.click('#heightmap')]);
  await chooser.accept([path.join(path.dirname(new URL(import.meta.url).pathname), '..', '..', 'examples', 'valley.png')]);
  for (let i = 0; i < 50 && !(await sketch()).exacity?.terrain; ++i) await new Promise(r => setTimeout(r, 100));
  check((await sketch()).exacity.terrain.heightmap === 'heightmap.png', 'the loaded heightmap is the sketch\'s terrain');
  await page.waitForFunction(() => document.getElementById('heightmap-in-use').textContent === 'heightmap.png', {timeout: 30000});
  check(await page.$eval('#models-in-use', e => e.textContent.startsWith('none')), 'the panel names the heightmap, and no model library');

  // Reload: the page shows the sketch the server kept.
  await page.reload({waitUntil: 'load'});
  await ready();
  check(await page.$eval('body', b => b.dataset.features) === '2', 'after a reload the page shows both features');

  // Generate: the progress bar moves through the stages, then the layers and the report.
  await watch();
  await page.click('#generate');
  // The city is shown at the server's answer, then validated: the message says both, in turn.
  await page.waitForSelector('body[data-city="validated"]', {timeout: 600000});
  const messages = await seen('message');
  const answeredAt = messages.indexOf('City generated; validating it…'), validatedAt = messages.indexOf('City generated and validated.');
  check(answeredAt >= 0 && validatedAt > answeredAt, `the city shown at the answer, then validated: ${few(messages)}`);
  check(await page.evaluate(() => {
    const dt = [...document.querySelectorAll('#report dt')].find(d => d.textContent === 'answered in');
    return /^\d+\.\d s$/.test(dt?.nextElementSibling?.textContent || '');
  }), 'the report shows the server\'s time to the answer');
  check((await seen('time-left')).some(t => /^(estimating…|about \d+ (s|min) left)$/.test(t)) && await page.$eval('#time-left', e => e.textContent) === '',
        `the generation showed its time left, gone at its end: ${few(await seen('time-left'))}`);
  const layers = await page.$$eval('#layer-toggles input', inputs => inputs.map(i => i.dataset.layer));
  check(['zones', 'blocks', 'lots', 'roads', 'buildings'].every(l => layers.includes(l)), `generated layers shown: ${layers}`);
  const legend = await page.$$eval('#layer-toggles label', labels => labels.map(l => l.querySelector('.swatch')?.style.background));
  check(legend.length === layers.length && legend.every(b => b && b !== 'none'), `each of the ${layers.length} layers' toggles has its swatch`);
  const figures = await page.$$eval('#report dt', dts => dts.map(d => d.textContent));
  check(figures.includes('lots') && figures.includes('buildings'), 'the report\'s figures beside the map');
  check(await page.$eval('#progress', p => p.value) === 1, 'the progress bar is full');
  // Every output the server has, listed to download, each one there.
  const downloads = async () => page.$$eval('#downloads a', links => links.map(a => [a.getAttribute('href'), a.download]));
  let listed = await downloads();
  const names = listed.map(([, name]) => name);
  check(['sketch.geojson', 'city.glb', 'city.city.json', 'city.obj', 'city.ply', 'city.gpkg', 'map.svg', 'report.json',
         'zones.geojson', 'buildings.geojson'].every(n => names.includes(n)) &&
        !names.includes('still.png'), `the city's outputs listed to download: ${names}`);
  for (const [href, name] of listed) {
    const r = await get(href);
    check(r.status === 200 && (await r.arrayBuffer()).byteLength > 0, `${name} downloads (${href})`);
  }
  await page.screenshot({path: path.join(out, 'map.png')});

  // With "after each edit" ticked, settings the server takes are generated without a click.
  await page.click('#auto-generate');
  const [generated] = await Promise.all([
    page.waitForResponse(r => r.url().includes('/api/generate') && r.request().method() === 'POST', {timeout: 30000}),
    page.$eval('textarea[data-zone="commercial"]', t => { t.value = '{}'; })
      .then(() => page.$eval('textarea[data-zone="residential"]', t => { t.value = '{"block_area": 9000}'; }))
      .then(() => page.$eval('#apply-settings', b => b.click())),  // the button is scrolled out of the panel here
  ]);
  check(generated.status() === 202, `the edit the server took started a generation (${generated.status()})`);
  let edited = {state: 'running'};
  for (let i = 0; i < 6000 && edited.state === 'running'; ++i) {
    await new Promise(r => setTimeout(r, 100));
    edited = await (await get('/api/status')).json();
  }
  check(edited.state === 'done', `the generation after the edit ended done (${edited.state})`);
  await page.waitForSelector('body[data-job="done"]', {timeout: 60000});
  // The report beside the map says what the generation reused of the one before.
  // Read in the same evaluation that finds it: the report is redrawn when the layers reload,
  // and a dt read in a later round trip may already be detached from its dd.
  const reusedText = await (await page.waitForFunction(() => {
    const dt = [...document.querySelectorAll('#report dt')].find(d => d.textContent === 'reused');
    return dt?.nextElementSibling?.textContent;
  }, {timeout: 60000})).jsonValue();
  check(/^[\d,]+ of [\d,]+ regions, [\d,]+ of [\d,]+ blocks, [\d,]+ of [\d,]+ lots, [\d,]+ of [\d,]+ meshes$/.test(reusedText),
        `the report shows what was reused: ${reusedText}`);
  // And the server time of that update, tiles included (report.json's timings_s).
  const serverTime = await page.evaluate(() => {
    const dt = [...document.querySelectorAll('#report dt')].find(d => d.textContent === 'server time');
    return dt?.nextElementSibling?.textContent;
  });
  const stages = (await (await get('/api/report')).json()).timings_s;
  check(/^\d+\.\d s$/.test(serverTime || '') && 'tiles' in stages, `the report shows the update's server time, tiles included: ${serverTime}`);
  await page.click('#auto-generate');  // untick it: the page keeps the setting for the later steps

  // Explore: the 3D view, orbited with the mouse, then rendered.
  await page.click('[data-view="explore"]');
  await page.waitForFunction(() => window.exacityExplore && window.exacityExplore.city, {timeout: 60000});
  // The minimap's background is an overview of the city taken from above (an air photo):
  // not one colour, and the minimap shows it.
  await page.waitForFunction(() => window.exacityExplore.overview, {timeout: 60000});
  const overview = await page.evaluate(() => {
    const data = window.exacityExplore.overview.canvas.getContext('2d').getImageData(0, 0, 256, 256).data;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4 * 97) colours.add(`${data[i]},${data[i + 1]},${data[i + 2]}`);
    const map = document.getElementById('minimap');
    const middle = map.getContext('2d').getImageData(map.width / 2, map.height / 2, 1, 1).data;
    return {colours: colours.size, minimapMiddle: [...middle.slice(0, 3)]};
  });
  check(overview.colours > 20 && overview.minimapMiddle.join() !== '244,244,240',
        `the minimap shows an overview of the city: ${JSON.stringify(overview)}`);
  const spec = async () => page.$eval('#camera-spec', e => e.textContent);
  const first = await spec();
  const view = await (await page.$('#three')).boundingBox();
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(view.x + view.width / 2 + 10 * i, view.y + view.height / 2 - 3 * i);
  await page.mouse.up();
  const second = await spec();
  check(first !== second && /azimuth=/.test(second), `orbiting moved the camera (${first} to ${second})`);
  // Dragging far down stops at the top of the upper hemisphere (the orbit camera).
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 4);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(view.x + view.width / 2, view.y + view.height / 4 + 40 * i);
  await page.mouse.up();
  check(/elevation=90,/.test(await spec()), `the camera stops straight above: ${await spec()}`);
  // Back down to a view of the city from the side, zoomed in with the wheel.
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  await page.mouse.down();
  for (let i = 1; i <= 10; ++i) await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2 - 18 * i);
  await page.mouse.up();
  await page.mouse.wheel({deltaY: -200});
  const third = await spec();
  check(/elevation=(3\d|4\d)/.test(third), `orbited back down: ${third}`);
  // Levels of detail: from far away every tile in view shows its coarsest level; close over a
  // tile, that one shows its full level; each level loaded when first wanted.
  const tiles = async () => {
    await page.waitForFunction(() => window.exacityExplore.tileCounts().pending === 0, {timeout: 30000});
    return page.evaluate(() => window.exacityExplore.tileCounts());
  };
  const kept_orbit = await page.evaluate(() => ({...window.exacityExplore.orbit}));
  // Zoom stops at its limit, a few times the city's size.
  const limit = await page.evaluate(() => {
    const view = window.exacityExplore, [x0, y0, x1, y1] = view.bounds;
    view.setOrbit({distance: 1e9});
    return {distance: view.orbit.distance, diagonal: Math.hypot(x1 - x0, y1 - y0)};
  });
  check(limit.distance === Math.max(5000, 8 * limit.diagonal), `zooming out stops at 8 city diagonals, or 5 km: ${JSON.stringify(limit)}`);
  check((await seen('tiles-loading')).some(t => /^Loading \d+ tiles?…$/.test(t)) && !(await visible('#tiles-loading')),
        `the tiles' loading was shown, and hidden once in: ${few(await seen('tiles-loading'))}`);
  await page.evaluate(() => window.exacityExplore.setOrbit({elevation: 60, distance: 4000}));
  const far = await tiles();
  check(far.tiles >= 2 && far.inView === far.tiles && far.shown[2] === far.tiles && far.shown[0] === 0 &&
        far.shown[1] === 0, `far away, every tile at its coarsest level: ${JSON.stringify(far)}`);
  // Looking down 37° and more, the view is all ground: the renderer's grass plane goes on past
  // the city's ground, so no sky shows under the horizon.
  const sky = await page.evaluate(() => {
    const pixels = window.exacityExplore.pixels(), background = window.exacityExplore.scene.background.clone();
    const [r, g, b] = background.convertLinearToSRGB().toArray().map(v => Math.round(v * 255));
    let n = 0;
    for (let i = 0; i < pixels.length; i += 4)
      if (Math.abs(pixels[i] - r) < 4 && Math.abs(pixels[i + 1] - g) < 4 && Math.abs(pixels[i + 2] - b) < 4) ++n;
    return n;
  });
  check(sky === 0, `no sky under the horizon: ${sky} pixels of the sky's colour`);
  // Between 3 and 8 tile sides (250 m) from every tile of this city (under 1 km across): boxes.
  await page.evaluate(o => window.exacityExplore.setOrbit({...o, elevation: 60, distance: 1400}), kept_orbit);
  const middle = await tiles();
  check(middle.inView > 0 && middle.shown[1] === middle.inView && middle.loaded[1] === middle.inView,
        `halfway, the tiles in view at their boxes: ${JSON.stringify(middle)}`);
  await page.evaluate(() => {
    const view = window.exacityExplore, box = view.tiles[0].box;
    view.setOrbit({target: [(box.min.x + box.max.x) / 2, -(box.min.z + box.max.z) / 2, box.min.y], elevation: 45, distance: 60});
  });
  const near = await tiles();
  check(near.shown[0] >= 1 && near.loaded[0] >= 1,
        `close over a tile, it shows its full level: ${JSON.stringify(near)}`);
  // A click on a building shows its attributes: straight above one whose footprint holds its
  // corners' mean, the view's middle is its roof.
  const picked = await page.evaluate(() => {
    const view = window.exacityExplore;
    for (const f of view.layers.buildings.features) {
      const ring = f.geometry.type === 'Polygon' ? f.geometry.coordinates[0] : f.geometry.coordinates[0][0];
      const [x, y] = ring.slice(1).reduce(([a, b], [c, d]) => [a + c / (ring.length - 1), b + d / (ring.length - 1)], [0, 0]);
      if (ring.length !== 5 || f.properties.model) continue;  // a plain box, whose middle is inside
      view.setOrbit({target: [x, y, 0], elevation: 90, distance: 120});
      return f.properties;
    }
    return null;
  });
  await tiles();
  await page.mouse.click(view.x + view.width / 2, view.y + view.height / 2);
  await page.waitForSelector('#building-info:not([hidden])', {timeout: 30000});
  const info = await page.$eval('#building-info', b => b.textContent);
  check(picked && await page.$eval('#building-info', b => b.dataset.id) === String(picked.id) &&
        info.includes(picked.zone) && info.includes(`lot${picked.lot}`),
        `a click on building ${picked?.id} shows its attributes: ${info}`);
  // Walls have the still's windows: facing a wall of one of the tallest extruded buildings
  // from 30 m at half its height (the first whose wall the view's middle meets: neighbours
  // and the heightmap's hills can stand between), dark glass in rows where the wall alone is light.
  let tallest = null;
  for (let k = 0; k < 5 * 4 && !tallest; ++k) {
    const candidate = await page.evaluate((k) => {
      const view = window.exacityExplore;
      const plain = view.layers.buildings.features.filter(f => !f.properties.model)
                        .sort((a, b) => b.properties.height - a.properties.height);
      const f = plain[Math.floor(k / 4)];
      if (!f) return null;
      const ring = f.geometry.type === 'Polygon' ? f.geometry.coordinates[0] : f.geometry.coordinates[0][0];
      const xs = ring.map(p => p[0]), ys = ring.map(p => p[1]);
      const cx = xs.reduce((s, v) => s + v, 0) / xs.length, cy = ys.reduce((s, v) => s + v, 0) / ys.length;
      // Its south, west, north and east sides, each from outside, at half its height over
      // the heightmap's ground under its middle.
      const z = view.groundHeight(cx, cy) + f.properties.height / 2;
      const sides = [[cx, Math.min(...ys), 270], [Math.min(...xs), cy, 180], [cx, Math.max(...ys), 90], [Math.max(...xs), cy, 0]];
      const [x, y, azimuth] = sides[k % 4];
      view.setOrbit({target: [x, y, z], azimuth, elevation: 5, distance: 30});
      return f.properties;
    }, k);
    if (!candidate) break;
    await tiles();
    const seenId = await page.evaluate(() => {
      const r = window.exacityExplore.renderer.domElement.getBoundingClientRect();
      return window.exacityExplore.buildingAt(r.left + r.width / 2, r.top + r.height / 2)?.properties.id;
    });
    if (seenId === candidate.id) tallest = candidate;
  }
  check(tallest, 'a wall of one of the five tallest extruded buildings can be seen from 30 m');
  const darkShare = () => page.evaluate(() => {
    const pixels = window.exacityExplore.pixels();
    let dark = 0;
    for (let i = 0; i < pixels.length; i += 4) if (pixels[i] < 60 && pixels[i + 1] < 60 && pixels[i + 2] < 70) ++dark;
    return dark / (pixels.length / 4);
  });
  const withWindows = await darkShare();
  await page.evaluate(() => { window.exacityExplore.facadeWindows.value = 0; });
  const bare = await darkShare();
  await page.evaluate(() => { window.exacityExplore.facadeWindows.value = 1; });
  check(withWindows > bare + 0.05, `the walls have windows: ${(100 * withWindows).toFixed(1)}% of the view dark glass against ` +
        `${(100 * bare).toFixed(1)}% without (building ${tallest.id}, ${tallest.height} m)`);
  await page.screenshot({path: path.join(out, 'windows.png')});
  // Each building's own windows, as the renderer draws them: every wall triangle of the
  // full levels loaded carries its building's style from facades.json (its storey, bay,
  // window, phase, sill, head, floor and eaves), its building the footprint just inside it.
  const styles = await page.evaluate(() => {
    const view = window.exacityExplore, facades = view.facades.buildings;
    let walls = 0, styled = 0, own = 0;
    const heights = new Set();
    for (const tile of view.tiles) tile.loaded[0]?.traverse(o => {
      if (!o.isMesh || !/_wall/.test(o.material.name)) return;
      const g = o.geometry, p = g.attributes.position, a = g.attributes.facadeA, b = g.attributes.facadeB;
      for (let t = 0; t < (g.index ? g.index.count : p.count); t += 3) {
        const i = g.index ? g.index.getX(t) : t;
        ++walls;
        if (!(a.getX(i) > 0)) continue;
        ++styled;
        const same = (k, field, value) => Math.fround(facades[k][field]) === value;  // the attributes are single floats
        const id = Object.keys(facades).find(k => same(k, 0, a.getX(i)) && same(k, 1, a.getY(i)) && same(k, 5, a.getW(i)) &&
                                                    same(k, 6, b.getZ(i)) && same(k, 7, b.getW(i)));
        if (id !== undefined) ++own;
        heights.add(a.getX(i));
      }
    });
    return {walls, styled, own, storeys: heights.size, buildings: Object.keys(facades).length};
  });
  check(styles.walls > 0 && styles.styled >= 0.9 * styles.walls && styles.own === styles.styled && styles.storeys > 1,
        `walls take their buildings' own windows: ${styles.styled} of ${styles.walls} wall triangles styled, each as one of ` +
        `the ${styles.buildings} buildings' facades, ${styles.storeys} storey heights`);
  // Roofs have the still's tiles or gravel: looking down on the tallest building's roof
  // from 12 m, the pattern changes the roof's pixels.
  await page.evaluate(t => {
    const view = window.exacityExplore, f = view.layers.buildings.features.find(f => f.properties.id === t.id);
    const ring = f.geometry.type === 'Polygon' ? f.geometry.coordinates[0] : f.geometry.coordinates[0][0];
    const x = ring.reduce((s, p) => s + p[0], 0) / ring.length, y = ring.reduce((s, p) => s + p[1], 0) / ring.length;
    view.setOrbit({target: [x, y, view.groundHeight(x, y) + t.height], azimuth: 200, elevation: 85, distance: 12});
  }, tallest);
  await tiles();
  const roofPixels = () => page.evaluate(() => Array.from(window.exacityExplore.pixels()));
  const patterned = await roofPixels();
  await page.evaluate(() => { window.exacityExplore.roofPattern.value = 0; });
  const plainRoof = await roofPixels();
  await page.evaluate(() => { window.exacityExplore.roofPattern.value = 1; });
  let changed = 0;
  for (let i = 0; i < patterned.length; i += 4)
    if (Math.abs(patterned[i] - plainRoof[i]) + Math.abs(patterned[i + 1] - plainRoof[i + 1]) > 2) ++changed;
  await page.screenshot({path: path.join(out, 'roof.png')});
  check(changed > 0.15 * patterned.length / 4, `the roof has its pattern: ${(400 * changed / patterned.length).toFixed(1)}% of the view changed by it`);
  // Walk: the CLI's pedestrian, where the orbit looked; keys move it along its heading.
  await page.click('[data-mode="pedestrian"]');
  const walker = await spec();
  check(/^pedestrian:at=[-\d.]+,[-\d.]+,heading=[\d.]+,pitch=0$/.test(walker), `walking: ${walker}`);
  // The orbit looked at the tallest building's roof: the walker stands outside it, not in it.
  const standing = /at=([-\d.]+),([-\d.]+)/.exec(walker).slice(1).map(Number);
  check(await page.evaluate(([x, y]) => window.exacityExplore.footprints.at(x, y), standing) === null,
        `the walker stands outside every building: ${walker}`);
  await page.keyboard.press('w');
  await page.keyboard.press('w');
  const walked = await spec();
  const [wx0, wy0] = /at=([-\d.]+),([-\d.]+)/.exec(walker).slice(1).map(Number), [wx1, wy1] = /at=([-\d.]+),([-\d.]+)/.exec(walked).slice(1).map(Number);
  check(Math.abs(Math.hypot(wx1 - wx0, wy1 - wy0) - 4) < 0.05, `two steps of 2 m: ${walker} to ${walked}`);
  // Fly: the CLI's flyer, standing where the orbit's camera stood, looking the same way.
  await page.click('[data-mode="orbit"]');
  await page.evaluate(() => window.exacityExplore.setOrbit({elevation: 30, distance: 300, azimuth: 225}));
  const eye = () => page.evaluate(() => window.exacityExplore.camera.position.toArray());
  const orbitEye = await eye();
  await page.click('[data-mode="flyer"]');
  const flyer = await spec(), flyerEye = await eye();
  check(/^flyer:at=[-\d.]+,[-\d.]+,height=[\d.]+,heading=45,pitch=-30$/.test(flyer) &&
        orbitEye.every((v, i) => Math.abs(v - flyerEye[i]) < 0.05), `flying from where the orbit's camera was: ${flyer}`);
  const height = async () => Number(/height=([\d.]+)/.exec(await spec())[1]);
  const before_r = await height();
  await page.keyboard.press('r');
  check(await height() > before_r, `R raises the flyer: ${await spec()}`);
  await page.click('#fit-view');
  check(/^orbit:.*elevation=35,/.test(await spec()), `Fit view orbits the whole city again: ${await spec()}`);
  await page.evaluate(o => window.exacityExplore.setOrbit(o), kept_orbit);
  await watch();
  await page.click('#render-view');
  await page.waitForFunction(() => {
    const img = document.getElementById('render-image');
    return !document.getElementById('render-result').hidden && img.complete && img.naturalWidth > 0;
  }, {timeout: 600000});
  check((await seen('time-left')).some(t => /^(estimating…|about \d+ (s|min) left)$/.test(t)),
        `the render showed its time left: ${few(await seen('time-left'))}`);
  // A click enlarges the still to the view's size, another brings it back.
  const stillWidth = () => page.$eval('#render-image', i => i.getBoundingClientRect().width);
  const small = await stillWidth();
  await page.click('#render-image');
  const enlarged = await stillWidth();
  await page.screenshot({path: path.join(out, 'still-large.png')});
  await page.click('#render-image');
  check(small <= 480 && enlarged > 1.5 * small && await stillWidth() === small, `a click enlarges the still (${small} to ${enlarged} px) and another shrinks it`);
  listed = await downloads();
  check(listed.some(([href, name]) => href === '/api/render/still.png' && name === 'still.png') &&
        listed.some(([, name]) => name === 'still.json'), 'the still listed to download');
  await page.screenshot({path: path.join(out, 'explore.png')});

  // Models…: the example library's files uploaded together; the sketch then names it.
  await page.click('[data-view="map"]');
  const library = path.join(path.dirname(new URL(import.meta.url).pathname), '..', '..', 'examples', 'models');
  const [modelsChooser] = await Promise.all([page.waitForFileChooser(), page.click('#models')]);
  await modelsChooser.accept(fs.readdirSync(library).filter(f => !f.endsWith('.py')).map(f => path.join(library, f)));
  for (let i = 0; i < 50 && !(await sketch()).exacity?.models; ++i) await new Promise(r => setTimeout(r, 100));
  check((await sketch()).exacity.models === 'models/library.json', 'the uploaded model library is the sketch\'s');
  // The server holds the new sketch a moment before the page has read its answer and said so.
  const said = await page.waitForFunction(
      () => /Model library models\/library.json loaded/.test(document.getElementById('message').textContent),
      {timeout: 30000}).then(() => true, () => false);
  check(said, 'the page says the library loaded');
  check(await page.$eval('#models-in-use', e => e.textContent) === 'models/library.json', 'the panel names the model library');
  // The library in use, listed: each model with its kind and zone types.
  await page.waitForFunction(() => document.getElementById('library-name').textContent.startsWith('models/library.json'), {timeout: 30000});
  const listedModels = await page.$$eval('#library-models tbody tr', rows => rows.map(r => [...r.cells].map(c => c.textContent).join('|')));
  check(listedModels.includes('apartment|building|residential, commercial') && listedModels.includes('tree|tree|residential, commercial, industrial'),
        `the library's models listed with their zone types: ${listedModels.join('; ')}`);

  // Like a place…: a file of a real place's footprints, measured by the server as generate
  // --like measures it. Its own residential land 330 m by 100 m along a road, and twelve
  // footprints 10 m deep 5 m behind the road's surface, 4 m apart, 10 to 32 m wide: areas 100
  // to 320 m² (median 200, p90 300; tests/like_test.cpp). A file with three is refused with
  // the CLI's line, the sketch as it was.
  const rectangle = (x0, y0, x1, y1) => [[[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]];
  const placeFeatures = [
    {type: 'Feature', properties: {zone: 'residential'}, geometry: {type: 'Polygon', coordinates: rectangle(0, 0, 330, 100)}},
    {type: 'Feature', properties: {road: 'local', width: 10}, geometry: {type: 'LineString', coordinates: [[-10, 0], [340, 0]]}}];
  for (let i = 0, x = 10; i < 12; x += 10 + 2 * i + 4, ++i)
    placeFeatures.push({type: 'Feature', properties: {building: 'house', height: 6 + i},
                        geometry: {type: 'Polygon', coordinates: rectangle(x, 10, x + 10 + 2 * i, 20)}});
  const placeFile = path.join(out, 'place.geojson'), fewFile = path.join(out, 'few.geojson');
  fs.writeFileSync(placeFile, JSON.stringify({type: 'FeatureCollection', features: placeFeatures}));
  fs.writeFileSync(fewFile, JSON.stringify({type: 'FeatureCollection', features: placeFeatures.slice(0, 5)}));
  const likeChooser = async file => {
    const [chooser] = await Promise.all([page.waitForFileChooser(), page.click('#like')]);
    await chooser.accept([file]);
  };
  errors.length = 0;
  const [fewAnswer] = await Promise.all([page.waitForResponse(r => r.url().endsWith('/api/like') && r.request().method() === 'POST'),
                                         likeChooser(fewFile)]);
  const fewMessage = await fewAnswer.text();
  check(fewAnswer.status() === 400 && fewMessage === 'like/few.geojson: maps 3 building footprints, too few to measure a place by ' +
        '(at least 10); give an extract or a file with more of its buildings, or leave out --like',
        `a place with three footprints refused with the CLI's line: ${fewMessage}`);
  await page.waitForFunction(m => document.getElementById('message').textContent === m, {timeout: 30000}, fewMessage);
  check(!('like' in (await sketch()).exacity) && await page.$eval('#like-panel', p => p.hidden), 'the sketch names no place after the refusal');
  check(errors.filter(e => /^HTTP 400: .*\/api\/like$/.test(e)).length === 1 && errors.every(e => /400/.test(e)),
        `only the refusal was an error (${errors.join(' | ')})`);
  errors.length = 0;
  await likeChooser(placeFile);
  for (let i = 0; i < 50 && !(await sketch()).exacity?.like; ++i) await new Promise(r => setTimeout(r, 100));
  check((await sketch()).exacity.like === 'like/place.geojson', 'the uploaded place is the sketch\'s "like"');
  await page.waitForFunction(() => document.querySelectorAll('#like-figures tbody tr').length === 3, {timeout: 30000});
  check(await page.$eval('#like-in-use', e => e.textContent) === 'like/place.geojson' &&
        /^like\/place.geojson: 12 footprints; zones from the file's land use$/.test(await page.$eval('#like-name', e => e.textContent)),
        'the panel names the place and what it measured');
  const likeRows = async () => page.$$eval('#like-figures tbody tr', rows => rows.map(r => [...r.cells].map(c => c.textContent).join('|')));
  let rows = await likeRows();
  check(rows[0] === 'residential|12|200 / 300|–' && rows[1] === 'commercial|0|too few|–',
        `the place's footprints measured per zone type: ${rows.join('; ')}`);
  const likeSet = await page.$$eval('#like-set li', items => items.map(i => i.textContent));
  check(/^residential: .*setback 5, building gap 4,/.test(likeSet[0]) && /footprint areas \[100,/.test(likeSet[0]) &&
        likeSet[1] === 'commercial: defaults kept (fewer than 10 mapped buildings in commercial land)',
        `the settings the place gives each zone type: ${likeSet.join('; ')}`);
  // Generate looks like it: report.json's "like" is the place's, and the panel sets the
  // generated footprints beside the place's.
  const [likeStart] = await Promise.all([
    page.waitForResponse(r => r.url().endsWith('/api/generate') && r.request().method() === 'POST', {timeout: 30000}),
    page.click('#generate')]);
  check(likeStart.status() === 202, `Generate started (${likeStart.status()})`);
  let liked = {state: 'running'};
  for (let i = 0; i < 6000 && liked.state === 'running'; ++i) {
    await new Promise(r => setTimeout(r, 100));
    liked = await (await get('/api/status')).json();
  }
  check(liked.state === 'done', `the generation like the place ended done (${liked.state})`);
  const likeReport = await (await get('/api/report')).json();
  check(likeReport.like?.file === 'like/place.geojson' && likeReport.like.zones.residential.set.setback === 5,
        `the generation looked like the place: ${JSON.stringify(likeReport.like?.zones?.residential?.set)}`);
  const m2 = v => Math.round(v).toLocaleString('en');
  const expectedRows = ['residential', 'commercial', 'industrial'].map(zone => {
    const g = likeReport.footprints_by_zone[zone]?.generated;
    return g?.footprints ? `${m2(g.median_m2)} / ${m2(g.p90_m2)}` : '–';
  });
  await page.waitForFunction(expected => [...document.querySelectorAll('#like-figures tbody tr')].map(r => r.cells[3].textContent).join() === expected,
                             {timeout: 60000}, expectedRows.join()).catch(() => {});
  rows = await likeRows();
  check(rows.map(r => r.split('|')[3]).join() === expectedRows.join() && expectedRows.some(r => r !== '–'),
        `the generated footprints beside the place's: ${rows.join('; ')}`);
  await page.screenshot({path: path.join(out, 'like.png')});
  // Stop using it: the sketch names no place, and the panel goes.
  await page.$eval('#like-clear', b => b.click());
  for (let i = 0; i < 50 && (await sketch()).exacity?.like; ++i) await new Promise(r => setTimeout(r, 100));
  check(!('like' in (await sketch()).exacity), 'Stop using it: the sketch names no place');
  await page.waitForFunction(() => document.getElementById('like-panel').hidden, {timeout: 30000});

  // Save downloads the sketch; Open reads one from a file and shows what the server took.
  const cdp = await page.createCDPSession();
  await cdp.send('Browser.setDownloadBehavior', {behavior: 'allow', downloadPath: path.resolve(out)});
  await page.click('#save');
  const downloaded = path.join(out, 'sketch.geojson');
  for (let i = 0; i < 50 && !fs.existsSync(downloaded); ++i) await new Promise(r => setTimeout(r, 100));
  const saved_doc = JSON.parse(fs.readFileSync(downloaded, 'utf8'));
  check(JSON.stringify(saved_doc.features) === JSON.stringify((await sketch()).features), 'Save downloaded the sketch');
  const opened = path.join(out, 'opened.geojson');
  fs.writeFileSync(opened, JSON.stringify({type: 'FeatureCollection', exacity: {seed: 5}, features: [
    {type: 'Feature', properties: {zone: 'industrial'},
     geometry: {type: 'Polygon', coordinates: [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}}]}));
  const [openChooser] = await Promise.all([page.waitForFileChooser(), page.click('#open')]);
  await openChooser.accept([opened]);
  await features(1);
  s = await sketch();
  check(s.exacity.seed === 5 && s.features[0].properties.zone === 'industrial', 'Open read a sketch from a file');
  check(await page.$eval('#seed', i => i.value) === '5', 'the panel shows the opened sketch\'s seed');

  // A basemap under a sketch with a place on Earth (UTM zone 33 north, around 15° E,
  // 49.65° N): tiles from the URL named, none before; those asked for cover the sketch.
  const tileRequests = [];
  const tileServer = http.createServer((req, res) => {
    tileRequests.push(req.url);
    res.writeHead(200, {'Content-Type': 'image/png', 'Access-Control-Allow-Origin': '*'});
    res.end(fs.readFileSync(path.join(path.dirname(new URL(import.meta.url).pathname), '..', '..', 'examples', 'valley.png')));
  });
  await new Promise(resolve => tileServer.listen(0, '127.0.0.1', resolve));
  const placed = path.join(out, 'placed.geojson');
  fs.writeFileSync(placed, JSON.stringify({type: 'FeatureCollection', crs: {type: 'name', properties: {name: 'urn:ogc:def:crs:EPSG::32633'}},
    features: [{type: 'Feature', properties: {zone: 'residential'},
                geometry: {type: 'Polygon', coordinates: [[[499800, 5499800], [500200, 5499800], [500200, 5500200], [499800, 5500200], [499800, 5499800]]]}}]}));
  const [placedChooser] = await Promise.all([page.waitForFileChooser(), page.click('#open')]);
  await placedChooser.accept([placed]);
  await page.waitForFunction(() => /EPSG:32633/.test(document.getElementById('basemap-where').textContent), {timeout: 30000});
  check(tileRequests.length === 0, 'no basemap is fetched before one is named');
  await page.click('#basemap-panel summary');
  await page.$eval('#basemap-url', (i, port) => { i.value = `http://127.0.0.1:${port}/{z}/{x}/{y}.png`; }, tileServer.address().port);
  await page.click('#basemap-show');
  await page.evaluate(() => window.exacityPage.drawn());
  const tileOf = (z, lon, lat) => [Math.floor((lon + 180) / 360 * 2 ** z),
                                   Math.floor((1 - Math.asinh(Math.tan(lat * Math.PI / 180)) / Math.PI) / 2 * 2 ** z)];
  const asked = tileRequests.map(u => u.slice(1, -4).split('/').map(Number));
  check(asked.length > 0 && asked.some(([z, x, y]) => tileOf(z, 15, 49.65254)[0] === x && tileOf(z, 15, 49.65254)[1] === y),
        `the basemap's tiles cover the sketch (15° E, 49.65° N): ${tileRequests.slice(0, 4).join(' ')}`);
  await page.click('#basemap-hide');
  const hidden = tileRequests.length;
  await page.evaluate(() => window.exacityPage.drawn(true));
  check(tileRequests.length === hidden, 'Hide drops the basemap: no tiles asked for after it');

  // A GeoTIFF of the work folder in Web Mercator, white with a red square 40 m across on a
  // point of the sketch: the server warps it into the sketch's UTM zone and the page lays it
  // under the sketch, the square's middle red where the point is drawn and white 60 m off.
  // A name that leaves the folder is refused with its one line.
  const mark = [499900, 5500100];
  const [lon, lat] = await page.evaluate(m => window.exacityPage.lonLat(m), mark);
  const mercator = [lon * 20037508.342789244 / 180, Math.log(Math.tan((90 + lat) * Math.PI / 360)) * 6378137];
  const cells = 200, cell = 8;  // in Web Mercator metres: some 5.2 m on the ground here
  const rgb = new Uint8Array(cells * cells * 3).fill(255);
  const half = Math.round(20 / 0.648 / cell);  // 20 m on the ground, Mercator's scale 1/cos(49.65°)
  for (let r = cells / 2 - half; r < cells / 2 + half; ++r)
    for (let c = cells / 2 - half; c < cells / 2 + half; ++c) rgb[(r * cells + c) * 3 + 1] = rgb[(r * cells + c) * 3 + 2] = 0;
  fs.mkdirSync(path.join(out, 'work', 'maps'), {recursive: true});
  fs.writeFileSync(path.join(out, 'work', 'maps', 'mark.tif'), Buffer.from(writeArrayBuffer(rgb, {
    width: cells, height: cells, ModelPixelScale: [cell, cell, 0],
    ModelTiepoint: [0, 0, 0, mercator[0] - cells / 2 * cell, mercator[1] + cells / 2 * cell, 0],
    GTModelTypeGeoKey: 1, GTRasterTypeGeoKey: 1, ProjectedCSTypeGeoKey: 3857})));
  await page.$eval('#geotiff-name', i => { i.value = '../mark.tif'; });
  await page.click('#geotiff-show');
  await page.waitForSelector('#message.error', {timeout: 30000});
  check(/^basemap \.\.\/mark\.tif: "\.\." would leave the folder/.test(await message()),
        `a GeoTIFF name leaving the work folder is refused: ${await message()}`);
  check(errors.filter(e => /^HTTP 400: .*\/api\/basemap\?file=\.\.%2Fmark\.tif$/.test(e)).length === 1 &&
        errors.every(e => /400/.test(e)), `its 400 is the only error: ${errors.join(' | ')}`);
  errors.length = 0;
  await page.$eval('#geotiff-name', i => { i.value = 'maps/mark.tif'; });
  await page.click('#geotiff-show');
  await page.waitForFunction(() => /^Basemap maps\/mark\.tif under the sketch, warped into EPSG:32633\.$/.test(
      document.getElementById('message').textContent), {timeout: 30000});
  await page.evaluate(() => window.exacityPage.drawn());
  const colours = await page.evaluate(m => window.exacityPage.geotiffAt([m, [m[0] + 60, m[1]], [m[0], m[1] - 60]]), mark);
  const red = c => c && c[0] > 200 && c[1] < 80 && c[2] < 80, white = c => c && c.slice(0, 3).every(v => v > 200);
  check(red(colours[0]) && white(colours[1]) && white(colours[2]),
        `the GeoTIFF's red square lies on its point, white around it: ${JSON.stringify(colours)}`);
  await page.screenshot({path: path.join(out, 'geotiff.png')});
  // Both basemaps shown survive a reload; Hide forgets them.
  await page.click('#basemap-show');
  const beforeReload = tileRequests.length;
  await page.reload({waitUntil: 'load'});
  await ready();
  await page.evaluate(() => window.exacityPage.drawn());
  const again = await page.evaluate(m => window.exacityPage.geotiffAt([m, [m[0] + 60, m[1]]]), mark);
  check(tileRequests.length > beforeReload && red(again[0]) && white(again[1]) &&
        await page.$eval('#basemap-url', i => i.value) === `http://127.0.0.1:${tileServer.address().port}/{z}/{x}/{y}.png`,
        `after a reload the tiles (${tileRequests.length - beforeReload} asked for) and the GeoTIFF (${JSON.stringify(again)}) are drawn again`);
  await page.click('#basemap-panel summary');
  await page.click('#basemap-hide');
  check(await page.evaluate(() => window.exacityPage.geotiffAt([[0, 0]])[0]) === null &&
        await page.evaluate(() => localStorage.getItem('exacity.basemap') === null && localStorage.getItem('exacity.geotiff') === null),
        'Hide drops the GeoTIFF and the tiles, also for the next reload');
  tileServer.close();

  // Cancel: a city some kilometres across (as serve_test's), cancelled in its lots stage; the
  // progress bar empties and says so.
  const large = path.join(out, 'large.geojson');
  fs.writeFileSync(large, JSON.stringify({type: 'FeatureCollection', exacity: {seed: 5}, features: [
    {type: 'Feature', properties: {zone: 'residential'},
     geometry: {type: 'Polygon', coordinates: [[[0, 0], [3000, 0], [3000, 2000], [0, 2000], [0, 0]]]}},
    {type: 'Feature', properties: {zone: 'commercial'},
     geometry: {type: 'Polygon', coordinates: [[[3000, 0], [4000, 0], [4000, 2000], [3000, 2000], [3000, 0]]]}},
    {type: 'Feature', properties: {road: 'highway', width: 16},
     geometry: {type: 'LineString', coordinates: [[-50, 1000], [4050, 1000]]}}]}));
  const [largeChooser] = await Promise.all([page.waitForFileChooser(), page.click('#open')]);
  await largeChooser.accept([large]);
  await features(3);
  // The grid's labels: each kilometre of this city, x along the top, y along the left.
  const gridLabelled = await page.waitForFunction(() => {
    const labels = window.exacityPage.gridLabels();
    const on = axis => labels.filter(l => l.axis === axis).map(l => l.label);
    return ['0 m', '1000 m', '2000 m', '3000 m', '4000 m'].every(t => on('x').includes(t)) &&
           ['0 m', '1000 m', '2000 m'].every(t => on('y').includes(t));
  }, {timeout: 30000}).then(() => true, () => false);
  check(gridLabelled, `the grid is labelled: ${JSON.stringify(await page.evaluate(() => window.exacityPage.gridLabels()))}`);
  // No label in the top left corner, under the zoom buttons or on the other row's labels,
  // wherever the grid's lines fall: the view moved 17 px at a time over 136 px.
  const cornered = [];
  for (let i = 0; i < 8; ++i) {
    await page.evaluate(() => window.exacityPage.pan(17, 17));
    for (const l of await page.evaluate(() => window.exacityPage.gridLabels()))
      if ((l.axis === 'x' && l.at[0] < 32) || (l.axis === 'y' && l.at[1] < 72)) cornered.push(`${l.label} at ${l.at.map(Math.round)}`);
  }
  check(cornered.length === 0, `no grid label in the zoom buttons' corner: ${cornered.join(', ')}`);
  await page.click('#generate');
  await page.waitForFunction(() => / lots$/.test(document.getElementById('stage').textContent), {timeout: 120000});
  check(await page.$eval('#progress', p => p.value) > 0, 'the generation under way fills the bar');
  // By then its time left is known: from the stage clock's seconds of the last generation.
  const timeLeft = await page.waitForFunction(() => /^about \d+ (s|min) left$/.test(document.getElementById('time-left').textContent),
                                              {timeout: 30000}).then(() => true, () => false);
  check(timeLeft, `the generation's time left: ${await page.$eval('#time-left', e => e.textContent)}`);
  await page.click('#cancel');
  await page.waitForSelector('body[data-job="cancelled"]', {timeout: 60000});
  check(await page.$eval('#progress', p => p.value) === 0 && await page.$eval('#stage', e => e.textContent) === 'generate cancelled',
        `after Cancel the bar is empty and says so: ${await page.$eval('#stage', e => e.textContent)}`);
  check(await page.$eval('#time-left', e => e.textContent) === '', 'and no time left is shown');
  check(/cancelled during the lots stage/.test(await message()), `the page says where it stopped: ${await message()}`);
  check(errors.length === 0, `no console errors${errors.length ? ': ' + errors.join(' | ') : ''}`);

  // A page the server no longer knows (restarted, its token another; here the page's cookie
  // is dropped): an edit is refused, the page keeps what is drawn and says so, and Save
  // downloads what is drawn.
  await page.deleteCookie(...(await page.cookies()));
  const drawnBefore = await pageFeatures();
  await page.click('#undo');
  await page.waitForSelector('body[data-server="lost"]', {timeout: 30000});
  const lostNote = await page.$eval('#message-note', e => e.textContent);
  check(/^refused: no token/.test(await message()) && /^Not saved: the server does not know this page/.test(lostNote),
        `a refused token is said: ${await message()} / ${lostNote}`);
  const drawnAfter = await pageFeatures();
  check(drawnAfter !== drawnBefore && drawnAfter !== await serverFeatures(), 'the page keeps the edit the server did not take');
  fs.rmSync(downloaded);
  await page.click('#save');
  for (let i = 0; i < 50 && !fs.existsSync(downloaded); ++i) await new Promise(r => setTimeout(r, 100));
  check(fs.existsSync(downloaded) && rounded(JSON.parse(fs.readFileSync(downloaded, 'utf8')).features) === drawnAfter,
        'Save downloads the sketch as drawn');
} catch (e) {
  console.error(String(e.stack || e));
  if (errors.length) console.error('console errors:', errors.join(' | '));
  failed = true;
} finally {
  await browser.close();
  server.kill('SIGTERM');
  const {code} = await serverExit;
  if (code !== 128 + 15) {
    console.error(`exacity serve exited with ${code} on SIGTERM, not 143: ${serverLog}`);
    failed = true;
  }
}
process.exit(failed ? 1 : 0);
