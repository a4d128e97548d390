// The viewer with the real lang2manip, in headless Chromium: the page `run --html` writes, opened
// from the file system; and `lang2manip serve` (with a token) showing a session's scene and a run
// it executed. Screenshots go to OUT/ (CI keeps them as artifacts).
// Usage: node test/lang2manip-e2e.mjs --lang2manip PATH_TO_CLI --out DIR
// Prints one line per case and "N passed, N failed"; exits 1 when a case failed.
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { mkdir, rm } from 'node:fs/promises';
import { join, resolve, dirname } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const option = (name) => {
  const i = process.argv.indexOf(name);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : null;
};
const lang2manip = option('--lang2manip');
const out = option('--out') && resolve(option('--out'));
if (!lang2manip || !out) {
  console.error('usage: node test/lang2manip-e2e.mjs --lang2manip PATH_TO_CLI --out DIR');
  process.exit(2);
}
const TOKEN = 'e2e-token';
const chromium = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(chromium)) {
  // `make test` installs Chromium and sets LANG2MANIP_REQUIRE_BROWSER=1: there, a missing one fails.
  const required = process.env.LANG2MANIP_REQUIRE_BROWSER === '1';
  console.log(`lang2manip-e2e: ${required ? 'FAILED' : 'skipped'}: no Chromium at ${chromium} (Debian: apt-get install chromium; or set CHROMIUM)`);
  process.exit(required ? 1 : 77);
}

function run(command, args, { capture = false } = {}) {
  return new Promise((done) => {
    const child = spawn(command, args, { stdio: ['ignore', capture ? 'pipe' : 'inherit', 'inherit'] });
    let output = '';
    if (capture) child.stdout.on('data', (d) => (output += d));
    child.on('error', (error) => done({ code: 127, output: String(error) }));
    child.on('close', (code) => done({ code, output }));
  });
}

/// `lang2manip serve --port 0 --token TOKEN`, resolved once it prints its address.
function startServer() {
  return new Promise((ready, fail) => {
    const child = spawn(lang2manip, ['serve', '--port', '0', '--token', TOKEN], { stdio: ['ignore', 'pipe', 'inherit'] });
    let output = '';
    const timer = setTimeout(() => fail(new Error(`serve printed no address: ${output}`)), 30000);
    child.stdout.on('data', (d) => {
      output += d;
      const match = /serving on (http:\/\/[^/ ]+)\//.exec(output);
      if (match) {
        clearTimeout(timer);
        ready({ child, url: match[1] });
      }
    });
    child.on('error', fail);
  });
}

async function api(url, path, body) {
  const response = await fetch(url + path, {
    method: body === undefined ? 'GET' : 'POST',
    headers: { Authorization: `Bearer ${TOKEN}`, 'Content-Type': 'application/json' },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const text = await response.text();
  if (!response.ok) throw new Error(`${path}: HTTP ${response.status}: ${text}`);
  return JSON.parse(text);
}

async function waitForRun(url, id) {
  for (let i = 0; i < 600; i++) {
    const status = await api(url, `/api/runs/${id}`);
    if (!['queued', 'running'].includes(status.state)) return status;
    await new Promise((r) => setTimeout(r, 200));
  }
  throw new Error(`run ${id} did not finish`);
}

const browserTest = (args) => run(process.execPath, [join(here, 'browser-test.mjs'), ...args]);

await rm(out, { recursive: true, force: true });
await mkdir(out, { recursive: true });
const cases = [];
cases.push({
  name: 'run --html, opened from the file system',
  test: async () => {
    const made = await run(lang2manip, ['run', '--html', '--out', join(out, 'run')]);
    if (made.code !== 0) return `lang2manip run --html exited with ${made.code}`;
    const url = pathToFileURL(join(out, 'run', 'run.html')).href;
    const checked = await browserTest(['--url', url, '--expect-actions', '4', '--expect-animation', '--expect-source', 'inline',
      '--expect-text', 'observation=marker', '--expect-text', 'prompt=put the marker and eraser in the holder',
      '--screenshot', join(out, 'run-html.png')]);
    return checked.code === 0 ? null : 'browser test failed';
  },
});
cases.push({
  name: 'serve: a session\'s scene and a run, with a token',
  test: async () => {
    const server = await startServer();
    try {
      await api(server.url, '/api/sessions/e2e/openProblem', { problem: 'panda_desk' });
      const session = await browserTest(['--url', `${server.url}/?session=e2e&token=${TOKEN}`, '--expect-source', 'session',
        '--expect-actions', '0', '--no-play', '--screenshot', join(out, 'serve-session.png')]);
      if (session.code !== 0) return 'browser test of the session failed';
      const landing = await browserTest(['--url', `${server.url}/?token=${TOKEN}`, '--expect-source', 'server', '--expect-actions', '0',
        '--no-play', '--screenshot', join(out, 'serve-landing.png')]);
      if (landing.code !== 0) return 'browser test of the served page with nothing named failed';
      const started = await api(server.url, '/api/runs', { task: 'put the marker in the holder' });
      const status = await waitForRun(server.url, started.id);
      if (status.state !== 'succeeded') return `the run ended ${status.state}`;
      const files = `/api/runs/${started.id}/files`;
      const page = `${server.url}/?run=${files}/viewer.json&glb=${files}/scene.glb&token=${TOKEN}`;
      const shown = await browserTest(['--url', page, '--expect-source', 'url', '--expect-actions', '2', '--expect-animation',
        '--screenshot', join(out, 'serve-run.png')]);
      return shown.code === 0 ? null : 'browser test of the run failed';
    } finally {
      server.child.kill('SIGTERM');
    }
  },
});

let passed = 0;
let failed = 0;
for (const c of cases) {
  console.log(`--- ${c.name}`);
  let problem;
  try {
    problem = await c.test();
  } catch (error) {
    problem = String(error && error.message ? error.message : error);
  }
  if (problem) {
    failed++;
    console.log(`not ok: ${c.name}: ${problem}`);
  } else {
    passed++;
  }
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
