// The viewer in headless Chromium (Debian's /usr/bin/chromium, driven by playwright-core),
// served by the real `proxima view`:
//   1. record test/scene.jsonl with `proxima world --record`: a static grey box (id 0, top at
//      z = 0.5), a blue sphere (id 1) resting 0.1 deep in it, so one contact with witnesses
//      (0, 0, 0.5) and (0, 0, 0.4) drawn as red markers, and a blue capsule (id 2, user data
//      42) moved from y = 1 to y = 0 over three steps;
//   2. load the page, step to the last frame, screenshot, and look at the pixels where the
//      viewer's own camera (window.proximaViewer.project) puts the contact witness and the
//      capsule's centre: the marker's red, the capsule's blue; at step 0 the capsule's pixel is
//      not blue (it was elsewhere), and with the layers off both colours are gone;
//   3. click the capsule: the inspector shows its fields; the slider scrubs, Play plays to the end;
//   4. a truncated capture shows the error naming the cut line;
//   5. a 2D capture (test/scene2d.jsonl through `proxima world --2d --record`: a chain floor and
//      a blue box moved and turned over three steps) shows the box in the plane z = 0 where
//      the camera puts its centre at the last step, not there at step 0, and its fields;
//   and the browser console holds no error throughout.
import assert from 'node:assert/strict';
import { rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { chromium } from 'playwright-core';

import { chromiumOptions, decodePng, recordScene, scratchDir, startViewer } from './helpers.mjs';

const CONTACT_WITNESS = [0, 0, 0.5];
const CAPSULE_CENTRE_LAST_STEP = [1.2, 0, 2];
const MARKER_RED = [255, 40, 40];

let dir;
let context;
let captureText;
const consoleErrors = [];

before(async () => {
  dir = scratchDir();
  captureText = recordScene(join(dir, 'scene.capture.jsonl'));
  context = await chromium.launchPersistentContext(join(dir, 'chromium-profile'), chromiumOptions());
});

after(async () => {
  await context?.close();
  rmSync(dir, { recursive: true, force: true });
});

/** A new page that records console errors and uncaught exceptions. */
async function newPage() {
  const page = await context.newPage();
  page.on('console', (message) => {
    if (message.type() === 'error') consoleErrors.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => consoleErrors.push(`page: ${error.message}`));
  return page;
}

/** Waits until the viewer has finished loading (ready or error); returns the status. */
async function loaded(page) {
  await page.waitForFunction(() => window.proximaViewer && window.proximaViewer.status !== 'loading', null, { timeout: 15000 });
  return page.evaluate(() => window.proximaViewer.status);
}

async function screenshot(page) {
  return decodePng(await page.screenshot({ type: 'png' }));
}

async function projected(page, point) {
  return page.evaluate((p) => window.proximaViewer.project(p), point);
}

function near(actual, expected, tolerance) {
  return actual.every((value, i) => Math.abs(value - expected[i]) <= tolerance);
}

/** Blue clearly above red: the colour of the moving objects ([70, 130, 230]), lit. */
function isBlue([r, , b]) {
  return b > r + 40;
}

test('a recorded step shows the contact marker and the object where the camera puts them', async () => {
  const server = await startViewer(join(dir, 'scene.capture.jsonl'));
  try {
    const page = await newPage();
    await page.goto(server.address);
    assert.equal(await loaded(page), 'ready', await page.evaluate(() => window.proximaViewer.error));
    assert.equal(await page.evaluate(() => window.proximaViewer.stepCount), 3);

    // Step 0: the capsule is still at y = 1, so its last-step centre shows something else.
    await page.evaluate(() => window.proximaViewer.setStep(0));
    const capsule = await projected(page, CAPSULE_CENTRE_LAST_STEP);
    assert.ok(capsule.visible, 'the capsule centre is in view');
    const before = await screenshot(page);
    assert.ok(!isBlue(before.at(capsule.x, capsule.y)), `step 0 at the capsule's later place: ${before.at(capsule.x, capsule.y)}`);

    await page.evaluate(() => window.proximaViewer.setStep(2));
    assert.match(await page.textContent('#step-label'), /step 2 \/ 2/);
    const marker = await projected(page, CONTACT_WITNESS);
    assert.ok(marker.visible, 'the contact witness is in view');
    const shot = await screenshot(page);
    const markerPixel = shot.at(marker.x, marker.y);
    assert.ok(near(markerPixel, MARKER_RED, 12), `contact marker pixel ${markerPixel}, expected ${MARKER_RED}`);
    const capsulePixel = shot.at(capsule.x, capsule.y);
    assert.ok(isBlue(capsulePixel), `capsule pixel ${capsulePixel} is not the moving objects' blue`);

    // With the layers off, the same pixels lose those colours.
    await page.evaluate(() => {
      window.proximaViewer.setLayer('shapes', false);
      window.proximaViewer.setLayer('contacts', false);
    });
    const hidden = await screenshot(page);
    const background = await page.evaluate(() => window.proximaViewer.background);
    assert.ok(near(hidden.at(capsule.x, capsule.y), background, 8), `shapes off: ${hidden.at(capsule.x, capsule.y)}`);
    assert.ok(!near(hidden.at(marker.x, marker.y), MARKER_RED, 40), `contacts off: ${hidden.at(marker.x, marker.y)}`);
    await page.evaluate(() => window.proximaViewer.setLayer('shapes', true));

    // A click on the capsule selects it and shows its fields.
    await page.mouse.click(capsule.x, capsule.y);
    assert.equal(await page.evaluate(() => window.proximaViewer.selectedId), 2);
    const fields = await page.textContent('#inspector');
    assert.match(fields, /capsule/);
    assert.match(fields, /user data\s*42/);
    assert.match(fields, /moving/);

    // The slider scrubs; Play runs to the last step and stops there.
    await page.$eval('#step-slider', (slider) => {
      slider.value = '1';
      slider.dispatchEvent(new Event('input'));
    });
    assert.match(await page.textContent('#step-label'), /step 1 \/ 2/);
    await page.click('#play');
    await page.waitForFunction(() => window.proximaViewer.step === 2 && document.getElementById('play').textContent === 'Play', null, {
      timeout: 5000,
    });

    assert.deepEqual(consoleErrors, []);
    await page.close();
  } finally {
    assert.equal(await server.stop(), 0, 'proxima view exits 0 on SIGTERM');
  }
});

test('a truncated capture shows which line is cut', async () => {
  const cut = captureText.slice(0, captureText.length - 40); // the last step loses its end
  const lastLine = cut.split('\n').length;
  const path = join(dir, 'truncated.capture.jsonl');
  writeFileSync(path, cut);
  const server = await startViewer(path);
  try {
    const page = await newPage();
    await page.goto(server.address);
    assert.equal(await loaded(page), 'error');
    assert.ok(await page.isVisible('#error'), 'the error panel is shown');
    const message = await page.textContent('#error');
    assert.match(message, new RegExp(`line ${lastLine}: the line is cut`));
    assert.deepEqual(consoleErrors, []);
    await page.close();
  } finally {
    assert.equal(await server.stop(), 0);
  }
});

test('a 2D capture shows its objects in the plane z = 0', async () => {
  const path = join(dir, 'scene2d.capture.jsonl');
  recordScene(path, 'scene2d.jsonl', ['--2d']);
  const server = await startViewer(path);
  try {
    const page = await newPage();
    await page.goto(server.address);
    assert.equal(await loaded(page), 'ready', await page.evaluate(() => window.proximaViewer.error));
    assert.equal(await page.evaluate(() => window.proximaViewer.stepCount), 3);
    await page.evaluate(() => window.proximaViewer.setStep(2));
    const box = await projected(page, [-2, 3, 0]);
    assert.ok(box.visible, 'the box centre is in view');
    const shot = await screenshot(page);
    assert.ok(isBlue(shot.at(box.x, box.y)), `box pixel ${shot.at(box.x, box.y)} is not the moving objects' blue`);
    await page.evaluate(() => window.proximaViewer.setStep(0));
    const before = await screenshot(page);
    assert.ok(!isBlue(before.at(box.x, box.y)), `step 0 at the box's later place: ${before.at(box.x, box.y)}`);
    await page.evaluate(() => window.proximaViewer.setStep(2));
    await page.mouse.click(box.x, box.y);
    assert.equal(await page.evaluate(() => window.proximaViewer.selectedId), 1);
    const fields = await page.textContent('#inspector');
    assert.match(fields, /polygon/);
    assert.match(fields, /user data\s*7/);
    assert.deepEqual(consoleErrors, []);
    await page.close();
  } finally {
    assert.equal(await server.stop(), 0);
  }
});
