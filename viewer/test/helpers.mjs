// What the viewer's tests share: recording the test scene with `proxima world --record`,
// starting `proxima view` on a free port, and decoding the PNG screenshots to pixels.
//   recordScene: runs the proxima executable ($PROXIMA_CLI) on test/scene.jsonl (or
//                test/scene2d.jsonl with --2d);
//   startViewer: spawns `proxima view CAPTURE --port 0` and reads the address it prints
//                (a time limit, never a hang); stop() sends SIGTERM and waits for exit 0;
//   decodePng:   8-bit RGB / RGBA PNG (what Chromium writes) to {width, height, at(x, y)}.
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { inflateSync } from 'node:zlib';

export const testDir = dirname(fileURLToPath(import.meta.url));

/** The proxima executable under test: $PROXIMA_CLI (ctest sets it). */
export function proximaPath() {
  const path = process.env.PROXIMA_CLI;
  if (!path) throw new Error('set PROXIMA_CLI to the built proxima executable (ctest does)');
  return path;
}

/** A fresh temporary folder. */
export function scratchDir() {
  return mkdtempSync(join(tmpdir(), 'proxima-viewer-'));
}

/** Records test/`scene` into `capturePath` with `proxima world --record` (`options`: e.g. ['--2d']). */
export function recordScene(capturePath, scene = 'scene.jsonl', options = []) {
  const run = spawnSync(proximaPath(), ['world', ...options, '--record', capturePath, join(testDir, scene)], {
    encoding: 'utf8',
    timeout: 30000,
  });
  if (run.status !== 0) throw new Error(`proxima world --record failed (${run.status}): ${run.stderr}`);
  return readFileSync(capturePath, 'utf8');
}

/** Starts `proxima view capturePath --port 0`; resolves to {address, stop()} once it prints its address. */
export function startViewer(capturePath, timeoutMs = 10000) {
  const child = spawn(proximaPath(), ['view', capturePath, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal })));
  const address = new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`proxima view printed no address in ${timeoutMs} ms: ${output}`)), timeoutMs);
    const onData = (chunk) => {
      output += chunk;
      const match = output.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (match) {
        clearTimeout(timer);
        resolve(match[0]);
      }
    };
    child.stdout.on('data', onData);
    child.stderr.on('data', (chunk) => (output += chunk));
    exited.then(({ code }) => {
      clearTimeout(timer);
      reject(new Error(`proxima view exited (${code}) before serving: ${output}`));
    });
  });
  return address.then((url) => ({
    address: url,
    /** Sends SIGTERM; resolves to the exit code (null when it had to be killed). */
    stop: async () => {
      child.kill('SIGTERM');
      const killer = setTimeout(() => child.kill('SIGKILL'), 5000);
      const { code } = await exited;
      clearTimeout(killer);
      return code;
    },
  }));
}

/** The Chromium launch options that work on a machine with no network and no GPU. */
export function chromiumOptions() {
  return {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    viewport: { width: 900, height: 600 },
    deviceScaleFactor: 1,
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
    ],
  };
}

function paeth(a, b, c) {
  const p = a + b - c;
  const pa = Math.abs(p - a);
  const pb = Math.abs(p - b);
  const pc = Math.abs(p - c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/** Decodes a non-interlaced 8-bit RGB or RGBA PNG; at(x, y) gives [r, g, b]. */
export function decodePng(buffer) {
  if (buffer.readUInt32BE(0) !== 0x89504e47) throw new Error('not a PNG');
  let offset = 8;
  let width = 0;
  let height = 0;
  let channels = 0;
  const data = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('ascii', offset + 4, offset + 8);
    const body = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      const [depth, colorType, , , interlace] = body.subarray(8, 13);
      if (depth !== 8 || interlace !== 0 || (colorType !== 2 && colorType !== 6)) throw new Error('unsupported PNG layout');
      channels = colorType === 6 ? 4 : 3;
    } else if (type === 'IDAT') {
      data.push(body);
    }
    offset += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(data));
  const stride = width * channels;
  const pixels = Buffer.alloc(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    for (let i = 0; i < stride; ++i) {
      const x = raw[y * (stride + 1) + 1 + i];
      const a = i >= channels ? pixels[y * stride + i - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + i] : 0;
      const c = y > 0 && i >= channels ? pixels[(y - 1) * stride + i - channels] : 0;
      const predictor = [0, a, b, (a + b) >> 1, paeth(a, b, c)][filter];
      if (predictor === undefined) throw new Error(`PNG filter ${filter} unknown`);
      pixels[y * stride + i] = (x + predictor) & 0xff;
    }
  }
  return {
    width,
    height,
    at(x, y) {
      const i = Math.floor(y) * stride + Math.floor(x) * channels;
      return [pixels[i], pixels[i + 1], pixels[i + 2]];
    },
  };
}
