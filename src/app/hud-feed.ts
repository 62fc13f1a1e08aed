/** What the HUD shows: the app's and the simulation's state, gathered into the HUD's fields and notes. */
import { clothEntries, clothName, measureTest, plainText, type ClothSpec, type TestResult } from '../core/index.js';
import type { HudCloth, HudInfo } from '../ui/hud.js';
import { finite } from '../ui/dom.js';
import { SCENE_LABELS } from '../ui/menu-labels.js';
import type { App } from './app.js';
import { contactDistance } from './contact-meter.js';
import { slowCause } from './slow-cause.js';
import { fitSideBySide } from './limits.js';
import { linkCannotCarry } from './mesh-import.js';
import { clothMesh, meshNames } from './meshes.js';
import { SWEEP_STAGE_FRAMES, sweepIgnored, sweeps } from './sweep.js';

/**
 * The HUD's content now: sizes, backends (and why not the one asked for), solver and view, and the notes (unstable
 * cloths, a clamped resolution, a sweep the cloth's shape does not take, a thinned side-by-side sweep, mesh files
 * (the cloth's, mesh colliders') that a link cannot carry). `fps` and `idle` come from the frame loop.
 */
export function hudInfo(app: App, fps: number, idle: boolean): HudInfo {
  const { sim, scene } = app;
  let particles = 0, triangles = 0, springs = 0;
  for (const m of sim.mirrors) {
    particles += m.sim.model.particleCount;
    triangles += m.sim.model.triangles.length / 3;
    springs += m.sim.model.restLengths.length;
  }
  const sweep = app.sweep.list();
  const notes: string[] = [];
  sim.mirrors.forEach((m, k) => {
    if (m.unstableAt >= 0) notes.push(`${app.slots.clothName(k)}: unstable at frame ${m.unstableAt}, stopped — Reset (R) to start again`);
  });
  if (app.capNote) notes.push(app.capNote);
  const ignored = sweepIgnored(scene);
  if (ignored) notes.push(ignored);
  const files = meshNames(scene);
  if (files.length) notes.push(linkCannotCarry(files));
  if (sweeps(scene) && app.sweep.layout === 'side-by-side') {
    const fit = fitSideBySide(scene.resolutionSweep ?? [], sim.kind);
    if (fit.note) notes.push(fit.note);
  }
  // the standard fabric test the scene is, measured on the first cloth as the page has it now
  const first = sim.mirrors[0];
  // a scene of several cloths (one slot: a sweep is of one cloth): each one's particles, by its name
  const entries = clothEntries(scene);
  const starts = first?.sim.model.clothStarts;
  const cloths: HudCloth[] | undefined = entries.length > 1 && starts?.length === entries.length + 1
    ? entries.map((e, k) => ({ name: plainText(clothName(e, k), 40), shape: shapeWords(e.cloth), particles: starts[k + 1] - starts[k] }))
    : undefined;
  const slow = !sim.paused && sim.stats.measured && sim.stats.realTime < 0.9 ? slowCause(sim.stats.realTime, sim.stats.stepMs, fps) : null;
  const measured = scene.test && first && first.unstableAt < 0 ? measureTest(first.sim.model, first.sim.state, scene) : undefined;
  return {
    notes,
    test: measured ? testLine(measured) : undefined,
    fps,
    idle,
    backend: app.stage.backend === 'webgpu' ? 'WebGPU' : 'WebGL2',
    simBackend: sim.kind === 'gpu' ? 'GPU (WebGPU compute)'
      : `CPU (worker${sim.stats.kernel === 'wasm' ? ', WebAssembly SIMD' : sim.stats.kernel === 'ts' ? ', TypeScript' : ''})`,
    backendNote: app.backend.note,
    stepMs: sim.stats.stepMs,
    measuring: !sim.stats.measured,
    slow: slow?.text ?? '',
    slowBy: slow?.by ?? '',
    paused: sim.paused,
    particles, triangles, springs, cloths,
    solver: scene.solver.type,
    // the substeps run: solver.substeps, or more for self-contact (the note says why)
    substeps: first?.sim.params.substeps ?? scene.solver.substeps,
    clamps: sim.stats.clamps,
    view: app.view,
    maxStrain: sim.stats.maxStrain,
    selfContact: scene.solver.selfContact,
    contacts: app.contactMeter.count(sim.mirrors.filter((m) => m.unstableAt < 0).map((m) => m.sim), performance.now()),
    contactDistance: first ? contactDistance(first.sim) : 0,
    slots: sim.mirrors.length,
    extra: [
      sweep.length && app.sweep.layout === 'sequence'
        ? `resolution ${app.sweep.index % sweep.length + 1} of ${sweep.length}, ${SWEEP_STAGE_FRAMES / 60} s each`
        : Object.hasOwn(SCENE_LABELS, scene.name) ? '' : `scene: ${plainText(scene.name, 100)}`,
      entries.length === 1 && shapeWords(scene.cloth) ? `cloth: ${shapeWords(scene.cloth)}` : '',
    ].filter(Boolean).join(' · ') || undefined,
  };
}

/** A cloth's shape in the HUD's words, '' for the rectangle: 'disc', 'mesh tshirt.obj' (as text). */
function shapeWords(cloth: ClothSpec): string {
  const mesh = clothMesh(cloth);
  return mesh !== null ? `mesh ${plainText(mesh, 80)}` : cloth.shape === 'rectangle' ? '' : cloth.shape;
}

/** One line for the HUD: what a fabric test measures now ('—' for a value that is not finite: an unstable cloth). */
export function testLine(t: TestResult): string {
  if (t.type === 'cantilever') {
    const c = t.bendingLength === null ? '— (the tip has not dropped yet)' : `${finite(100 * t.bendingLength, 2)} cm`;
    return `cantilever: tip ${finite(t.chordAngle, 1)}° below the edge, ${finite(100 * t.overhang, 2)} cm out → bending length ${c}`;
  }
  return `Cusick drape: coefficient ${finite(t.drapeCoefficient, 3)}, ${finite(t.folds, 0)} fold${t.folds === 1 ? '' : 's'}`;
}
