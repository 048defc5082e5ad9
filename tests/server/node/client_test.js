// client_test.js - an independent holotraced client: @grpc/grpc-js + @grpc/proto-loader load
// protocol/holotrace/v1/holotrace.proto as-is (docs/SERVICE.md §8). Usage: node client_test.js HOLOTRACED_EXE
// Exit 0 = pass, 1 = fail, 77 = skipped (node_modules absent: run `npm ci` in tests/server/node).
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawn } = require('child_process');

let grpc, protoLoader;
try {
  grpc = require('@grpc/grpc-js');
  protoLoader = require('@grpc/proto-loader');
} catch (e) {
  console.log('SKIP: node_modules absent (npm ci --prefix tests/server/node)');
  process.exit(77);
}

const exe = process.argv[2];
const repo = path.resolve(__dirname, '..', '..', '..');
const loadOptions = { keepCase: true, longs: Number, enums: String, defaults: true, oneofs: true };
const api = grpc.loadPackageDefinition(
  protoLoader.loadSync(path.join(repo, 'protocol', 'holotrace', 'v1', 'holotrace.proto'), loadOptions)).holotrace.v1;
const health = grpc.loadPackageDefinition(
  protoLoader.loadSync(path.join(__dirname, 'health.proto'), loadOptions)).grpc.health.v1;

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'ht-node-'));
for (const d of ['displays', 'scenes', 'out']) fs.mkdirSync(path.join(dir, d));
fs.writeFileSync(path.join(dir, 'displays', 'tiny.json'), JSON.stringify({
  name: 'tiny', model: 'lenticular', spp: 1,
  calibration: { configVersion: '3.0', serial: 'LKG-TEST-2', pitch: 52.59, slope: -7.21, center: 0.4, viewCone: 40,
    invView: 1, verticalAngle: 0, DPI: 324, screenW: 64, screenH: 48, flipImageX: 0, flipImageY: 0, flipSubp: 0,
    CellPatternMode: 0, subpixelCells: [] },
}));
const socket = path.join(dir, 'run', 'd.sock');
fs.writeFileSync(path.join(dir, 'd.json'), JSON.stringify({
  displays_dir: 'displays', scene_root: 'scenes', output_root: 'out', listen: ['unix:' + socket] }));

const daemon = spawn(exe, ['--config', path.join(dir, 'd.json')], { stdio: ['ignore', 'inherit', 'inherit'] });
const target = 'unix:' + socket;
const client = () => new api.Holotrace(target, grpc.credentials.createInsecure(),
  { 'grpc.max_receive_message_length': 64 << 20 });
const deadline = (s) => new Date(Date.now() + s * 1000);
const call = (c, method, request) => new Promise((resolve, reject) =>
  c[method](request, { deadline: deadline(60) }, (err, res) => (err ? reject(err) : resolve(res))));

function check(ok, what) {
  if (!ok) throw new Error('FAILED: ' + what);
  console.log('ok - ' + what);
}

async function expectCode(promise, code, what) {
  try {
    await promise;
    check(false, what + ' (succeeded)');
  } catch (e) {
    check(e.code === code, what + ` -> ${grpc.status[e.code]} (${e.details})`);
  }
}

// Header + chunks of every frame until `count` frames, then cancel; resolves with the frames and final code.
function readFrames(stream, count) {
  return new Promise((resolve) => {
    const frames = [];
    let current = null;
    stream.on('data', (part) => {
      if (part.header) current = { header: part.header, bytes: 0 };
      else if (part.chunk && current) current.bytes += part.chunk.data.length;
      if (current && current.bytes === current.header.total_bytes) {
        frames.push(current);
        current = null;
        if (frames.length === count) stream.cancel();
      }
    });
    stream.on('error', (e) => resolve({ frames, code: e.code }));
    stream.on('end', () => resolve({ frames, code: grpc.status.OK }));
  });
}

async function waitReady() {
  for (let i = 0; i < 300; ++i) {
    if (fs.existsSync(socket)) {
      const h = new health.Health(target, grpc.credentials.createInsecure());
      try {
        const r = await new Promise((res, rej) =>
          h.Check({ service: '' }, { deadline: deadline(2) }, (e, v) => (e ? rej(e) : res(v))));
        h.close();
        return r;
      } catch (e) { h.close(); }
    }
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error('daemon did not become ready');
}

async function main() {
  const status = await waitReady();
  check(status.status === 'SERVING', 'grpc.health.v1 Check reports SERVING');
  const c = client();
  const displays = await call(c, 'ListDisplays', {});
  check(displays.displays.some((d) => d.id === 'tiny' && d.panel_width === 64), 'ListDisplays has tiny 64x48');
  const scene = await call(c, 'LoadScene', { path: 'builtin:plain' });
  check(scene.triangles > 0, `LoadScene builtin:plain: ${scene.triangles} triangles`);

  const one = await readFrames(c.RenderFrame({ scene_id: scene.scene_id, display_id: 'tiny', format: 'PIXEL_FORMAT_RGBA8' }), 0);
  check(one.code === grpc.status.OK && one.frames.length === 1 && one.frames[0].bytes === 64 * 48 * 4,
    'RenderFrame RGBA8: one complete 64x48 frame');

  const streamed = await readFrames(c.StreamFrames({
    render: { scene_id: scene.scene_id, display_id: 'tiny', format: 'PIXEL_FORMAT_RGBA16F' }, frames_per_second: 20,
    mode: 'STREAM_MODE_INDEPENDENT' }), 3);
  check(streamed.frames.length === 3 && streamed.code === grpc.status.CANCELLED,
    'StreamFrames: 3 RGBA16F frames, then client cancel -> CANCELLED');

  await expectCode(call(c, 'GetDisplay', { display_id: 'nope' }), grpc.status.NOT_FOUND, 'unknown display');
  await expectCode(call(c, 'LoadScene', { path: '../etc/passwd' }), grpc.status.PERMISSION_DENIED, '../ path');
  await expectCode(call(c, 'LoadScene', { path: '/etc/passwd' }), grpc.status.PERMISSION_DENIED, 'absolute path');
  c.close();
}

main().then(() => 0, (e) => { console.error(e.message); return 1; }).then((rc) => {
  daemon.kill('SIGTERM');
  const timer = setTimeout(() => { daemon.kill('SIGKILL'); }, 20000);
  daemon.on('exit', (code) => {
    clearTimeout(timer);
    fs.rmSync(dir, { recursive: true, force: true });
    if (rc === 0) check(code === 0, 'holotraced exits 0 on SIGTERM');
    process.exit(rc === 0 && code === 0 ? 0 : 1);
  });
});
