// The 3D side: renderer, camera and controls, lights and ground grid, the run's glTF scene and its
// trajectory animation, and the visibility toggles.
import {
  AnimationMixer,
  AxesHelper,
  Box3,
  Color,
  DirectionalLight,
  GridHelper,
  Group,
  HemisphereLight,
  LineBasicMaterial,
  LoopOnce,
  MathUtils,
  Object3D,
  PerspectiveCamera,
  Scene,
  Vector3,
  WebGLRenderer,
} from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export const BACKGROUND = 0xeef1f5;
export const TOOL_PATH_COLOR = 0xe0302b;
export const TREE_COLOR = 0x2e9e44;
/** Default camera: a 3/4 view from the front-right (+x, -y in the z-up world), above. */
export const DEFAULT_VIEW = { azimuth: -40, elevation: 28, distance: null };
const FOV = 40;

/** The glTF name a node was given (GLTFLoader sanitizes `name`; the original is kept here). */
function gltfName(object) {
  return object.userData && typeof object.userData.name === 'string' ? object.userData.name : object.name;
}

/** A world (z-up) direction as three.js (y-up) coordinates: (x, y, z) -> (x, z, -y). */
function fromWorld(x, y, z) {
  return new Vector3(x, z, -y);
}

/** Promise form of GLTFLoader.parse. */
export function parseGlb(buffer) {
  return new Promise((resolve, reject) => {
    new GLTFLoader().parse(buffer, '', resolve, (error) => reject(error instanceof Error ? error : new Error(String(error))));
  });
}

export class SceneView {
  constructor(canvas) {
    this.canvas = canvas;
    this.renderer = new WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true, alpha: false });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(BACKGROUND, 1);
    this.scene = new Scene();
    this.scene.background = new Color(BACKGROUND);
    this.camera = new PerspectiveCamera(FOV, 1, 0.01, 100);
    this.scene.add(this.camera);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = false;
    this.controls.screenSpacePanning = true;
    this.needsRender = true;
    this.controls.addEventListener('change', () => {
      this.needsRender = true;
    });

    // Lights: sky/ground fill, a fixed key light from above, a head light following the camera.
    this.scene.add(new HemisphereLight(0xffffff, 0x7d8590, 1.6));
    const key = new DirectionalLight(0xffffff, 1.6);
    key.position.copy(fromWorld(1.5, -2.0, 4.0));
    this.scene.add(key);
    const head = new DirectionalLight(0xffffff, 1.1);
    const headTarget = new Object3D();
    head.position.set(0.3, 0.6, 0);
    headTarget.position.set(0, 0, -1);
    head.target = headTarget;
    this.camera.add(head, headTarget);

    this.grid = new Group();
    this.scene.add(this.grid);

    this.model = null;
    this.mixer = null;
    this.action = null;
    this.clipDuration = 0;
    this.entities = [];
    this.toolPaths = null;
    this.toolPathByAction = new Map();
    this.tree = null;
    this.axes = [];
    this.center = new Vector3();
    this.radius = 1;
    this.view = { ...DEFAULT_VIEW };
    this.viewport = { width: 1, height: 1, offset: 0 };
    /** Names of the objects the camera frames with the robots (see frame()). */
    this.focus = null;
  }

  /** Add a loaded glTF (from parseGlb): classify its nodes, set up the animation, frame it. */
  setModel(gltf) {
    const root = gltf.scene;
    this.model = root;
    this.scene.add(root);

    root.traverse((object) => {
      const kind = object.userData && object.userData.kind;
      const name = gltfName(object);
      if (kind === 'link' || kind === 'object') this.entities.push(object);
      if (name === 'tool_paths' && !this.toolPaths) this.toolPaths = object;
      if (name === 'exploration_tree' && !this.tree) this.tree = object;
    });
    // Scenes written before the visual/collision groups and extras: every top-level node of the
    // world root is a link or object.
    if (this.entities.length === 0) {
      const worldRoot = root.children.length === 1 ? root.children[0] : root;
      for (const child of worldRoot.children) if (child !== this.toolPaths && child !== this.tree) this.entities.push(child);
    }

    if (this.toolPaths) {
      this.toolPaths.traverse((object) => {
        if (!object.isLine) return;
        object.material = new LineBasicMaterial({ color: TOOL_PATH_COLOR, transparent: true, opacity: 1 });
        object.renderOrder = 2;
      });
      for (const child of this.toolPaths.children) {
        const match = /^tool_path\/(\d+)$/.exec(gltfName(child));
        if (match) this.toolPathByAction.set(Number(match[1]), child);
      }
    }
    if (this.tree) {
      this.tree.traverse((object) => {
        if (object.isLine) object.material = new LineBasicMaterial({ color: TREE_COLOR, transparent: true, opacity: 0.75 });
      });
    }

    const clip = gltf.animations.find((a) => a.name === 'trajectory') || (gltf.animations.length === 1 ? gltf.animations[0] : null);
    if (clip) {
      this.mixer = new AnimationMixer(root);
      this.action = this.mixer.clipAction(clip);
      this.action.setLoop(LoopOnce, 1);
      this.action.clampWhenFinished = true;
      this.action.paused = true; // time is set by setTime, never advanced by the mixer
      this.action.play();
      this.clipDuration = clip.duration;
    }

    this.setCollision(false);
    this.setTree(false);
    this.frame();

    const size = MathUtils.clamp(this.radius * 0.12, 0.03, 0.3);
    for (const entity of this.entities) {
      const axes = new AxesHelper(size);
      axes.material.depthTest = false;
      axes.material.transparent = true;
      axes.renderOrder = 3;
      axes.visible = false;
      axes.userData.helper = true;
      entity.add(axes);
      this.axes.push(axes);
    }
    this.needsRender = true;
  }

  get hasCollisionGroups() {
    return this.entities.some((e) => e.children.some((c) => gltfName(c) === 'collision'));
  }

  /**
   * Bounding box over the animation of the scene (tool paths included, exploration tree and
   * helpers not), or only of the top-level bodies `keep` accepts (tool paths always).
   */
  sceneBox(keep = null) {
    const box = new Box3();
    const part = new Box3();
    const times = this.action ? [0, this.clipDuration / 2, this.clipDuration] : [null];
    const skipped = new Set(keep ? this.entities.filter((entity) => !keep(entity)) : []);
    for (const t of times) {
      if (t !== null) this.setTime(t);
      this.model.updateMatrixWorld(true);
      const visit = (object) => {
        if (object === this.tree || object.userData.helper || skipped.has(object)) return;
        if (object.geometry && object.visible !== false) {
          if (!object.geometry.boundingBox) object.geometry.computeBoundingBox();
          part.copy(object.geometry.boundingBox).applyMatrix4(object.matrixWorld);
          if (!part.isEmpty()) box.union(part);
        }
        for (const child of object.children) if (child.visible !== false || child === this.toolPaths) visit(child);
      };
      visit(this.model);
    }
    if (this.action) this.setTime(0);
    return box;
  }

  /**
   * Fit the ground grid to the scene, and the camera to what matters: the robots and the objects
   * named in `focus` (the objects a task touches) with the tool paths; the whole scene when no
   * object is named or none of them is in it.
   */
  frame(focus = this.focus) {
    this.focus = focus;
    const whole = this.sceneBox();
    if (whole.isEmpty()) whole.set(new Vector3(-0.5, 0, -0.5), new Vector3(0.5, 1, 0.5));
    const named = focus && focus.size > 0 ? this.entities.filter((entity) => focus.has(gltfName(entity))) : [];
    const box =
      named.length > 0
        ? this.sceneBox((entity) => entity.userData.kind === 'link' || named.includes(entity))
        : whole.clone();
    if (box.isEmpty()) box.copy(whole);
    box.getCenter(this.center);
    this.radius = Math.max(0.1, box.getSize(new Vector3()).length() / 2);

    this.grid.clear();
    const reach = Math.max(Math.abs(whole.min.x), Math.abs(whole.max.x), Math.abs(whole.min.z), Math.abs(whole.max.z)) + this.radius;
    const size = Math.max(2, 2 * Math.ceil(reach));
    const minor = new GridHelper(size, Math.round(size * 10), 0xd3d8df, 0xd3d8df);
    const major = new GridHelper(size, size, 0x9aa3ae, 0xaab2bd);
    const floor = whole.min.y < -0.05 ? whole.min.y : 0;
    minor.position.y = floor;
    major.position.y = floor + 0.0005;
    this.grid.add(minor, major);

    this.setView(this.view);
  }

  /** Place the camera: azimuth from +x towards +y, elevation above the ground (degrees), distance (m, null: fit). */
  setView({ azimuth, elevation, distance }) {
    this.view = { azimuth, elevation, distance };
    const az = MathUtils.degToRad(azimuth);
    const el = MathUtils.degToRad(MathUtils.clamp(elevation, -89.9, 89.9));
    const d = distance || this.fitDistance();
    const direction = fromWorld(Math.cos(el) * Math.cos(az), Math.cos(el) * Math.sin(az), Math.sin(el));
    this.camera.position.copy(this.center).addScaledVector(direction, d);
    this.camera.near = Math.max(0.001, this.radius / 200);
    this.camera.far = d + this.radius * 50 + 20;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(this.center);
    this.controls.update();
    this.needsRender = true;
  }

  fitDistance() {
    const { width, height, offset } = this.viewport;
    const aspect = Math.max(0.1, (width - offset) / Math.max(1, height));
    const vertical = MathUtils.degToRad(FOV);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * aspect);
    return (this.radius / Math.sin(Math.min(vertical, horizontal) / 2)) * 1.02;
  }

  /**
   * Size the drawing buffer to the canvas's CSS size. `offset` pixels on the right are covered
   * (by the side panel): the view is shifted so the scene is centred in the uncovered part.
   */
  resize(width, height, offset = 0) {
    width = Math.max(1, Math.floor(width));
    height = Math.max(1, Math.floor(height));
    this.viewport = { width, height, offset };
    this.renderer.setSize(width, height, false);
    if (offset > 0 && width > 2 * offset) {
      this.camera.aspect = (width + offset) / height;
      this.camera.setViewOffset(width + offset, height, offset, 0, width, height);
    } else {
      this.camera.aspect = width / height;
      this.camera.clearViewOffset();
    }
    this.camera.updateProjectionMatrix();
    this.needsRender = true;
  }

  /** Pose the scene at time t (seconds) of the trajectory animation. */
  setTime(t) {
    if (!this.action) return;
    this.action.enabled = true;
    this.action.time = MathUtils.clamp(t, 0, this.clipDuration);
    this.mixer.update(0);
    this.needsRender = true;
  }

  /**
   * World (z-up) position of the origin of the node named `name` (its glTF name, e.g. a link
   * "panda/panda_hand") as the scene is posed now; null when no node has that name.
   */
  nodeWorldPosition(name) {
    let found = null;
    if (!this.model) return null;
    this.model.traverse((object) => {
      if (!found && gltfName(object) === name) found = object;
    });
    if (!found) return null;
    found.updateWorldMatrix(true, false);
    const p = new Vector3().setFromMatrixPosition(found.matrixWorld);
    return [p.x, -p.z, p.y];
  }

  /** Collision geometry instead of the visual one. */
  setCollision(on) {
    for (const entity of this.entities) {
      for (const child of entity.children) {
        const name = gltfName(child);
        if (name === 'visual') child.visible = !on;
        if (name === 'collision') child.visible = on;
      }
    }
    this.needsRender = true;
  }

  setPaths(on) {
    if (this.toolPaths) this.toolPaths.visible = on;
    this.needsRender = true;
  }

  setTree(on) {
    if (this.tree) this.tree.visible = on;
    this.needsRender = true;
  }

  setAxes(on) {
    for (const axes of this.axes) axes.visible = on;
    this.needsRender = true;
  }

  setGrid(on) {
    this.grid.visible = on;
    this.needsRender = true;
  }

  /** The tool path of the action playing drawn solid, the others faded (none playing: all solid). */
  highlightPath(actionIndex) {
    for (const [index, path] of this.toolPathByAction) {
      const solid = actionIndex === null || index === actionIndex;
      path.traverse((object) => {
        if (object.isLine) object.material.opacity = solid ? 1 : 0.3;
      });
    }
    this.needsRender = true;
  }

  render() {
    this.renderer.render(this.scene, this.camera);
    this.needsRender = false;
  }

  /** Draw the scene at `width` x `height` CSS pixels into a 2D context (for contact sheets). */
  renderInto(context, width, height) {
    const saved = { ...this.viewport };
    this.resize(width, height, 0);
    this.setView(this.view);
    this.render();
    context.drawImage(this.renderer.domElement, 0, 0, context.canvas.width, context.canvas.height);
    this.resize(saved.width, saved.height, saved.offset);
  }
}
