// Page parameters: the query string says where the data is, the hash how to show it.

/** Query parameters: data sources and the access token. */
export function queryParams(search = window.location.search) {
  const q = new URLSearchParams(search);
  return {
    run: q.get('run') || null,
    glb: q.get('glb') || null,
    session: q.get('session') || null,
    token: q.get('token') || null,
  };
}

function number(text) {
  if (text === null || text === undefined || String(text).trim() === '') return null;
  const value = Number(text);
  return Number.isFinite(value) ? value : null;
}

/**
 * Hash parameters (`#t=3.5&ui=0&camera=30,25,2.5`, `#sheet=0,2,4&labels=a|b|c&cols=3`).
 * Unknown keys are ignored; malformed values fall back to the defaults.
 */
export function hashParams(hash = window.location.hash) {
  const h = new URLSearchParams(hash.replace(/^#/, ''));
  const result = { t: null, ui: true, camera: null, sheet: null, labels: null, cols: null, play: false, speed: null };
  result.t = number(h.get('t'));
  const ui = h.get('ui');
  if (ui !== null) result.ui = !(ui === '0' || ui === 'false' || ui === 'off');
  const play = h.get('play');
  if (play !== null) result.play = play === '1' || play === 'true';
  result.speed = number(h.get('speed'));
  const camera = h.get('camera');
  if (camera) {
    const [azimuth, elevation, distance] = camera.split(',').map(number);
    if (azimuth !== null && elevation !== null) result.camera = { azimuth, elevation, distance: distance > 0 ? distance : null };
  }
  const sheet = h.get('sheet');
  if (sheet) {
    const times = sheet.split(',').map(number).filter((t) => t !== null);
    if (times.length) result.sheet = times;
  }
  const labels = h.get('labels');
  if (labels !== null) result.labels = labels.split('|');
  const cols = number(h.get('cols'));
  if (cols !== null && cols >= 1) result.cols = Math.floor(cols);
  return result;
}
