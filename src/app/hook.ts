/**
 * `window.drape`: a small, read-mostly hook for browser tests (documented in docs/app.md). Installed by the dev
 * server, and in a production build only when the page's query has `?testhook` (main.ts): a link cannot call it —
 * the site's Content-Security-Policy lets only the site's own scripts run — and nothing in it runs code or reaches
 * outside the page. Queries return plain JSON values. What it can change: stepping (`step`, for tests that must
 * not depend on the machine's speed), `import` (the same path as the panel's import button), and three test-only
 * faults, `loseDevice`, `gpuError` and `poison`.
 */
import { Vector3 } from 'three/webgpu';
import { clothEntries, clothName, sceneDocument } from '../core/index.js';
import type { App } from './app.js';

export interface DrapeHook {
  /** true once the first frame has been drawn */
  readonly ready: boolean;
  /** ms from navigation start to the first drawn frame */
  readonly firstFrameMs: number;
  backend(): 'webgpu' | 'webgl2';
  /** where the simulation runs: 'gpu' (WebGPU compute on the renderer's device) or 'cpu' (worker) */
  simBackend(): 'gpu' | 'cpu';
  /** true once every GPU cloth is compiled and drawn from the solver's buffers (always true on the CPU) */
  gpuDrawing(): boolean;
  /** tests: destroys the renderer's WebGPU device, as a GPU reset would (false when there is none) */
  loseDevice(): boolean;
  /** tests: the GPU simulation reports `message` as its error (as a solver that cannot be made would); false when it is not on the GPU */
  gpuError(message: string): boolean;
  /** tests: makes one particle's position NaN in the simulation (worker or GPU), as a blown-up solve would */
  poison(slot?: number): void;
  /** frame at which a slot's cloth became unstable (non-finite) and was stopped; -1 while it is fine */
  unstableAt(slot?: number): number;
  sceneName(): string;
  /** the current scene document (a copy; a scene of several cloths as its list `cloths`, as a file holds it) */
  scene(): unknown;
  /** which cloth the panel's Cloth & material and Pins folders edit (an index into the scene's cloths) */
  editedCloth(): number;
  /**
   * the cloths of a slot as drawn: each one's name, its first particle (the slot's numbering) and particles, the
   * look its shaded view draws it with, and the triangles it draws
   */
  cloths(slot?: number): { name: string; first: number; particles: number; look: string; triangles: number }[];
  view(): string;
  paused(): boolean;
  pinTool(): boolean;
  /** number of cloths on screen (7 for the Mesh Resolution scene side by side) */
  slots(): number;
  /** frames stepped since the cloth of a slot (re)started */
  frame(slot?: number): number;
  particleCount(slot?: number): number;
  /** [x, y, z] of the given particles (all when omitted) */
  positions(indices?: number[], slot?: number): number[][];
  /** mean position of a slot's particles */
  centroid(slot?: number): number[];
  /** indices of pinned particles */
  pinned(slot?: number): number[];
  /** grabbed particle or -1 */
  grabbed(slot?: number): number;
  /** where a particle is on screen, in CSS pixels of the page */
  screenOf(particle: number, slot?: number): { x: number; y: number };
  /** camera position */
  camera(): number[];
  /** the collider meshes the stage draws, by type (the floor is the stage's own) */
  colliders(): string[];
  /** where each drawn collider mesh is now: position and quaternion (x, y, z, w), in the order of colliders() */
  colliderPoses(): { position: number[]; quaternion: number[] }[];
  /** the drawn ground's height at the origin [m]: the first floor's, moved with it */
  groundHeight(): number;
  /** the scene's mannequin's pose and animation, or null when it has none */
  mannequin(): { pose?: string; animation?: string } | null;
  /** the text of the last message shown in the page, and its kind */
  lastMessage(): { text: string; kind: string };
  /** text of the floating labels (Mesh Resolution scene) */
  labels(): string[];
  stats(): { fps: number; stepMs: number; realTime: number; framesDone: number; clamps: string[] };
  /** the particles the contact view marked at its last frame, over all slots (0 in the other views) */
  contacts(): number;
  /** steps n frames now (whether paused or not) and resolves when they are drawn into the mirrors */
  step(frames?: number): Promise<void>;
  /** imports a scene document as the panel does; false (and a message) when refused */
  import(text: string): boolean;
}

/** Installs `window.drape`, reading and driving `app`, and returns it. */
export function installHook(app: App): DrapeHook {
  const mirror = (slot = 0) => {
    const m = app.sim.mirrors[slot];
    if (!m) throw new RangeError(`no slot ${slot}`);
    return m;
  };
  const hook: DrapeHook = {
    get ready() { return app.loop.firstFrameAt > 0; },
    get firstFrameMs() { return app.loop.firstFrameAt; },
    backend: () => app.stage.backend,
    simBackend: () => app.sim.kind,
    gpuDrawing: () => app.sim.kind === 'cpu' || (app.views.length > 0 && app.views.every((v) => v.attached)),
    loseDevice: () => {
      const d = app.stage.device;
      if (!d) return false;
      d.destroy();
      return true;
    },
    gpuError: (message) => {
      if (app.sim.kind !== 'gpu' || !app.sim.onError) return false;
      app.sim.onError(String(message).slice(0, 200));
      return true;
    },
    poison: (slot = 0) => { mirror(slot); app.sim.poison(slot); },
    unstableAt: (slot) => mirror(slot).unstableAt,
    sceneName: () => app.scene.name,
    scene: () => structuredClone(sceneDocument(app.scene)),
    editedCloth: () => app.cloth,
    cloths: (slot = 0) => {
      const { sim } = mirror(slot), starts = sim.model.clothStarts;
      const drawn = app.views[slot]?.drawnCloths ?? [];
      return clothEntries(sim.scene).map((e, c) => ({
        name: clothName(e, c), first: starts[c], particles: starts[c + 1] - starts[c],
        look: drawn[c]?.look ?? '', triangles: drawn[c]?.triangles ?? 0,
      }));
    },
    view: () => app.view,
    contacts: () => app.views.reduce((n, v) => n + v.contacts, 0),
    paused: () => app.sim.paused,
    pinTool: () => app.pinTool,
    slots: () => app.sim.mirrors.length,
    frame: (slot) => mirror(slot).frame,
    particleCount: (slot) => mirror(slot).sim.model.particleCount,
    positions: (indices, slot) => {
      const x = mirror(slot).sim.state.positions;
      const ids = indices ?? Array.from({ length: x.length / 3 }, (_, i) => i);
      return ids.map((i) => [x[3 * i], x[3 * i + 1], x[3 * i + 2]]);
    },
    centroid: (slot) => {
      const x = mirror(slot).sim.state.positions;
      const c = [0, 0, 0];
      for (let i = 0; i < x.length; i += 3) { c[0] += x[i]; c[1] += x[i + 1]; c[2] += x[i + 2]; }
      return c.map((v) => (3 * v) / x.length);
    },
    pinned: (slot) => {
      const p = mirror(slot).sim.state.pinned;
      const out: number[] = [];
      for (let i = 0; i < p.length; i++) if (p[i]) out.push(i);
      return out;
    },
    grabbed: (slot) => mirror(slot).grabbed,
    screenOf: (particle, slot) => {
      const x = mirror(slot).sim.state.positions;
      const v = new Vector3(x[3 * particle], x[3 * particle + 1], x[3 * particle + 2]).project(app.stage.camera);
      const r = app.stage.container.getBoundingClientRect();
      return { x: r.left + ((v.x + 1) / 2) * r.width, y: r.top + ((1 - v.y) / 2) * r.height };
    },
    camera: () => app.stage.camera.position.toArray(),
    colliders: () => app.stage.colliderNames(),
    colliderPoses: () => app.stage.colliderPoses(),
    groundHeight: () => app.stage.groundHeight(),
    mannequin: () => (app.mannequin ? { ...app.mannequin.options } : null),
    lastMessage: () => ({ text: app.overlay.lastMessage, kind: app.overlay.lastMessageKind }),
    labels: () => [...app.overlay.labelLayer.querySelectorAll('.drape-label')].map((l) => (l as HTMLElement).innerText.replace(/\s+/g, ' ').trim()),
    stats: () => ({
      fps: app.loop.fps, stepMs: app.sim.stats.stepMs, realTime: app.sim.stats.realTime,
      framesDone: app.sim.stats.framesDone, clamps: [...app.sim.stats.clamps],
    }),
    step: (frames = 1) => app.sim.step(frames),
    import: (text) => app.fileImport.importText(text, 'hook'),
  };
  (window as unknown as { drape: DrapeHook }).drape = hook;
  return hook;
}
