// The capture reader of the page (src/capture.js) under node, without a browser: a recorded
// capture reads and replays; every kind of damage is reported with its line and member.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { test } from 'node:test';

import { CaptureError, CaptureState, parseCapture } from '../src/capture.js';
import { recordScene, scratchDir } from './helpers.mjs';

const header = '{"format":"proxima-capture","version":1,"dimension":3,"units":"m","precision":"float"}';
const triangle = '"mesh":{"positions":[0,0,0,1,0,0,0,1,0],"indices":[0,1,2]}';
const object = (id) => `{"id":${id},"kind":"moving","position":[0,0,0],"rotation":[0,0,0,1],${triangle}}`;
const scene = `{"type":"scene","objects":[${object(0)},${object(1)}]}`;
const step = (index, rest = '') => `{"type":"step","index":${index}${rest}}`;

/** The error parseCapture throws for `lines` (joined with newlines, a final one unless `cut`). */
function errorOf(lines, cut = false) {
  const text = lines.join('\n') + (cut ? '' : '\n');
  try {
    parseCapture(text);
  } catch (error) {
    assert.ok(error instanceof CaptureError, `a CaptureError, not ${error}`);
    return error;
  }
  assert.fail('the capture was accepted');
}

test('a recorded capture reads and its steps replay in order', () => {
  const capture = parseCapture(recordScene(join(scratchDir(), 'scene.capture.jsonl')));
  assert.equal(capture.steps.length, 3);
  assert.deepEqual(capture.levels.get('contacts'), [0]);
  assert.deepEqual(capture.levels.get('queries'), [0]);
  const state = new CaptureState(capture);
  state.seek(2);
  assert.deepEqual(state.objects.get(2).position, [1.2, 0, 2]);
  state.seek(0); // back: replayed from the scene
  assert.deepEqual(state.objects.get(2).position, [1.2, 1, 2]);
  assert.equal(state.objects.get(2).record.user_data, '42');
});

test('removed, added and poses apply in that order within a step', () => {
  const added = `{"id":1,"kind":"static","position":[5,0,0],"rotation":[0,0,0,1],${triangle}}`;
  const lines = [header, scene, step(0, `,"removed":[0,1],"added":[${added}],"poses":[{"id":1,"position":[7,0,0],"rotation":[0,0,0,1]}]`)];
  const state = new CaptureState(parseCapture(lines.join('\n') + '\n'));
  state.seek(0);
  assert.deepEqual([...state.objects.keys()], [1]);
  assert.equal(state.objects.get(1).record.kind, 'static');
  assert.deepEqual(state.objects.get(1).position, [7, 0, 0]);
});

test('damage is named by line and member', () => {
  assert.match(errorOf([header, scene, step(0), step(1).slice(0, 12)], true).message, /^line 4: the line is cut/);
  assert.match(errorOf([header, scene, '{"type":"step",']).message, /^line 3: not valid JSON/);
  assert.match(errorOf([header, scene, step(0), step(2)]).message, /^line 4: index is 2, expected 1/);
  assert.match(errorOf(['{"format":"other"}', scene]).message, /^line 1: not a capture/);
  assert.match(errorOf([header.replace('"version":1', '"version":9'), scene]).message, /^line 1: version 9/);
  assert.match(errorOf([header]).message, /^line 2: the capture ends before its scene/);
  assert.match(errorOf([header, scene.replace('"indices":[0,1,2]', '"indices":[0,1,3]')]).message, /^line 2: objects\[0\]\.mesh\.indices\[2\] = 3/);
  assert.match(errorOf([header, scene, step(0, ',"poses":[{"id":1,"position":[0,0],"rotation":[0,0,0,1]}]')]).message, /^line 3: poses\[0\]\.position/);
  assert.match(errorOf([header, scene, '', step(0)]).message, /^line 3: empty line/);
  assert.throws(() => parseCapture(''), /the capture is empty/);
});
