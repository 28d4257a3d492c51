// The viewer page in a real browser: Debian's Chromium, headless, driven by playwright-core.
// Run by ../run_tests.sh, which builds the pages this opens (TUMBLE_VIEWER_PAGES, comma-separated).
// Checks: the page loads with no console errors; the canvas shows the bodies (pixels change where
// each body is when the bodies are hidden); scrubbing to another time changes the picture.
// TUMBLE_SCREENSHOTS=PAGE=FILE,... also saves screenshots (PAGE a page's file name) at the time
// TUMBLE_SCREENSHOT_TIME (seconds, default the middle).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

const pages = (process.env.TUMBLE_VIEWER_PAGES || 'test-output/demo.html').split(',');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const screenshots = new Map((process.env.TUMBLE_SCREENSHOTS || '').split(',').filter(Boolean).map((s) => s.split('=')));
const WIDTH = 1100;
const HEIGHT = 700;

let context;
let profile;

before(async () => {
  profile = fs.mkdtempSync(path.join(os.tmpdir(), 'tumble-chromium-'));
  context = await chromium.launchPersistentContext(profile, {
    executablePath: chromiumPath,
    headless: true,
    viewport: { width: WIDTH, height: HEIGHT },
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--enable-unsafe-swiftshader', // WebGL in software: this machine has no GPU
    ],
  });
});

after(async () => {
  await context?.close();
  fs.rmSync(profile, { recursive: true, force: true });
});

/** Opens `file`, collecting console errors, page errors and any request off the file itself. */
async function open(file) {
  const page = await context.newPage();
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('request', (r) => { if (!r.url().startsWith('file:')) problems.push(`network request: ${r.url()}`); });
  await page.goto(pathToFileURL(path.resolve(file)).href);
  await page.waitForFunction(() => document.body.dataset.ready === 'true' || document.querySelector('.fatal'), null, { timeout: 60_000 });
  return { page, problems };
}

/** Test helpers put into the page: snapshots of the canvas kept there, compared there (moving
 * millions of pixel values out of the page is slow). */
function installHelpers() {
  const shots = {};
  window.__snap = (name) => {
    const source = window.tumbleViewer.canvas;
    const c = document.createElement('canvas');
    c.width = source.width;
    c.height = source.height;
    const g = c.getContext('2d');
    g.drawImage(source, 0, 0);
    shots[name] = g.getImageData(0, 0, c.width, c.height);
    return { width: c.width, height: c.height };
  };
  // Pixels differing by more than `tolerance` in some channel between two snapshots, in `box`.
  window.__diff = (a, b, tolerance = 24, box = null) => {
    const A = shots[a];
    const B = shots[b];
    const [x0, y0, x1, y1] = box ?? [0, 0, A.width, A.height];
    let count = 0;
    for (let y = Math.max(0, y0); y < Math.min(A.height, y1); y++) {
      for (let x = Math.max(0, x0); x < Math.min(A.width, x1); x++) {
        const k = 4 * (y * A.width + x);
        if (Math.abs(A.data[k] - B.data[k]) > tolerance || Math.abs(A.data[k + 1] - B.data[k + 1]) > tolerance
          || Math.abs(A.data[k + 2] - B.data[k + 2]) > tolerance) count++;
      }
    }
    return count;
  };
}

const snap = (page, name) => page.evaluate((n) => window.__snap(n), name);
const diff = (page, a, b, box = null) => page.evaluate(([a, b, box]) => window.__diff(a, b, 24, box), [a, b, box]);

for (const file of pages) {
  test(`viewer page ${path.basename(file)}: loads cleanly, shows the bodies, scrubs`, async () => {
    assert.ok(fs.existsSync(file), `${file} is missing: run viewer/run_tests.sh, which builds it`);
    const { page, problems } = await open(file);
    const fatal = await page.evaluate(() => document.querySelector('.fatal')?.textContent ?? '');
    assert.equal(fatal, '', 'the viewer starts');
    const viewer = await page.evaluate(() => ({ frames: window.tumbleViewer.frameCount, names: window.tumbleViewer.bodyNames }));
    assert.ok(viewer.frames > 2, 'the page has frames');

    // The bodies are drawn: around each body's origin the picture changes when bodies are hidden.
    await page.evaluate(installHelpers);
    await page.evaluate(() => window.tumbleViewer.setFrame(0));
    const { width } = await snap(page, 'shown');
    const ratio = width / WIDTH; // device pixels per CSS pixel
    const points = await page.evaluate(() => window.tumbleViewer.bodyScreenPoints());
    await page.evaluate(() => window.tumbleViewer.setBodiesVisible(false));
    await snap(page, 'hidden');
    await page.evaluate(() => window.tumbleViewer.setBodiesVisible(true));
    const background = await diff(page, 'shown', 'hidden');
    assert.ok(background > 40, `bodies cover ${background} pixels: too few`);
    for (const [i, p] of points.entries()) {
      if (!p.visible) continue;
      const r = 12 * ratio;
      const box = [p.x * ratio - r, p.y * ratio - r, p.x * ratio + r, p.y * ratio + r].map(Math.round);
      const changed = await diff(page, 'shown', 'hidden', box);
      assert.ok(changed > 0, `body ${viewer.names[i]}: nothing drawn near its screen position (${p.x.toFixed(0)}, ${p.y.toFixed(0)})`);
    }

    // Scrubbing with the slider, as a person would, moves the bodies.
    const mid = Math.floor(viewer.frames / 2);
    await page.locator('input[type=range]').fill(String(mid));
    assert.equal(await page.evaluate(() => window.tumbleViewer.frame), mid, 'the slider sets the frame');
    await snap(page, 'later');
    const moved = await diff(page, 'shown', 'later');
    assert.ok(moved > 200, `scrubbing to frame ${mid} changed only ${moved} pixels`);
    const time = await page.locator('.time').textContent();
    assert.ok(!time.startsWith('0.000'), `the time read-out follows the slider: ${time}`);

    // The panel and the overlay switches are there and work.
    assert.match(await page.locator('.stats').textContent(), /energy\s+-?[\d.]+/);
    await page.locator('input[data-overlay=omega]').uncheck();
    await page.locator('input[data-overlay=L]').uncheck();
    await snap(page, 'noArrows');
    assert.ok((await diff(page, 'later', 'noArrows')) > 20, 'switching the ω and L arrows off changes the picture');
    await page.locator('input[data-overlay=omega]').check();
    await page.locator('input[data-overlay=L]').check();

    // Playing moves time on.
    await page.locator('.transport button[title^=play]').click();
    await page.waitForTimeout(400);
    assert.ok(await page.evaluate(() => window.tumbleViewer.frame !== 0));

    const shot = screenshots.get(path.basename(file));
    if (shot) {
      const time = process.env.TUMBLE_SCREENSHOT_TIME;
      await page.evaluate((t) => {
        const v = window.tumbleViewer;
        v.setFrame(t === null ? Math.floor(v.frameCount / 2) : v.frameAtTime(t));
      }, time === undefined ? null : Number(time));
      await page.mouse.move(5, HEIGHT / 2);
      fs.mkdirSync(path.dirname(shot), { recursive: true });
      await page.screenshot({ path: shot });
    }
    assert.deepEqual(problems, [], 'no console errors and no network');
    await page.close();
  });
}
