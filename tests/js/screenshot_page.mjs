// The README's pictures of exacity serve: serves SKETCH, generates it, and saves the map
// with the generated city (the residential settings' form open) and the 3D view with its
// path-traced still, a building's attributes and the city's legend and report (no checks: see check_page.mjs). Usage: node screenshot_page.mjs EXACITY_BINARY SKETCH OUT_DIR
import {spawn} from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const [binary, sketch, out] = process.argv.slice(2);
fs.mkdirSync(out, {recursive: true});
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'exacity-screenshots-'));
const server = spawn(binary, ['serve', sketch, '--port', '0', '--work', work], {stdio: ['ignore', 'pipe', 'inherit']});
// The address as printed, with its token when it has one.
const address = await new Promise(resolve => {
  let text = '';
  server.stdout.on('data', d => {
    text += d;
    const m = text.match(/serving (http:\/\/127\.0\.0\.1:\d+\/(\?token=\w+)?)/);
    if (m) resolve(new URL(m[1]));
  });
});
const browser = await puppeteer.launch({executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
                                        args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader']});
try {
  const page = await browser.newPage();
  await page.setViewport({width: 1400, height: 860});
  address.searchParams.set('spp', '32');
  await page.goto(address.href, {timeout: 120000});  // a loaded machine takes its time
  await page.waitForSelector('body[data-ready="yes"]', {timeout: 120000});
  await page.click('#generate');
  await page.waitForSelector('body[data-city="shown"]', {timeout: 600000});
  await page.click('.zone-form[data-zone="residential"] summary');
  await page.screenshot({path: path.join(out, 'serve-map.png')});
  await page.click('.zone-form[data-zone="residential"] summary');  // the city's legend and report in view again
  await page.click('[data-view="explore"]');
  await page.waitForFunction(() => window.exacityExplore && window.exacityExplore.city, {timeout: 300000});
  await page.evaluate(() => window.exacityExplore.setOrbit({azimuth: 235, elevation: 28}));
  await page.click('#render-view');
  await page.waitForFunction(() => {
    const img = document.getElementById('render-image');
    return !document.getElementById('render-result').hidden && img.complete && img.naturalWidth > 0;
  }, {timeout: 600000});
  // Every tile in view at the level it asked for.
  await page.waitForFunction(() => window.exacityExplore.tileCounts().pending === 0, {timeout: 300000});
  // A building near the view's middle, its attributes shown as a click shows them.
  await page.evaluate(() => {
    const view = window.exacityExplore, r = view.renderer.domElement.getBoundingClientRect();
    for (let step = 0; step < 40; ++step) {
      const a = step * 2.4, d = step * 6;
      const feature = view.buildingAt(r.left + r.width / 2 + d * Math.cos(a), r.top + r.height / 2 + d * Math.sin(a));
      if (feature) return view.showBuilding(feature);
    }
  });
  await page.screenshot({path: path.join(out, 'serve-explore.png')});
} finally {
  await browser.close();
  server.kill('SIGTERM');
  fs.rmSync(work, {recursive: true, force: true});
}
