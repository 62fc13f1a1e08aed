/**
 * The simulation worker: owns the Simulation objects (one per slot) so that stepping never blocks input or
 * drawing. Dumb on purpose: it applies commands in order and steps when asked (the page owns the clock). Where
 * the page is cross-origin isolated, the WebAssembly kernel shares large cloths' substeps with helper threads.
 */
import { Simulation, energy, grab, maxStructuralStrain, release, type Energy } from '../../core/index.js';
import { browserHelpers } from './helpers.js';
import { MeshStore } from './meshes.js';
import type { FromWorker, SlotFrame, ToWorker } from './protocol.js';

interface Slot {
  sim: Simulation;
  gen: number;
}

/**
 * Frame at which a slot's positions stopped being finite, or -1. The core's Simulation checks after every frame
 * and steps no further once they are not (`unstableFrame`); reset and rebuilds clear it.
 */
const unstableAt = (s: Slot): number => s.sim.unstableFrame ?? -1;

const ctx = self as unknown as {
  postMessage(message: FromWorker, transfer?: Transferable[]): void;
  onmessage: ((e: MessageEvent<ToWorker>) => void) | null;
};

let slots: Slot[] = [];
/** the kernel's helper threads where the page is cross-origin isolated (else none: one thread) */
const spawnHelper = browserHelpers();
/** the mesh files the page sent (`mesh` messages), for the scenes that name them (cloth.mesh, colliders[k].mesh) */
const meshes = new MeshStore();

function send(msg: FromWorker, transfer: Transferable[] = []): void {
  ctx.postMessage(msg, transfer);
}

function frameMessage(id: number, frames: number, stepMs: number): void {
  const out: SlotFrame[] = [];
  const transfer: Transferable[] = [];
  const total: Energy = { kinetic: 0, gravitational: 0, elastic: 0, bending: 0 };
  let maxStrain = 0;
  const clamps = new Set<string>();
  for (const s of slots) {
    const { sim } = s;
    const positions = sim.state.positions.slice();
    const pinned = sim.state.pinned.slice();
    transfer.push(positions.buffer, pinned.buffer);
    out.push({ gen: s.gen, frame: sim.frame, positions, pinned, grabbed: sim.state.grabbed, unstableAt: unstableAt(s) });
    // a cloth that is not finite any more has no energy or strain worth showing (NaN)
    if (unstableAt(s) >= 0) continue;
    const e = energy(sim.model, sim.state, sim.params);
    total.kinetic += e.kinetic;
    total.gravitational += e.gravitational;
    total.elastic += e.elastic;
    total.bending += e.bending;
    maxStrain = Math.max(maxStrain, maxStructuralStrain(sim.model, sim.state));
    for (const c of sim.notes) clamps.add(c);
  }
  const kernel = slots[0]?.sim.kernel ?? '';
  const threads = slots[0]?.sim.threads ?? 1;
  send({ type: 'frame', id, frames, slots: out, stepMs, energy: total, maxStrain, clamps: [...clamps], kernel, threads }, transfer);
}

function handle(msg: ToWorker): void {
  switch (msg.type) {
    case 'mesh':
      meshes.add(msg.entry);
      return;
    case 'load':
      slots = msg.scenes.map((scene) => ({ sim: new Simulation(scene, { meshes: meshes.resolve, spawnHelper }), gen: msg.gen }));
      return;
    case 'setScene': {
      const slot = slots[msg.slot];
      if (!slot) return;
      slot.sim.setScene(msg.scene, msg.carry);
      slot.gen = msg.gen;
      return;
    }
    case 'reset':
      slots.forEach((s, k) => {
        if (msg.slot !== undefined && msg.slot !== k) return;
        s.sim.reset();
        s.gen = msg.gen;
      });
      return;
    case 'grab': {
      const slot = slots[msg.slot];
      if (slot && msg.particle < slot.sim.model.particleCount) grab(slot.sim.state, msg.particle, msg.target);
      return;
    }
    case 'release': {
      const slot = slots[msg.slot];
      if (slot) release(slot.sim.state);
      return;
    }
    case 'colliderPose': {
      const slot = slots[msg.slot];
      if (slot && msg.index < slot.sim.params.colliders.length) slot.sim.setColliderPose(msg.index, msg.pose);
      return;
    }
    case 'setState': {
      const slot = slots[msg.slot];
      if (!slot || msg.positions.length !== slot.sim.state.positions.length) return;
      const st = slot.sim.state;
      st.positions.set(msg.positions);
      st.previousPositions.set(msg.previous);
      st.velocities.set(msg.velocities);
      // positions come as float32: nothing finer than that
      st.residuals.fill(0);
      st.previousResiduals.fill(0);
      st.time = msg.time;
      st.substeps = msg.substeps;
      st.tethersStale = true;
      slot.sim.frame = msg.frame;
      return;
    }
    case 'poison': {
      const slot = slots[msg.slot];
      if (!slot) return;
      const i = 3 * (slot.sim.model.particleCount >> 1);
      slot.sim.state.positions.fill(NaN, i, i + 3);
      return;
    }
    case 'advance': {
      const t0 = performance.now();
      // a cloth that blows up stops at the frame it did (Simulation.advance), and the page is told (unstableAt)
      for (const s of slots) s.sim.advance(msg.frames);
      const stepMs = msg.frames > 0 ? (performance.now() - t0) / msg.frames : 0;
      frameMessage(msg.id, msg.frames, stepMs);
      return;
    }
  }
}

ctx.onmessage = (e) => {
  try {
    handle(e.data);
  } catch (err) {
    send({ type: 'error', message: err instanceof Error ? err.message : String(err) });
  }
};
