// Opens a viewer page in headless Chromium (Debian's, software WebGL) and checks it works:
// the scene is drawn, the actions are listed, the animation plays to its end.
//
// Usage: node test/browser-test.mjs --url URL [--screenshot FILE] [--expect-actions N]
//          [--expect-animation] [--expect-source inline|url|session|server] [--expect-error TEXT]
//          [--expect-time T] [--no-play] [--min-scene-share F] [--timeout SECONDS] [--chromium PATH] [--viewport WxH]
//          [--expect-text ID=TEXT]... [--expect-position NODE@T=X,Y,Z]...
// URL may be file:///.../run.html or http://127.0.0.1:PORT/...; with `#sheet=` in it the page is
// checked as a contact sheet. Exits 0 when every check passed, 1 with "FAIL: ..." otherwise.
import { chromium } from 'playwright-core';
import { existsSync } from 'node:fs';
import { mkdir } from 'node:fs/promises';
import { dirname, resolve } from 'node:path';

const USAGE =
  'usage: node test/browser-test.mjs --url URL [--screenshot FILE] [--expect-actions N] [--expect-animation]\n' +
  '         [--expect-source inline|url|session|server] [--expect-error TEXT] [--expect-time T] [--no-play]\n' +
  '         [--min-scene-share F] [--timeout SECONDS]\n' +
  '         [--chromium PATH] [--viewport WxH] [--expect-text ID=TEXT]... [--expect-position NODE@T=X,Y,Z]...';

function parseArgs(argv) {
  const args = { url: null, screenshot: null, expectActions: null, expectAnimation: false, expectSource: null, expectError: null, expectTime: null, play: true, minSceneShare: 0.01, timeout: 120, chromium: process.env.CHROMIUM || '/usr/bin/chromium', viewport: [1280, 800], expectTexts: [], expectPositions: [] };
  for (let i = 0; i < argv.length; i++) {
    const name = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) throw new Error(`${name} needs a value`);
      return argv[++i];
    };
    if (name === '--url') args.url = value();
    else if (name === '--screenshot') args.screenshot = resolve(value());
    else if (name === '--expect-actions') args.expectActions = Number(value());
    else if (name === '--expect-animation') args.expectAnimation = true;
    else if (name === '--expect-source') args.expectSource = value();
    else if (name === '--expect-error') args.expectError = value();
    else if (name === '--expect-time') args.expectTime = Number(value());
    else if (name === '--no-play') args.play = false;
    else if (name === '--min-scene-share') args.minSceneShare = Number(value());
    else if (name === '--timeout') args.timeout = Number(value());
    else if (name === '--chromium') args.chromium = value();
    else if (name === '--viewport') args.viewport = value().split('x').map(Number);
    else if (name === '--expect-text') {
      const [id, ...text] = value().split('=');
      if (!id || text.length === 0) throw new Error('--expect-text needs ID=TEXT');
      args.expectTexts.push({ id, text: text.join('=') });
    }
    else if (name === '--expect-position') {
      // NODE@T=X,Y,Z: at time T the node's origin is at (X, Y, Z) in the world (z up), within 2 mm.
      const text = value();
      const at = text.lastIndexOf('@');
      const equals = text.indexOf('=', at);
      const position = text.slice(equals + 1).split(',').map(Number);
      const time = Number(text.slice(at + 1, equals));
      if (at <= 0 || equals < 0 || position.length !== 3 || !position.every(Number.isFinite) || !Number.isFinite(time)) {
        throw new Error(`--expect-position needs NODE@T=X,Y,Z, got "${text}"`);
      }
      args.expectPositions.push({ node: text.slice(0, at), time, position });
    }
    else if (name === '--help' || name === '-h') {
      console.log(USAGE);
      process.exit(0);
    } else throw new Error(`unknown argument ${name}`);
  }
  if (!args.url) throw new Error('--url is required');
  if (args.expectActions !== null && !(Number.isInteger(args.expectActions) && args.expectActions >= 0)) throw new Error('--expect-actions needs a whole number');
  if (!(args.timeout > 0)) throw new Error('--timeout needs a positive number of seconds');
  if (args.viewport.length !== 2 || !args.viewport.every((x) => x > 0)) throw new Error('--viewport needs WIDTHxHEIGHT');
  return args;
}

class Failure extends Error {}

function check(condition, message) {
  if (!condition) throw new Failure(message);
}

// Installed in the page: pixel statistics of the WebGL canvas (read back through toDataURL).
const PAGE_HELPERS = `
window.__l2mTest = {
  async pixels(canvas) {
    const image = new Image();
    image.src = canvas.toDataURL('image/png');
    await image.decode();
    const copy = document.createElement('canvas');
    copy.width = image.width;
    copy.height = image.height;
    const context = copy.getContext('2d');
    context.drawImage(image, 0, 0);
    return context.getImageData(0, 0, copy.width, copy.height);
  },
  background() {
    const hex = window.lang2manipViewer.background.replace('#', '');
    return [0, 2, 4].map((i) => parseInt(hex.slice(i, i + 2), 16));
  },
  differs(data, i, rgb) {
    return Math.abs(data[i] - rgb[0]) + Math.abs(data[i + 1] - rgb[1]) + Math.abs(data[i + 2] - rgb[2]) > 24;
  },
  /** Share of the canvas's pixels that are not the background colour. */
  async sceneShare(canvas) {
    const { data, width, height } = await this.pixels(canvas || document.getElementById('viewer-canvas'));
    const rgb = this.background();
    let count = 0;
    for (let i = 0; i < data.length; i += 4) if (this.differs(data, i, rgb)) count++;
    return { share: count / (width * height), width, height };
  },
  async remember() {
    this.saved = await this.pixels(document.getElementById('viewer-canvas'));
  },
  /** Share of the canvas's pixels that changed since remember(). */
  async changedShare() {
    const { data, width, height } = await this.pixels(document.getElementById('viewer-canvas'));
    const before = this.saved.data;
    if (before.length !== data.length) return 1;
    let count = 0;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - before[i]) + Math.abs(data[i + 1] - before[i + 1]) + Math.abs(data[i + 2] - before[i + 2]) > 24) count++;
    }
    return count / (width * height);
  },
};`;

async function run(args) {
  const log = (message) => console.log(`  ok  ${message}`);
  check(existsSync(args.chromium), `no Chromium at ${args.chromium} (install Debian's: apt-get install -y chromium, or pass --chromium PATH)`);
  const browser = await chromium.launch({
    executablePath: args.chromium,
    headless: true,
    timeout: args.timeout * 1000,
    args: ['--use-angle=swiftshader', '--use-gl=angle', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--disable-dev-shm-usage'],
  });
  const pageErrors = [];
  const consoleErrors = [];
  try {
    const context = await browser.newContext({ viewport: { width: args.viewport[0], height: args.viewport[1] }, deviceScaleFactor: 1 });
    const page = await context.newPage();
    page.setDefaultTimeout(args.timeout * 1000);
    page.on('pageerror', (error) => pageErrors.push(error.message));
    page.on('console', (message) => {
      if (message.type() === 'error') consoleErrors.push(message.text());
    });
    const timeout = args.timeout * 1000;

    await page.goto(args.url, { waitUntil: 'load', timeout });
    await page
      .waitForFunction(() => ['ready', 'rendered', 'playing', 'paused', 'ended', 'error'].includes(document.body && document.body.dataset.state), null, { timeout, polling: 100 })
      .catch(async () => {
        const state = await page.evaluate(() => document.body && document.body.dataset.state).catch(() => undefined);
        throw new Failure(`the viewer did not become ready within ${args.timeout} s (state: ${state})`);
      });
    let state = await page.evaluate(() => document.body.dataset.state);
    const sheet = /[#&]sheet=/.test(new URL(args.url).hash);
    if (sheet && state === 'ready') {
      await page.waitForFunction(() => ['rendered', 'error'].includes(document.body.dataset.state), null, { timeout, polling: 100 });
      state = await page.evaluate(() => document.body.dataset.state);
    }

    if (args.expectError !== null) {
      check(state === 'error', `expected the error banner, but the viewer's state is "${state}"`);
      const shown = await page.evaluate(() => ({ error: document.body.dataset.error, banner: document.getElementById('error-banner').textContent, visible: document.getElementById('error-banner').offsetParent !== null }));
      check(shown.visible, 'the error banner is not visible');
      check(shown.error.includes(args.expectError), `the error is "${shown.error}", expected it to contain "${args.expectError}"`);
      log(`error banner shown: ${shown.banner}`);
      await screenshot(page, args);
      return;
    }
    if (state === 'error') throw new Failure(`the viewer reports an error: ${await page.evaluate(() => document.body.dataset.error)}`);
    log(`viewer ${sheet ? 'rendered the contact sheet' : 'ready'} (state "${state}")`);
    await page.evaluate(PAGE_HELPERS);

    const info = await page.evaluate(() => window.lang2manipViewer.state());
    if (args.expectSource) check(info.source === args.expectSource, `data source is "${info.source}", expected "${args.expectSource}"`);
    check(info.entities > 0, 'the scene has no link or object nodes');
    if (args.expectTime !== null) {
      check(Math.abs(info.time - args.expectTime) < 1e-6, `the viewer is at t = ${info.time}, expected ${args.expectTime}`);
      check(!info.playing, 'the viewer plays, expected it paused at the #t= time');
    }
    log(`source ${info.source}, ${info.entities} links/objects, ${info.toolPaths} tool paths, tree ${info.hasTree}, animation ${info.hasAnimation}, duration ${info.duration.toFixed(2)} s`);

    // Where the page draws a node at a time is where forward kinematics puts it.
    for (const { node, time, position } of args.expectPositions) {
      const shown = await page.evaluate(([name, t]) => {
        window.lang2manipViewer.pause();
        window.lang2manipViewer.seek(t);
        return window.lang2manipViewer.nodeWorldPosition(name);
      }, [node, time]);
      check(shown !== null, `the scene has no node "${node}"`);
      const distance = Math.hypot(...shown.map((v, i) => v - position[i]));
      check(distance < 0.002, `at t = ${time} the page draws "${node}" at (${shown.map((v) => v.toFixed(4)).join(', ')}), ` +
        `forward kinematics puts it at (${position.map((v) => v.toFixed(4)).join(', ')}): ${(distance * 1000).toFixed(1)} mm apart`);
      log(`at t = ${time.toFixed(3)} s "${node}" is drawn within ${(distance * 1000).toFixed(2)} mm of forward kinematics`);
    }
    if (args.expectPositions.length) await page.evaluate((t) => window.lang2manipViewer.seek(t), info.time);

    if (sheet) {
      const expected = new URL(args.url).hash.match(/sheet=([^&]*)/)[1].split(',').filter((x) => x.trim() !== '').length;
      const cells = await page.evaluate(async () => {
        const result = [];
        for (const figure of document.querySelectorAll('#sheet-grid figure')) {
          const { share } = await window.__l2mTest.sceneShare(figure.querySelector('canvas'));
          result.push({ share, label: figure.querySelector('figcaption').textContent });
        }
        return result;
      });
      check(cells.length === expected, `the contact sheet has ${cells.length} cells, expected ${expected}`);
      cells.forEach((cell, i) => check(cell.share > args.minSceneShare, `contact sheet cell ${i} ("${cell.label}") is blank: ${(cell.share * 100).toFixed(2)}% of its pixels are not background`));
      log(`contact sheet: ${cells.length} cells, labels ${cells.map((c) => JSON.stringify(c.label)).join(', ')}`);
      await screenshot(page, args, true);
      return;
    }

    if (!args.play) {
      // A snapshot: check the frame as the page shows it, change nothing.
      const stats = await page.evaluate(() => window.__l2mTest.sceneShare());
      check(stats.share > args.minSceneShare, `the scene is not drawn: ${(stats.share * 100).toFixed(2)}% of the canvas's pixels differ from the background`);
      log(`snapshot at t = ${info.time.toFixed(2)} s: ${(stats.share * 100).toFixed(1)}% of the canvas is not background`);
      await screenshot(page, args);
      if (pageErrors.length) throw new Failure(`the page threw: ${pageErrors.join(' | ')}`);
      return;
    }

    // The scene is drawn: without the ground grid, enough pixels differ from the background.
    const withoutGrid = await page.evaluate(async () => {
      window.lang2manipViewer.setToggle('grid', false);
      const stats = await window.__l2mTest.sceneShare();
      window.lang2manipViewer.setToggle('grid', true);
      return stats;
    });
    check(withoutGrid.share > args.minSceneShare, `the scene is not drawn: ${(withoutGrid.share * 100).toFixed(2)}% of the canvas's pixels differ from the background (needs > ${(args.minSceneShare * 100).toFixed(2)}%)`);
    log(`scene drawn: ${(withoutGrid.share * 100).toFixed(1)}% of the ${withoutGrid.width}x${withoutGrid.height} canvas is not background`);

    // The controls of the contract are there.
    const controls = await page.evaluate(() => {
      const ids = ['play', 'speed', 'scrubber', 'time', 'toggle-collision', 'toggle-paths', 'toggle-tree', 'toggle-axes', 'actions', 'panel'];
      return {
        missing: ids.filter((id) => !document.getElementById(id)),
        speeds: [...document.querySelectorAll('#speed option')].map((o) => Number(o.value)),
        scrubber: document.getElementById('scrubber').type,
      };
    });
    check(controls.missing.length === 0, `missing elements: ${controls.missing.map((id) => `#${id}`).join(', ')}`);
    check([0.25, 0.5, 1, 2, 4].every((s) => controls.speeds.includes(s)), `#speed offers ${controls.speeds.join(', ')}, expected 0.25, 0.5, 1, 2, 4`);
    check(controls.scrubber === 'range', '#scrubber is not an input range');
    log('controls present (#play, #speed, #scrubber, toggles)');

    const listed = await page.evaluate(() => [...document.querySelectorAll('#actions > li')].map((li) => ({ id: li.id, text: li.textContent })));
    if (args.expectActions !== null) {
      check(listed.length === args.expectActions, `the action list shows ${listed.length} actions, expected ${args.expectActions}`);
      check(listed.every((a) => /^action-\d+$/.test(a.id)), `action items without an id action-<index>: ${listed.map((a) => a.id).join(', ')}`);
      log(`${listed.length} actions listed: ${listed.map((a) => a.id).join(', ')}`);
    }

    // Collision geometry swaps with the visual one.
    if (info.hasCollisionGroups) {
      await page.evaluate(() => window.__l2mTest.remember());
      await page.click('#toggle-collision');
      const changed = await page.evaluate(() => (window.lang2manipViewer.render(), window.__l2mTest.changedShare()));
      check(changed > 0.001, `toggling collision geometry changed ${(changed * 100).toFixed(3)}% of the pixels`);
      await page.click('#toggle-collision');
      log(`#toggle-collision swaps visual and collision geometry (${(changed * 100).toFixed(1)}% of the pixels changed)`);
    }

    // Axes at every link and object frame appear and disappear with their toggle (paused, so that
    // only the toggle changes the picture).
    await page.evaluate(() => {
      window.lang2manipViewer.pause();
      window.lang2manipViewer.seek(0);
      return window.__l2mTest.remember();
    });
    await page.click('#toggle-axes');
    const axes = await page.evaluate(() => (window.lang2manipViewer.render(), window.__l2mTest.changedShare()));
    check(axes > 0.0003, `toggling the axes changed ${(axes * 100).toFixed(3)}% of the pixels`);
    await page.click('#toggle-axes');
    const axesOff = await page.evaluate(() => (window.lang2manipViewer.render(), window.__l2mTest.changedShare()));
    check(axesOff < axes / 10, `the axes stay after toggling them off (${(axesOff * 100).toFixed(3)}% of the pixels still differ)`);
    log(`#toggle-axes shows and hides the frames (${(axes * 100).toFixed(2)}% of the pixels changed)`);

    // The run document's text sections show its content (as text).
    for (const { id, text } of args.expectTexts) {
      const shown = await page.evaluate((element) => {
        const found = document.getElementById(element);
        return found ? found.textContent : null;
      }, id);
      check(shown !== null, `no element #${id}`);
      check(shown.includes(text), `#${id} does not contain "${text}" (it shows "${shown.slice(0, 120)}")`);
      log(`#${id} shows "${text}"`);
    }

    const duration = info.duration;
    if (args.expectAnimation) {
      check(info.hasAnimation, 'the scene has no trajectory animation');
      check(duration > 0, `the timeline's duration is ${duration}`);
      const moved = await page.evaluate(async () => {
        const v = window.lang2manipViewer;
        v.seek(0);
        await window.__l2mTest.remember();
        v.seek(v.duration);
        return window.__l2mTest.changedShare();
      });
      check(moved > 0.0005, `the animation moves nothing: ${(moved * 100).toFixed(3)}% of the pixels differ between t=0 and the end`);
      log(`animation moves the scene (${(moved * 100).toFixed(2)}% of the pixels differ between the start and the end)`);
    }

    // Each timed action is highlighted while the time is inside it.
    const timed = await page.evaluate(() => {
      const v = window.lang2manipViewer;
      const result = [];
      for (const li of document.querySelectorAll('#actions > li')) {
        const times = li.querySelector('.times');
        if (!times) continue;
        const [start, end] = times.textContent.match(/[\d.]+/g).map(Number);
        v.seek((start + end) / 2);
        result.push({ id: li.id, playing: [...document.querySelectorAll('#actions > li.playing')].map((x) => x.id), action: v.state().action });
      }
      v.seek(0);
      return result;
    });
    for (const t of timed) check(t.playing.length === 1 && t.playing[0] === t.id, `in the middle of ${t.id} the highlighted actions are [${t.playing.join(', ')}]`);
    if (timed.length) log(`the action playing is highlighted (class "playing") for ${timed.map((t) => t.id).join(', ')}`);

    // Play at speed 4 from near the end until it ends.
    if (duration > 0) {
      const from = Math.max(0, duration - 8);
      await page.evaluate((t) => {
        const v = window.lang2manipViewer;
        window.__l2mStates = [];
        new MutationObserver(() => window.__l2mStates.push(document.body.dataset.state)).observe(document.body, { attributes: true, attributeFilter: ['data-state'] });
        v.setSpeed(4);
        v.seek(t);
        v.play();
      }, from);
      const playTimeout = Math.max(30, (duration - from) / 4 * 10) * 1000;
      await page.waitForFunction(() => document.body.dataset.state === 'ended', null, { timeout: Math.min(playTimeout, timeout), polling: 100 }).catch(async () => {
        const s = await page.evaluate(() => window.lang2manipViewer.state());
        throw new Failure(`playback did not end: state "${s.state}" at ${s.time.toFixed(2)} of ${s.duration.toFixed(2)} s`);
      });
      const end = await page.evaluate(() => ({ info: window.lang2manipViewer.state(), states: window.__l2mStates, play: document.getElementById('play').textContent, scrubber: Number(document.getElementById('scrubber').value), time: document.getElementById('time').textContent, speed: document.getElementById('speed').value }));
      check(end.states.includes('playing'), `the state never was "playing" (states: ${end.states.join(' -> ')})`);
      check(Math.abs(end.info.time - duration) < 1e-6, `ended at ${end.info.time}, not at the duration ${duration}`);
      check(Math.abs(end.scrubber - duration) < 0.01, `the scrubber shows ${end.scrubber} at the end`);
      check(end.speed === '4', `#speed shows ${end.speed} after setSpeed(4)`);
      log(`played at speed 4 from ${from.toFixed(2)} s to the end (states ${end.states.join(' -> ')}; time text "${end.time}")`);
    } else {
      log('no timeline (duration 0): playback not checked');
    }

    await screenshot(page, args);
    if (pageErrors.length) throw new Failure(`the page threw: ${pageErrors.join(' | ')}`);
    if (consoleErrors.length) console.log(`  note: console errors: ${consoleErrors.join(' | ')}`);
  } finally {
    await browser.close();
  }
}

async function screenshot(page, args, fullPage = false) {
  if (!args.screenshot) return;
  await mkdir(dirname(args.screenshot), { recursive: true });
  await page.screenshot({ path: args.screenshot, fullPage });
  console.log(`  ok  screenshot ${args.screenshot}`);
}

let args;
try {
  args = parseArgs(process.argv.slice(2));
} catch (error) {
  console.error(`FAIL: ${error.message}\n${USAGE}`);
  process.exit(2);
}
console.log(`browser test: ${args.url}`);
const started = Date.now();
const overall = setTimeout(() => {
  console.error(`FAIL: ${args.url}: the test took longer than ${args.timeout * 3} s`);
  process.exit(1);
}, args.timeout * 3 * 1000);
try {
  await run(args);
  clearTimeout(overall);
  console.log(`PASS ${args.url} (${((Date.now() - started) / 1000).toFixed(1)} s)`);
} catch (error) {
  clearTimeout(overall);
  console.error(`FAIL: ${args.url}: ${error instanceof Failure ? error.message : error.stack || error.message}`);
  process.exit(1);
}
