// lang2manip web viewer: shows a run (its scene as GLB, its trajectory animation, its run document)
// in the browser. The bundle builds all of its DOM itself, so it works both loaded by index.html
// and inlined into a self-contained page. See README.md for the data contract and the test API.
import css from './viewer.css';
import { hashParams, queryParams } from './params.js';
import { LoadError, loadData, touchedObjects } from './data.js';
import { BACKGROUND, DEFAULT_VIEW, SceneView, parseGlb } from './scene.js';

const SPEEDS = [0.25, 0.5, 1, 2, 4];
const TOGGLES = ['collision', 'paths', 'tree', 'axes'];

/** A DOM element: el('div', {id: 'x', className: 'y'}, child, 'text', ...). */
function el(tag, props = {}, ...children) {
  const element = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (key === 'dataset') Object.assign(element.dataset, value);
    else if (key in element) element[key] = value;
    else element.setAttribute(key, value);
  }
  for (const child of children) if (child !== null && child !== undefined) element.append(child);
  return element;
}

function formatTime(seconds) {
  return `${seconds.toFixed(2)} s`;
}

function number(value) {
  return typeof value === 'number' && Number.isFinite(value) ? value : null;
}

// ---- state and the automation API -------------------------------------------------------------

let state = 'loading';
let time = 0;
let duration = 0;
let speed = 1;
let playing = false;
let lastFrame = 0;
let run = null;
let source = null;
let actions = []; // {index, start, end, item, entry}
let currentAction = null;
let view = null;
let dom = null;
let errorMessage = null;
let hash = hashParams();
let panelHidden = false;

let resolveReady;
let rejectReady;
const ready = new Promise((resolve, reject) => {
  resolveReady = resolve;
  rejectReady = reject;
});
ready.catch(() => {}); // a failed load is reported in the page; no unhandled rejection

function setState(next) {
  state = next;
  if (document.body) document.body.dataset.state = next;
  if (dom) {
    dom.root.dataset.state = next;
    dom.play.textContent = next === 'playing' ? 'Pause' : next === 'ended' ? 'Replay' : 'Play';
  }
}

function stateInfo() {
  return {
    state,
    time,
    duration,
    speed,
    playing,
    action: currentAction,
    source,
    hasRun: run !== null,
    hasAnimation: Boolean(view && view.action),
    actions: actions.length,
    entities: view ? view.entities.length : 0,
    toolPaths: view ? view.toolPathByAction.size : 0,
    hasTree: Boolean(view && view.tree),
    hasCollisionGroups: Boolean(view && view.model && view.hasCollisionGroups),
    error: errorMessage,
  };
}

window.lang2manipViewer = {
  ready,
  get duration() {
    return duration;
  },
  play,
  pause,
  seek,
  setSpeed,
  state: stateInfo,
  /** Not in the contract's core, for tests and automation. */
  background: `#${BACKGROUND.toString(16).padStart(6, '0')}`,
  setToggle(name, on) {
    if (name === 'grid') {
      if (view) view.setGrid(on);
    } else setToggle(name, on);
    renderNow();
  },
  setCamera(azimuth, elevation, distance) {
    if (view) view.setView({ azimuth, elevation, distance: distance > 0 ? distance : null });
    renderNow();
  },
  render: renderNow,
  /** World position (x, y, z; z up) of a node of the scene at the current time, or null. */
  nodeWorldPosition(name) {
    return view ? view.nodeWorldPosition(name) : null;
  },
};

// ---- playback ----------------------------------------------------------------------------------

function renderNow() {
  if (view) view.render();
}

function actionAt(t) {
  let found = null;
  for (const action of actions) {
    if (action.start === null || action.end === null) continue;
    if (action.start <= t && t < action.end) found = action;
  }
  if (found === null) {
    for (const action of actions) if (action.start !== null && action.end !== null && action.start <= t && t <= action.end) found = action;
  }
  return found;
}

function applyTime() {
  if (view) view.setTime(time);
  if (dom) {
    dom.scrubber.value = String(time);
    dom.time.textContent = `${formatTime(time)} / ${formatTime(duration)}`;
  }
  const action = actionAt(time);
  const index = action ? action.index : null;
  if (index !== currentAction) {
    currentAction = index;
    for (const a of actions) a.item.classList.toggle('playing', a === action);
    if (action && playing && action.item.scrollIntoView) action.item.scrollIntoView({ block: 'nearest' });
    if (view) view.highlightPath(index);
  }
}

function play() {
  if (!view || state === 'loading' || state === 'error') return;
  if (duration <= 0) {
    time = 0;
    applyTime();
    renderNow();
    setState('ended');
    return;
  }
  if (time >= duration) time = 0;
  playing = true;
  lastFrame = performance.now();
  applyTime();
  setState('playing');
}

function pause() {
  if (!playing) return;
  playing = false;
  setState('paused');
}

function seek(seconds) {
  if (!view) return;
  const t = Number(seconds);
  time = Math.min(Math.max(Number.isFinite(t) ? t : 0, 0), duration);
  applyTime();
  renderNow();
  if (state === 'ended' && time < duration) setState('paused');
}

function setSpeed(x) {
  const value = Number(x);
  if (!(value > 0)) return;
  speed = value;
  if (dom) {
    if (!SPEEDS.includes(value) && ![...dom.speed.options].some((o) => Number(o.value) === value)) {
      dom.speed.append(el('option', { value: String(value), textContent: `${value}x` }));
    }
    dom.speed.value = String(value);
  }
}

function tick(now) {
  requestAnimationFrame(tick);
  if (!view) return;
  if (playing) {
    const dt = Math.min(0.25, Math.max(0, (now - lastFrame) / 1000));
    lastFrame = now;
    time = Math.min(duration, time + dt * speed);
    applyTime();
    if (time >= duration) {
      playing = false;
      view.render();
      setState('ended');
      return;
    }
  }
  if (view.needsRender) view.render();
}

// ---- DOM ----------------------------------------------------------------------------------------

function injectStyle() {
  if (document.getElementById('lang2manip-viewer-style')) return;
  const style = el('style', { id: 'lang2manip-viewer-style', textContent: css });
  (document.head || document.body).append(style);
}

function buildDom() {
  const canvas = el('canvas', { id: 'viewer-canvas', tabIndex: 0 });
  const play = el('button', { id: 'play', type: 'button', textContent: 'Play', disabled: true, title: 'Play / pause (space)' });
  const speedSelect = el('select', { id: 'speed', title: 'Playback speed', disabled: true });
  for (const s of SPEEDS) speedSelect.append(el('option', { value: String(s), textContent: `${s}x` }));
  speedSelect.value = '1';
  const scrubber = el('input', { id: 'scrubber', type: 'range', min: '0', max: '0', step: 'any', value: '0', disabled: true, title: 'Time' });
  const timeText = el('span', { id: 'time', textContent: '0.00 s / 0.00 s' });
  const toggles = el('div', { id: 'toggles' });
  const toggleInputs = {};
  const labels = { collision: 'collision', paths: 'tool paths', tree: 'exploration tree', axes: 'axes' };
  for (const name of TOGGLES) {
    const input = el('input', { id: `toggle-${name}`, type: 'checkbox', checked: name === 'paths' });
    toggleInputs[name] = input;
    toggles.append(el('label', { htmlFor: `toggle-${name}`, id: `label-${name}` }, input, labels[name]));
  }
  const task = el('h1', { id: 'task', className: 'empty', textContent: 'No run document' });
  const hidePanel = el('button', { id: 'hide-panel', type: 'button', textContent: '\u00bb', title: 'Hide the panel' });
  const meta = el('div', { id: 'meta' });
  const actionList = el('ol', { id: 'actions' });
  const actionsEmpty = el('div', { id: 'actions-empty', textContent: 'No actions.' });
  const sections = {};
  for (const [key, title] of [
    ['observation', 'Observation'],
    ['prompt', 'Prompt'],
    ['report', 'Report'],
  ]) {
    const pre = el('pre', { id: key });
    const details = el('details', { id: `${key}-section`, hidden: true }, el('summary', { textContent: title }), pre);
    sections[key] = { details, pre };
  }
  const panel = el(
    'aside',
    { id: 'panel' },
    el('div', { id: 'panel-head' }, task, hidePanel),
    meta,
    el('div', { id: 'controls' }, play, timeText, speedSelect, scrubber),
    toggles,
    el('h2', { textContent: 'Actions' }),
    actionList,
    actionsEmpty,
    sections.observation.details,
    sections.prompt.details,
    sections.report.details,
  );
  const showPanel = el('button', { id: 'show-panel', type: 'button', textContent: '\u00ab', title: 'Show the panel' });
  const banner = el('div', { id: 'error-banner', role: 'alert' });
  const loading = el('div', { id: 'loading', textContent: 'Loading\u2026' });
  const sheetTitle = el('h1', { id: 'sheet-title' });
  const sheetGrid = el('div', { id: 'sheet-grid' });
  const sheet = el('div', { id: 'sheet' }, sheetTitle, sheetGrid);
  const root = el('div', { id: 'lang2manip-viewer', className: 'loading' }, canvas, panel, showPanel, banner, loading, sheet);
  document.body.append(root);

  play.addEventListener('click', () => (playing ? pause() : play()));
  speedSelect.addEventListener('change', () => setSpeed(speedSelect.value));
  scrubber.addEventListener('input', () => seek(scrubber.value));
  for (const name of TOGGLES) toggleInputs[name].addEventListener('change', () => setToggle(name, toggleInputs[name].checked));
  hidePanel.addEventListener('click', () => setPanelHidden(true));
  showPanel.addEventListener('click', () => setPanelHidden(false));
  document.addEventListener('keydown', (event) => {
    if (event.code !== 'Space' || event.repeat) return;
    const tag = event.target && event.target.tagName;
    if (tag === 'INPUT' || tag === 'SELECT' || tag === 'BUTTON' || tag === 'TEXTAREA') return;
    event.preventDefault();
    if (playing) pause();
    else play();
  });

  return { root, canvas, panel, play, speed: speedSelect, scrubber, time: timeText, toggleInputs, task, meta, actionList, actionsEmpty, sections, banner, sheetTitle, sheetGrid };
}

function setToggle(name, on) {
  if (!view || !TOGGLES.includes(name)) return;
  on = Boolean(on);
  if (dom) dom.toggleInputs[name].checked = on;
  if (name === 'collision') view.setCollision(on);
  if (name === 'paths') view.setPaths(on);
  if (name === 'tree') view.setTree(on);
  if (name === 'axes') view.setAxes(on);
}

function setPanelHidden(hidden) {
  panelHidden = hidden;
  dom.root.classList.toggle('panel-hidden', hidden);
  layout();
}

function layout() {
  if (!view || !dom) return;
  const showsPanel = hash.ui && !panelHidden && !hash.sheet;
  view.resize(dom.root.clientWidth, dom.root.clientHeight, showsPanel ? dom.panel.offsetWidth : 0);
  renderNow();
}

function fillRun() {
  const { task, meta, actionList, actionsEmpty, sections } = dom;
  meta.replaceChildren();
  if (!run) {
    task.textContent = source === 'session' ? 'Scene only (session)' : source === 'server' ? "Scene only (the server's problem)" : 'Scene only';
    task.className = 'empty';
    actionsEmpty.textContent = 'No run document: scene only.';
    return;
  }
  if (typeof run.task === 'string' && run.task.trim()) {
    task.textContent = run.task;
    task.className = '';
    if (!document.title) document.title = `lang2manip: ${run.task}`;
  } else {
    task.textContent = '(no task)';
  }
  if (typeof run.success === 'boolean') {
    meta.append(el('span', { id: 'success', className: `badge ${run.success ? 'success' : 'failure'}`, textContent: run.success ? 'succeeded' : 'failed' }));
  }
  if (typeof run.robot === 'string' && run.robot) meta.append(el('span', { id: 'robot', className: 'badge', textContent: run.robot }));
  if (number(run.duration) !== null) meta.append(el('span', { id: 'run-duration', textContent: formatTime(run.duration) }));

  const list = Array.isArray(run.actions) ? run.actions : [];
  list.forEach((action, position) => {
    if (!action || typeof action !== 'object') return;
    const index = Number.isInteger(action.index) ? action.index : position;
    const start = number(action.start_time);
    const end = number(action.end_time);
    const text = typeof action.text === 'string' && action.text ? action.text : [action.kind, action.object].filter((x) => typeof x === 'string' && x).join(' ') || 'action';
    const status = typeof action.status === 'string' ? action.status : '';
    const item = el(
      'li',
      { id: `action-${index}`, className: status ? `status-${status.replace(/[^A-Za-z0-9_-]/g, '_')}` : '', dataset: { index: String(index) } },
      el('span', { className: 'index', textContent: `${index + 1}.` }), // numbered from 1, as the CLI numbers them
      el('span', { className: 'text', textContent: text }),
      el('span', { className: 'status', textContent: status }),
    );
    if (start !== null && end !== null) {
      item.append(el('span', { className: 'index' }), el('span', { className: 'times', textContent: `${start.toFixed(2)} \u2013 ${end.toFixed(2)} s` }));
      item.title = 'Go to the start of this action';
      item.addEventListener('click', () => seek(start));
    }
    actionList.append(item);
    actions.push({ index, start, end, item, text });
  });
  actionsEmpty.hidden = actions.length > 0;
  view.frame(touchedObjects(run));

  for (const key of ['observation', 'prompt', 'report']) {
    const value = run[key];
    if (value === undefined || value === null || value === '') continue;
    sections[key].pre.textContent = typeof value === 'string' ? value : JSON.stringify(value, null, 2);
    sections[key].details.hidden = false;
  }
}

function fail(error) {
  const message = error instanceof LoadError || !(error instanceof Error) ? String(error.message || error) : `${error.name}: ${error.message}`;
  errorMessage = message;
  console.error(`lang2manip viewer: ${message}`);
  if (dom) {
    dom.root.classList.remove('loading');
    dom.banner.textContent = `Cannot show this run: ${message}`;
    dom.banner.classList.add('shown');
  }
  if (document.body) document.body.dataset.error = message;
  setState('error');
  rejectReady(new Error(message));
}

// ---- hash parameters: snapshot time, camera, UI, contact sheet ----------------------------------

function applyHash(first) {
  dom.root.classList.toggle('no-ui', !hash.ui);
  layout();
  if (hash.camera) view.setView(hash.camera);
  else if (first) view.setView(DEFAULT_VIEW);
  if (hash.speed) setSpeed(hash.speed);
  if (hash.t !== null) {
    pause();
    seek(hash.t);
  }
  renderNow();
}

function sheetLabel(t, index) {
  if (hash.labels && index < hash.labels.length && hash.labels[index] !== '') return hash.labels[index];
  const action = actionAt(t);
  return action ? `t = ${formatTime(t)}: ${action.text}` : `t = ${formatTime(t)}`;
}

function renderSheet() {
  const times = hash.sheet;
  const cols = Math.min(hash.cols || Math.ceil(Math.sqrt(times.length)), times.length);
  dom.root.classList.add('sheet-mode');
  dom.sheetTitle.textContent = run && typeof run.task === 'string' ? run.task : '';
  dom.sheetTitle.hidden = !dom.sheetTitle.textContent;
  dom.sheetGrid.style.gridTemplateColumns = `repeat(${cols}, minmax(0, 1fr))`;
  const gap = 8;
  const width = Math.max(80, Math.floor((window.innerWidth - 20 - (cols - 1) * gap) / cols) - 2);
  const height = Math.round((width * 3) / 4);
  const ratio = Math.min(window.devicePixelRatio || 1, 2);
  const saved = time;
  times.forEach((t, index) => {
    const canvas = el('canvas', { width: Math.round(width * ratio), height: Math.round(height * ratio) });
    canvas.style.aspectRatio = `${width} / ${height}`;
    const at = Math.min(Math.max(t, 0), duration);
    dom.sheetGrid.append(el('figure', { className: 'sheet-cell', dataset: { time: String(at) } }, canvas, el('figcaption', { textContent: sheetLabel(at, index) })));
    time = at;
    applyTime();
    view.renderInto(canvas.getContext('2d'), width, height);
  });
  time = saved;
  applyTime();
  setState('rendered');
}

// ---- start --------------------------------------------------------------------------------------

async function start() {
  document.body.dataset.state = 'loading';
  delete document.body.dataset.error;
  injectStyle();
  dom = buildDom();
  setState('loading');
  try {
    try {
      view = new SceneView(dom.canvas);
    } catch (error) {
      throw new LoadError(`WebGL is not available in this browser (${error.message})`);
    }
    layout();
    const data = await loadData(queryParams());
    source = data.source;
    run = data.run;
    let gltf;
    try {
      gltf = await parseGlb(data.glb);
    } catch (error) {
      throw new LoadError(`the scene is not a valid glTF binary: ${error.message}`);
    }
    view.setModel(gltf);
    fillRun();

    const runDuration = run ? number(run.duration) : null;
    const actionEnd = actions.reduce((m, a) => (a.end !== null ? Math.max(m, a.end) : m), 0);
    duration = Math.max(view.clipDuration, runDuration || 0, view.action ? 0 : actionEnd);
    dom.scrubber.max = String(duration);
    const timeline = duration > 0;
    dom.play.disabled = !timeline;
    dom.speed.disabled = !timeline;
    dom.scrubber.disabled = !timeline;
    const available = { collision: view.hasCollisionGroups, paths: Boolean(view.toolPaths), tree: Boolean(view.tree), axes: view.entities.length > 0 };
    for (const name of TOGGLES) {
      dom.toggleInputs[name].disabled = !available[name];
      if (!available[name]) dom.toggleInputs[name].checked = false;
      dom.toggleInputs[name].parentElement.classList.toggle('unavailable', !available[name]);
    }
    dom.root.classList.remove('loading');

    time = 0;
    currentAction = undefined;
    applyTime();
    applyHash(true);
    window.addEventListener('resize', layout);
    window.addEventListener('hashchange', () => {
      hash = hashParams();
      if (!hash.sheet) applyHash(false);
    });
    requestAnimationFrame(tick);
    if (hash.sheet) {
      setState('ready');
      renderSheet();
    } else {
      renderNow();
      setState('ready');
      if (hash.play) play();
    }
    resolveReady(window.lang2manipViewer);
  } catch (error) {
    fail(error);
  }
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start, { once: true });
else start();
