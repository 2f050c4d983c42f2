// tests/browser/viewer_check.js -- opens a report's viewer page from disk
// in Debian's headless Chromium (WebGL through SwiftShader) and writes
// what it saw as JSON: console errors, whether playing advanced the
// frame, the share of the canvas drawn, and the positions of every row's
// meshes as drawn at a chosen frame (compared with the stored ones by the
// calling test). Usage:
//   node viewer_check.js <chromium> <viewer/index.html> <frame> <out.json> <screenshot.png>
'use strict';
const fs = require('fs');
const path = require('path');
const puppeteer = require('puppeteer-core');

async function main() {
  const [chromium, page_path, frame_text, out_path, shot_path] = process.argv.slice(2);
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: 'shell',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
  });
  const result = { console_errors: [], advanced: false };
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1000, height: 800 });
    page.on('console', (m) => { if (m.type() === 'error') result.console_errors.push(m.text()); });
    page.on('pageerror', (e) => result.console_errors.push(String(e)));
    page.on('requestfailed', (r) => result.console_errors.push('failed request: ' + r.url()));
    await page.goto('file://' + path.resolve(page_path), { waitUntil: 'load' });
    await page.waitForFunction(() => window.layersViewer !== undefined, { timeout: 20000 });
    result.rows = await page.evaluate(() => window.layersViewer.rows);
    result.frames = await page.evaluate(() => window.layersViewer.frames);
    const before = await page.evaluate(() => window.layersViewer.frame());
    await page.waitForFunction((f) => window.layersViewer.frame() !== f, { timeout: 10000 }, before)
      .then(() => { result.advanced = true; }, () => {});
    const frame = Number(frame_text);
    result.frame = frame;
    result.positions = await page.evaluate((t) => {
      const v = window.layersViewer;
      v.pause();
      v.setFrame(t);
      const rows = [];
      for (let r = 0; r < v.rows.length; ++r) {
        const meshes = [];
        for (let m = 0; ; ++m) {
          try { meshes.push(v.positions(r, m)); } catch (e) { break; }
        }
        rows.push(meshes);
      }
      return rows;
    }, frame);
    result.shown_frame = await page.evaluate(() => window.layersViewer.frame());
    result.drawn_share = await page.evaluate(() => window.layersViewer.drawnShare());
    await page.screenshot({ path: shot_path });
  } finally {
    await browser.close();
  }
  fs.writeFileSync(out_path, JSON.stringify(result));
}

main().catch((e) => { console.error('viewer_check: ' + e.message); process.exit(1); });
