// Where a run's data comes from, in this order:
//   (a) inline in the page: <script type="application/json" id="lang2manip-run"> and
//       <script type="text/plain" id="lang2manip-glb"> (base64 GLB);
//   (b) ?run=URL&glb=URL, fetched;
//   (c) ?session=ID: the GLB at /api/sessions/ID/scene.glb, no run document (scene only).
// With ?token=TOKEN every fetch carries `Authorization: Bearer TOKEN`.

export const RUN_ELEMENT_ID = 'lang2manip-run';
export const GLB_ELEMENT_ID = 'lang2manip-glb';

export class LoadError extends Error {}

/** Bytes of a base64 text (whitespace allowed). */
export function base64ToBytes(text) {
  const clean = text.replace(/\s+/g, '');
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(clean);
  const binary = atob(clean);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

function parseRun(text, where) {
  let run;
  try {
    run = JSON.parse(text);
  } catch (error) {
    throw new LoadError(`the run document (${where}) is not JSON: ${error.message}`);
  }
  if (run === null || typeof run !== 'object' || Array.isArray(run)) throw new LoadError(`the run document (${where}) is not a JSON object`);
  if (run.format_version !== undefined && run.format_version !== 1) {
    console.warn(`lang2manip viewer: run document format_version ${run.format_version}, this viewer reads 1`);
  }
  return run;
}

async function fetchOrFail(url, token, what) {
  const headers = token ? { Authorization: `Bearer ${token}` } : {};
  let response;
  try {
    response = await fetch(url, { headers, credentials: 'same-origin' });
  } catch (error) {
    throw new LoadError(`could not fetch the ${what} from ${url}: ${error.message}`);
  }
  if (!response.ok) throw new LoadError(`could not fetch the ${what} from ${url}: HTTP ${response.status} ${response.statusText}`.trim());
  return response;
}

/** The GLB of /api/scene.glb, or null when this server has none (404). */
async function serverScene(token) {
  const headers = token ? { Authorization: `Bearer ${token}` } : {};
  let response;
  try {
    response = await fetch('/api/scene.glb', { headers, credentials: 'same-origin' });
  } catch (error) {
    return null;
  }
  if (response.status === 404) return null;
  if (!response.ok) throw new LoadError(`could not fetch the scene (GLB) from /api/scene.glb: HTTP ${response.status} ${response.statusText}`.trim());
  return response.arrayBuffer();
}

/**
 * The run document (or null) and the GLB bytes (ArrayBuffer) of this page.
 * `source` says which: "inline", "url", "session", or "server" (the page served with nothing
 * named: the server's default problem).
 */
export async function loadData(query, doc = document) {
  const runElement = doc.getElementById(RUN_ELEMENT_ID);
  const glbElement = doc.getElementById(GLB_ELEMENT_ID);
  if (runElement || glbElement) {
    const run = runElement && runElement.textContent.trim() ? parseRun(runElement.textContent, 'inline') : null;
    if (!glbElement || !glbElement.textContent.trim()) throw new LoadError(`the page has no scene: its script element #${GLB_ELEMENT_ID} is missing or empty`);
    let bytes;
    try {
      bytes = base64ToBytes(glbElement.textContent);
    } catch (error) {
      throw new LoadError(`the inline scene is not base64: ${error.message}`);
    }
    return { source: 'inline', run, glb: bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength) };
  }
  if (query.glb || query.run) {
    if (!query.glb) throw new LoadError('?run= was given without ?glb=: there is no scene to show');
    const [run, glb] = await Promise.all([
      query.run ? fetchOrFail(query.run, query.token, 'run document').then((r) => r.text()).then((text) => parseRun(text, query.run)) : null,
      fetchOrFail(query.glb, query.token, 'scene (GLB)').then((r) => r.arrayBuffer()),
    ]);
    return { source: 'url', run, glb };
  }
  if (query.session) {
    const url = `/api/sessions/${encodeURIComponent(query.session)}/scene.glb`;
    const glb = await fetchOrFail(url, query.token, 'scene (GLB)').then((r) => r.arrayBuffer());
    return { source: 'session', run: null, glb };
  }
  if (doc.location && /^https?:$/.test(doc.location.protocol)) {
    // Served by `lang2manip serve` with nothing named: the server's own problem (another server
    // has no /api/scene.glb: then there is nothing to show).
    const served = await serverScene(query.token);
    if (served) return { source: 'server', run: null, glb: served };
  }
  throw new LoadError(
    `nothing to show: the page has no inline run (script elements #${RUN_ELEMENT_ID}, #${GLB_ELEMENT_ID}) ` +
      'and no ?glb=URL[&run=URL] or ?session=ID in its address',
  );
}

/** Names of the objects a run document's actions move or aim at (their object, and the target of their params). */
export function touchedObjects(run) {
  const names = new Set();
  const actions = run && Array.isArray(run.actions) ? run.actions : [];
  for (const action of actions) if (action && typeof action.object === 'string') names.add(action.object);
  const reported = run && run.report && Array.isArray(run.report.actions) ? run.report.actions : [];
  for (const entry of reported) {
    const params = entry && entry.action && entry.action.params;
    if (params && typeof params.target === 'string') names.add(params.target);
  }
  return names;
}
