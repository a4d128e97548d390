// Writes a small run following the viewer's data contract, to test the viewer without the C++ side:
//   OUT/sample.glb        glTF 2.0 binary: a z-up world under a root turned y-up; a two-link "arm"
//                         (arm/base, arm/link1) and two objects (table, marker), each with `visual`
//                         and `collision` groups; tool_paths/tool_path/0 and /1 (LINE_STRIP); an
//                         exploration_tree (LINES); the animation `trajectory` (6 s: the arm turns,
//                         picks the marker, carries it over and puts it down).
//   OUT/sample-run.json   the run document.
//   OUT/sample-run.html   self-contained page: inline run document, base64 GLB, inlined viewer.js.
//   OUT/sessions/sample.glb   the same GLB, served by serve.mjs at /api/sessions/sample/scene.glb.
//   OUT/index.html, OUT/viewer.js   copies of the build, so OUT can be served as it is
//                         (index.html?run=sample-run.json&glb=sample.glb).
// Usage: node test/make-sample.mjs [--out DIR] [--viewer DIR_WITH_VIEWER_JS]
import { copyFile, mkdir, readFile, writeFile } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const viewerDir = dirname(dirname(fileURLToPath(import.meta.url)));

function option(name, fallback) {
  const i = process.argv.indexOf(name);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}

// ---- a minimal GLB writer ----------------------------------------------------------------------

const FLOAT = 5126;
const UNSIGNED_SHORT = 5123;
const ARRAY_BUFFER = 34962;
const ELEMENT_ARRAY_BUFFER = 34963;

class Glb {
  constructor() {
    this.json = { asset: { version: '2.0', generator: 'lang2manip viewer make-sample' }, scene: 0, scenes: [{ nodes: [] }], nodes: [], meshes: [], materials: [], accessors: [], bufferViews: [], animations: [] };
    this.chunks = [];
    this.length = 0;
  }

  view(typed, target) {
    const bytes = Buffer.from(typed.buffer, typed.byteOffset, typed.byteLength);
    const view = { buffer: 0, byteOffset: this.length, byteLength: bytes.length };
    if (target) view.target = target;
    this.chunks.push(bytes);
    this.length += bytes.length;
    const pad = (4 - (this.length % 4)) % 4;
    if (pad) {
      this.chunks.push(Buffer.alloc(pad));
      this.length += pad;
    }
    this.json.bufferViews.push(view);
    return this.json.bufferViews.length - 1;
  }

  accessor(values, type, { target, indices = false, bounds = false } = {}) {
    const size = { SCALAR: 1, VEC3: 3, VEC4: 4 }[type];
    const typed = indices ? new Uint16Array(values) : new Float32Array(values);
    const accessor = { bufferView: this.view(typed, target), componentType: indices ? UNSIGNED_SHORT : FLOAT, count: values.length / size, type };
    if (bounds) {
      accessor.min = [];
      accessor.max = [];
      for (let k = 0; k < size; k++) {
        let low = Infinity;
        let high = -Infinity;
        for (let i = k; i < typed.length; i += size) {
          low = Math.min(low, typed[i]);
          high = Math.max(high, typed[i]);
        }
        accessor.min.push(low);
        accessor.max.push(high);
      }
    }
    this.json.accessors.push(accessor);
    return this.json.accessors.length - 1;
  }

  material(rgba) {
    const material = { pbrMetallicRoughness: { baseColorFactor: rgba, metallicFactor: 0, roughnessFactor: 0.8 }, doubleSided: true };
    if (rgba[3] < 1) material.alphaMode = 'BLEND';
    this.json.materials.push(material);
    return this.json.materials.length - 1;
  }

  /** A triangle mesh ({positions, normals?, indices}) or lines ({positions, mode: 1 | 3}). */
  mesh({ positions, normals, indices, mode = 4 }, material) {
    const attributes = { POSITION: this.accessor(positions, 'VEC3', { target: ARRAY_BUFFER, bounds: true }) };
    if (normals) attributes.NORMAL = this.accessor(normals, 'VEC3', { target: ARRAY_BUFFER });
    const primitive = { attributes, mode, material };
    if (indices) primitive.indices = this.accessor(indices, 'SCALAR', { target: ELEMENT_ARRAY_BUFFER, indices: true });
    this.json.meshes.push({ primitives: [primitive] });
    return this.json.meshes.length - 1;
  }

  node(node) {
    this.json.nodes.push(node);
    return this.json.nodes.length - 1;
  }

  bytes() {
    let text = JSON.stringify(this.json);
    while (text.length % 4) text += ' ';
    const json = Buffer.from(text, 'utf8');
    const bin = Buffer.concat(this.chunks);
    const header = Buffer.alloc(12);
    header.writeUInt32LE(0x46546c67, 0); // "glTF"
    header.writeUInt32LE(2, 4);
    header.writeUInt32LE(12 + 8 + json.length + 8 + bin.length, 8);
    const chunk = (type, data) => {
      const head = Buffer.alloc(8);
      head.writeUInt32LE(data.length, 0);
      head.writeUInt32LE(type, 4);
      return Buffer.concat([head, data]);
    };
    return Buffer.concat([header, chunk(0x4e4f534a, json), chunk(0x004e4942, bin)]);
  }

  finish() {
    this.json.buffers = [{ byteLength: this.length }];
    return this.bytes();
  }
}

// ---- shapes (z-up world, metres) ---------------------------------------------------------------

function box([sx, sy, sz], withNormals = true) {
  const positions = [];
  const normals = [];
  const indices = [];
  const h = [sx / 2, sy / 2, sz / 2];
  for (let axis = 0; axis < 3; axis++) {
    for (const sign of [1, -1]) {
      const u = (axis + 1) % 3;
      const v = (axis + 2) % 3;
      const base = positions.length / 3;
      for (const [a, b] of [
        [-1, -1],
        [1, -1],
        [1, 1],
        [-1, 1],
      ]) {
        const p = [0, 0, 0];
        p[axis] = sign * h[axis];
        p[u] = a * h[u];
        p[v] = b * h[v] * sign;
        positions.push(...p);
        const n = [0, 0, 0];
        n[axis] = sign;
        normals.push(...n);
      }
      indices.push(base, base + 1, base + 2, base, base + 2, base + 3);
    }
  }
  return withNormals ? { positions, normals, indices } : { positions, indices };
}

function cylinder(radius, length, segments = 20) {
  const positions = [];
  const normals = [];
  const indices = [];
  const z = length / 2;
  for (let i = 0; i <= segments; i++) {
    const a = (2 * Math.PI * i) / segments;
    const [c, s] = [Math.cos(a), Math.sin(a)];
    positions.push(radius * c, radius * s, -z, radius * c, radius * s, z);
    normals.push(c, s, 0, c, s, 0);
  }
  for (let i = 0; i < segments; i++) {
    const k = 2 * i;
    indices.push(k, k + 2, k + 3, k, k + 3, k + 1);
  }
  for (const sign of [-1, 1]) {
    const centre = positions.length / 3;
    positions.push(0, 0, sign * z);
    normals.push(0, 0, sign);
    for (let i = 0; i <= segments; i++) {
      const a = (2 * Math.PI * i) / segments;
      positions.push(radius * Math.cos(a), radius * Math.sin(a), sign * z);
      normals.push(0, 0, sign);
    }
    for (let i = 0; i < segments; i++) indices.push(centre, centre + 1 + (sign > 0 ? i : i + 1), centre + 1 + (sign > 0 ? i + 1 : i));
  }
  return { positions, normals, indices };
}

function quatZ(angle) {
  return [0, 0, Math.sin(angle / 2), Math.cos(angle / 2)];
}

// ---- the sample run ----------------------------------------------------------------------------

const DURATION = 6;
const ARM_Z = 0.62;
const REACH = Math.hypot(0.45, 0.2);
const START = (40 * Math.PI) / 180;
const PICK = Math.atan2(-0.2, 0.45);
const PLACE = Math.atan2(0.2, 0.45);
const TABLE_TOP = 0.4;
const MARKER_LENGTH = 0.12;

/** Arm angle at time t: turn to the marker (0-2 s), wait (2-3 s), carry it (3-5 s), wait. */
function armAngle(t) {
  const smooth = (x) => x * x * (3 - 2 * x);
  if (t <= 2) return START + (PICK - START) * smooth(t / 2);
  if (t <= 3) return PICK;
  if (t <= 5) return PICK + (PLACE - PICK) * smooth((t - 3) / 2);
  return PLACE;
}

/** Marker centre at time t: lifted at 2-3 s, carried 3-5 s, put down 5-6 s. */
function markerPosition(t) {
  const down = TABLE_TOP + MARKER_LENGTH / 2;
  const up = down + 0.08;
  if (t <= 2) return [0.45, -0.2, down];
  if (t <= 3) return [0.45, -0.2, down + (up - down) * (t - 2)];
  const a = armAngle(t);
  if (t <= 5) return [REACH * Math.cos(a), REACH * Math.sin(a), up];
  return [0.45, 0.2, up + (down - up) * Math.min(1, t - 5)];
}

export function makeSampleGlb() {
  const glb = new Glb();
  const grey = glb.material([0.62, 0.65, 0.7, 1]);
  const orange = glb.material([0.95, 0.55, 0.1, 0.55]);
  const wood = glb.material([0.72, 0.55, 0.38, 1]);
  const blue = glb.material([0.2, 0.42, 0.85, 1]);
  const red = glb.material([0.85, 0.15, 0.15, 1]);
  const pathMaterial = glb.material([1, 0, 0, 1]);
  const treeMaterial = glb.material([0, 0.7, 0.2, 1]);
  const rootChildren = [];

  /** An entity node with `visual` and `collision` groups, each holding one shape node. */
  const entity = (name, kind, translation, rotation, visualMesh, collisionMesh, shapeOffset = [0, 0, 0]) => {
    const visualShape = glb.node({ name: `${name} visual shape`, mesh: visualMesh, translation: shapeOffset });
    const collisionShape = glb.node({ name: `${name} collision shape`, mesh: collisionMesh, translation: shapeOffset });
    const visual = glb.node({ name: 'visual', children: [visualShape] });
    const collision = glb.node({ name: 'collision', children: [collisionShape] });
    const node = glb.node({ name, translation, rotation, extras: { kind }, children: [visual, collision] });
    rootChildren.push(node);
    return node;
  };

  // The table has no normals, as the C++ writer's meshes (GLTFLoader then shades it flat).
  entity('table', 'object', [0.45, 0, TABLE_TOP - 0.02], [0, 0, 0, 1], glb.mesh(box([0.9, 0.9, 0.04], false), wood), glb.mesh(box([0.92, 0.92, 0.06]), orange));
  entity('arm/base', 'link', [0, 0, ARM_Z / 2], [0, 0, 0, 1], glb.mesh(box([0.12, 0.12, ARM_Z]), grey), glb.mesh(box([0.14, 0.14, ARM_Z + 0.02]), orange));
  const link1 = entity('arm/link1', 'link', [0, 0, ARM_Z + 0.03], quatZ(START), glb.mesh(box([REACH + 0.04, 0.05, 0.05]), blue), glb.mesh(box([REACH + 0.08, 0.08, 0.08]), orange), [REACH / 2, 0, 0]);
  const marker = entity('marker', 'object', markerPosition(0), [0, 0, 0, 1], glb.mesh(cylinder(0.015, MARKER_LENGTH), red), glb.mesh(cylinder(0.025, MARKER_LENGTH + 0.02), orange));

  // Tool paths: the tip of link1 during each action.
  const tip = (t) => {
    const a = armAngle(t);
    return [REACH * Math.cos(a), REACH * Math.sin(a), ARM_Z + 0.03];
  };
  const paths = [];
  for (const [index, from, to] of [
    [0, 0, 3],
    [1, 3, 6],
  ]) {
    const positions = [];
    for (let i = 0; i <= 30; i++) positions.push(...tip(from + ((to - from) * i) / 30));
    paths.push(glb.node({ name: `tool_path/${index}`, mesh: glb.mesh({ positions, mode: 3 }, pathMaterial) }));
  }
  rootChildren.push(glb.node({ name: 'tool_paths', children: paths }));

  // An exploration tree: a few random-looking segments around the workspace.
  const tree = [];
  let seed = 7;
  const random = () => ((seed = (seed * 16807) % 2147483647) / 2147483647) * 2 - 1;
  const nodes = [[0.3, 0, 0.7]];
  for (let i = 0; i < 40; i++) {
    const parent = nodes[Math.floor(((random() + 1) / 2) * nodes.length) % nodes.length];
    const child = [parent[0] + random() * 0.12, parent[1] + random() * 0.12, Math.max(0.45, parent[2] + random() * 0.08)];
    nodes.push(child);
    tree.push(...parent, ...child);
  }
  rootChildren.push(glb.node({ name: 'exploration_tree', mesh: glb.mesh({ positions: tree, mode: 1 }, treeMaterial) }));

  const root = glb.node({ name: 'world (z up)', rotation: [-Math.SQRT1_2, 0, 0, Math.SQRT1_2], children: rootChildren });
  glb.json.scenes[0].nodes.push(root);

  // The animation `trajectory`, sampled every 0.1 s.
  const times = [];
  const rotations = [];
  const translations = [];
  for (let i = 0; i <= DURATION * 10; i++) {
    const t = i / 10;
    times.push(t);
    rotations.push(...quatZ(armAngle(t)));
    translations.push(...markerPosition(t));
  }
  const input = glb.accessor(times, 'SCALAR', { bounds: true });
  glb.json.animations.push({
    name: 'trajectory',
    samplers: [
      { input, output: glb.accessor(rotations, 'VEC4'), interpolation: 'LINEAR' },
      { input, output: glb.accessor(translations, 'VEC3'), interpolation: 'LINEAR' },
    ],
    channels: [
      { sampler: 0, target: { node: link1, path: 'rotation' } },
      { sampler: 1, target: { node: marker, path: 'translation' } },
    ],
  });
  return glb.finish();
}

export const SAMPLE_RUN = {
  format_version: 1,
  task: 'Pick up the marker and put it on the left side of the table',
  success: true,
  duration: DURATION,
  robot: 'arm',
  actions: [
    { index: 0, kind: 'pick', object: 'marker', status: 'succeeded', start_time: 0.0, end_time: 3.0, text: 'pick marker (top grasp)' },
    { index: 1, kind: 'place', object: 'marker', status: 'succeeded', start_time: 3.0, end_time: 6.0, text: 'place marker at (0.45, 0.20) on table' },
  ],
  observation: 'Objects on the table: marker at (0.45, -0.20, 0.46).\nThe <b>marker</b> is upright; this text must show as text, never as HTML. </script> too.',
  prompt: 'You control a robot arm. Instruction: pick up the marker and put it on the left side of the table.',
  report: { planner: 'sample', planning_time: 0.12, actions: 2 },
};

/** A JSON text safe inside a <script> element. */
export function scriptJson(value) {
  return JSON.stringify(value).replace(/</g, '\\u003c');
}

/** The self-contained page: inline run document, base64 GLB, inlined viewer. */
export function selfContainedPage(run, glbBytes, viewerJs) {
  if (/<\/script/i.test(viewerJs)) throw new Error('viewer.js contains </script: it cannot be inlined');
  return `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>lang2manip run: ${run.task.replace(/[<>&"]/g, (c) => `&#${c.charCodeAt(0)};`)}</title>
<link rel="icon" href="data:,">
</head>
<body>
<script type="application/json" id="lang2manip-run">${scriptJson(run)}</script>
<script type="text/plain" id="lang2manip-glb">${Buffer.from(glbBytes).toString('base64')}</script>
<script>${viewerJs}</script>
</body>
</html>
`;
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const out = resolve(option('--out', join(viewerDir, 'test', 'out')));
  const dist = resolve(option('--viewer', resolve(viewerDir, process.env.VIEWER_OUT_DIR || 'dist')));
  let viewerJs;
  try {
    viewerJs = await readFile(join(dist, 'viewer.js'), 'utf8');
  } catch {
    console.error(`make-sample: ${join(dist, 'viewer.js')} is missing: run "npm run build" first`);
    process.exit(1);
  }
  await mkdir(out, { recursive: true });
  const glb = makeSampleGlb();
  await writeFile(join(out, 'sample.glb'), glb);
  await mkdir(join(out, 'sessions'), { recursive: true });
  await writeFile(join(out, 'sessions', 'sample.glb'), glb);
  await writeFile(join(out, 'sample-run.json'), JSON.stringify(SAMPLE_RUN, null, 2));
  await writeFile(join(out, 'sample-run.html'), selfContainedPage(SAMPLE_RUN, glb, viewerJs));
  await copyFile(join(dist, 'viewer.js'), join(out, 'viewer.js'));
  await copyFile(join(dist, 'index.html'), join(out, 'index.html'));
  console.log(`make-sample: wrote ${out}/{sample.glb (${glb.length} bytes), sample-run.json, sample-run.html, index.html, viewer.js}`);
}
