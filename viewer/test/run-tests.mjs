// Runs browser-test.mjs on the sample run (make-sample.mjs) in every way the viewer gets its data:
// file:// and HTTP inline pages, ?run=&glb=, ?session= with a token, the error cases, a #t=
// snapshot and a #sheet= contact sheet. Screenshots go to OUT/shots/.
// Usage: node test/run-tests.mjs [--out DIR] [--lang2manip PATH_TO_CLI]
//   --lang2manip: also `lang2manip gltf -o OUT/desk.glb` and show it through ?glb= (a real scene).
// Prints one line per case and "N passed, N failed"; exits 1 when a case failed, 77 without
// Chromium (1 when LANG2MANIP_REQUIRE_BROWSER=1).
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { serve } from './serve.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const option = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
};
const out = resolve(option('--out', join(here, 'out')));
const lang2manip = option('--lang2manip', process.env.LANG2MANIP || null);
const shots = join(out, 'shots');
const TOKEN = 'test-token-123';

function runNode(args, { quiet = false } = {}) {
  return new Promise((done) => {
    const child = spawn(process.execPath, args, { stdio: ['ignore', 'pipe', 'pipe'] });
    let output = '';
    child.stdout.on('data', (d) => (output += d));
    child.stderr.on('data', (d) => (output += d));
    child.on('close', (code) => {
      if (!quiet || code !== 0) process.stdout.write(output);
      done(code);
    });
  });
}

function runCommand(command, args) {
  return new Promise((done) => {
    const child = spawn(command, args, { stdio: ['ignore', 'inherit', 'inherit'] });
    child.on('error', () => done(127));
    child.on('close', (code) => done(code));
  });
}

const chromium = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(chromium)) {
  // `make test` installs Chromium and sets LANG2MANIP_REQUIRE_BROWSER=1: there, a missing one fails.
  const required = process.env.LANG2MANIP_REQUIRE_BROWSER === '1';
  console.log(`run-tests: ${required ? 'FAILED' : 'skipped'}: no Chromium at ${chromium} (Debian: apt-get install chromium; or set CHROMIUM)`);
  process.exit(required ? 1 : 77);
}

if (!existsSync(join(out, 'sample-run.html'))) {
  console.error(`run-tests: ${join(out, 'sample-run.html')} is missing: run "node test/make-sample.mjs" first`);
  process.exit(1);
}

const server = await serve({ root: out, token: TOKEN });
const http = server.url;
const file = pathToFileURL(join(out, 'sample-run.html')).href;
const full = ['--expect-actions', '2', '--expect-animation'];
const cases = [
  { name: 'inline page over file://', args: ['--url', file, ...full, '--expect-source', 'inline', '--screenshot', join(shots, 'file-inline.png')] },
  { name: 'inline page over HTTP', args: ['--url', `${http}/sample-run.html`, ...full, '--expect-source', 'inline', '--screenshot', join(shots, 'http-inline.png')] },
  { name: '?run=&glb= over HTTP', args: ['--url', `${http}/index.html?run=sample-run.json&glb=sample.glb`, ...full, '--expect-source', 'url', '--screenshot', join(shots, 'http-url.png')] },
  {
    name: '?session= with a token (scene only)',
    args: ['--url', `${http}/index.html?session=sample&token=${TOKEN}`, '--expect-actions', '0', '--expect-animation', '--expect-source', 'session', '--screenshot', join(shots, 'http-session.png')],
    after: () => {
      const asked = server.requests.filter((r) => r.path === '/api/sessions/sample/scene.glb');
      if (!asked.some((r) => r.authorization === `Bearer ${TOKEN}`)) return 'the session GLB was not fetched with "Authorization: Bearer TOKEN"';
      return null;
    },
  },
  { name: '?session= without the token: error banner', args: ['--url', `${http}/index.html?session=sample`, '--expect-error', 'HTTP 401', '--screenshot', join(shots, 'error-401.png')] },
  { name: 'missing GLB: error banner', args: ['--url', `${http}/index.html?glb=missing.glb`, '--expect-error', 'HTTP 404'] },
  { name: 'no data: error banner', args: ['--url', `${http}/index.html`, '--expect-error', 'nothing to show'] },
  { name: '#t= snapshot, no UI, camera', args: ['--url', `${file}#t=4&ui=0&camera=120,35,2.2`, '--no-play', '--expect-time', '4', '--screenshot', join(shots, 'snapshot-t4.png')] },
  { name: '#sheet= contact sheet', args: ['--url', `${file}#sheet=0,1.5,3,4.5,6&labels=start|reach|grasped|carry|placed&cols=3`, '--screenshot', join(shots, 'sheet.png')] },
];
if (lang2manip) {
  cases.push({
    name: `lang2manip gltf scene through ?glb= (${lang2manip})`,
    before: async () => ((await runCommand(lang2manip, ['gltf', '-o', join(out, 'desk.glb')])) === 0 ? null : `${lang2manip} gltf failed`),
    args: ['--url', `${http}/index.html?glb=desk.glb`, '--expect-actions', '0', '--expect-source', 'url', '--screenshot', join(shots, 'lang2manip-desk.png')],
  });
}

let passed = 0;
let failed = 0;
const failures = [];
for (const c of cases) {
  console.log(`--- ${c.name}`);
  let problem = c.before ? await c.before() : null;
  if (!problem) problem = (await runNode([join(here, 'browser-test.mjs'), ...c.args])) === 0 ? null : 'browser test failed';
  if (!problem && c.after) problem = c.after();
  if (problem) {
    failed++;
    failures.push(`${c.name}: ${problem}`);
    console.log(`not ok: ${c.name}: ${problem}`);
  } else {
    passed++;
  }
}
await server.close();
if (failures.length) console.log(`failed:\n  ${failures.join('\n  ')}`);
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
