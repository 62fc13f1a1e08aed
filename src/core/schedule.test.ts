/**
 * The phase schedule holds every CPU backend: each runs exactly the schedule's phases of a frame, in its order (the
 * WebAssembly kernel reports what it ran itself), and a phase a backend does not implement runs in the TypeScript
 * reference on the backend's memory. (The GPU's encoder is held to it in src/gpu/schedule.test.ts.)
 */
import { describe, expect, it } from 'vitest';
import { runFrame, type PhaseBackend } from './frame.js';
import { FRAME_DT } from './params.js';
import { WasmBackend } from './backend.js';
import { REFERENCE } from './reference.js';
import { grab } from './state.js';
import type { Scene, SolverType } from './scene.js';
import { validateScene } from './scene.js';
import { builtinScene } from './scenes.js';
import { PHASE, PHASE_COUNT, PHASES, PhaseLog, assignPhases, type BackendPhases, type PhaseName } from './schedule.js';
import { Simulation } from './simulation.js';
import { KERNEL_PHASES } from './wasm/xpbd-wasm.js';

/** The phases a frame must run, straight from the table: frame start, every substep's, frame end. */
function expected(solver: SolverType, substeps: number, wind: boolean, grabbed: boolean): PhaseName[] {
  const runs = (name: PhaseName) => {
    const p = PHASES[PHASE[name]];
    // the scenes here solve their springs one at a time (solver.stretch 'gauss-seidel': the 'local' phases)
    return p.solvers.includes(solver) && (p.when === 'always' || p.when === 'local' || (p.when === 'wind' && wind) || (p.when === 'grab' && grabbed));
  };
  const of = (scope: string) => PHASES.filter((p) => p.scope === scope && runs(p.name)).map((p) => p.name);
  return [...of('frame-start'), ...Array.from({ length: substeps }, () => of('substep')).flat(), ...of('frame-end')];
}

/** The hanging flag in gusts, pinned along one edge, with a particle grabbed: every condition of the table holds. */
function windyScene(solver: SolverType, edit: (s: Scene) => void = () => {}): Scene {
  const s = builtinScene('wind');
  s.cloth.resolution = 8;
  // the floor only (the flag's pole is a cylinder, whose rim adds triangle contact: the phases below are the floor's)
  s.colliders = [{ type: 'floor', height: 0 }];
  // self-contact off (the built-in scenes have it on): the table's self-contact condition is held in its own test;
  // the springs swept alone (the 'local' phases), not after the coarse correction, the default: its own cases below
  s.solver = { ...s.solver, type: solver, substeps: 3, iterations: 2, selfContact: false, stretch: 'gauss-seidel' };
  edit(s);
  return s;
}

/** One frame of `sim` with a log: TypeScript, or the kernel when the state lives in one. */
function loggedFrame(sim: Simulation, grabbed: boolean): PhaseLog {
  if (grabbed) grab(sim.state, 5, [0.1, 2.2, 0.3]);
  const log = new PhaseLog();
  if (sim.backend instanceof WasmBackend) sim.backend.kernel.frame(sim.model, sim.state, sim.params, FRAME_DT, log);
  else runFrame(sim.model, sim.state, sim.params, FRAME_DT, undefined, log);
  return log;
}

const plain = (log: PhaseLog) => log.names().map((n) => n.replace(' (reference)', ''));

describe('the phase schedule', () => {
  it('is the one table in order: ids ascend, scopes frame-start → substep → frame-end, a reference for every phase', () => {
    expect(PHASES.map((p) => p.id)).toEqual(Array.from({ length: PHASE_COUNT }, (_, i) => i));
    const rank = { 'frame-start': 0, substep: 1, 'frame-end': 2 };
    for (let id = 1; id < PHASE_COUNT; id++) expect(rank[PHASES[id].scope]).toBeGreaterThanOrEqual(rank[PHASES[id - 1].scope]);
    expect(REFERENCE).toHaveLength(PHASE_COUNT);
    for (const impl of REFERENCE) expect(impl).toBeTypeOf('function');
  });

  describe.each([
    ['xpbd', 'ts'], ['mass-spring', 'ts'], ['xpbd', 'wasm'],
  ] as const)('%s solver, %s kernel: runs the schedule, no phase skipped or moved', (solver, kernel) => {
    it.each([[true, true], [false, false], [true, false]])('wind %s, a grab %s', (wind, grabbed) => {
      const sim = new Simulation(windyScene(solver, (s) => { s.wind.enabled = wind; }), { kernel });
      expect(sim.kernel).toBe(kernel);
      const log = loggedFrame(sim, grabbed);
      expect(plain(log)).toEqual(expected(solver, 3, wind, grabbed));
      // and the next frame too (the grab still on, the Taylor start over)
      expect(plain(loggedFrame(sim, false))).toEqual(expected(solver, 3, wind, grabbed));
    });
  });

  it('the TypeScript backend runs every phase in the reference', () => {
    const log = loggedFrame(new Simulation(windyScene('xpbd'), { kernel: 'ts' }), true);
    expect([...log.byReference.subarray(0, log.length)].every((r) => r === 1)).toBe(true);
  });
});

describe('a phase a backend does not implement runs in the TypeScript reference on its memory', () => {
  it('the kernel: the start and end of a frame in TypeScript, its own phases in the kernel (the wind and floor contact too)', () => {
    const sim = new Simulation(windyScene('xpbd'), { kernel: 'wasm' });
    const log = loggedFrame(sim, true);
    const substep = ['wind', 'integrate', 'grab', 'distance', 'tethers', 'stretchLimit', 'contact'];
    expect(log.names()).toEqual(['begin (reference)', ...substep, ...substep, ...substep, 'velocities (reference)']);
  });

  // triangle contact with every analytic shape is the kernel's (triangle-contact.as.ts); with a mesh collider it is
  // left to the reference, on the kernel's memory (as the mesh's particle contact is)
  it.each(['sphere', 'capsule', 'cylinder', 'box'] as const)('the kernel: triangle contact on a coarse cloth over a %s is its own phase after the kernel\'s particle contact, run there', (shape) => {
    const s = builtinScene('resolution'); // one face on the sphere: contact needs triangles
    s.solver.selfContact = false;
    s.colliders = s.colliders.map((c) => c.type !== 'sphere' ? c : shape === 'box'
      ? { type: 'box', center: c.center, halfExtents: [c.radius, c.radius, c.radius], rotation: [0, 0, 0] }
      : shape === 'capsule' ? { type: 'capsule', a: [c.center[0] - 0.5, c.center[1], c.center[2]], b: [c.center[0] + 0.5, c.center[1], c.center[2]], radius: c.radius }
        : shape === 'cylinder' ? { type: 'cylinder', center: c.center, axis: [0, 1, 0], radius: c.radius, height: 2 * c.radius } : c);
    const sim = new Simulation(validateScene(s), { kernel: 'wasm' });
    const own = assignPhases(KERNEL_PHASES, sim.model, sim.params);
    expect(own & (1 << PHASE.contact)).not.toBe(0);
    expect(own & (1 << PHASE.contactTriangles)).not.toBe(0);
    const log = loggedFrame(sim, false);
    // (the springs' coarse correction, the default, is the kernel's too: before the sweep)
    const substep = ['integrate', 'coarseStretch', 'distance', 'tethers', 'stretchLimit', 'contact', 'contactTriangles'];
    expect(log.names()).toEqual(['begin (reference)', ...Array.from({ length: s.solver.substeps }, () => substep).flat(), 'velocities (reference)']);
    // and the cloth still comes to rest on it
    sim.advance(180);
    expect(sim.report().maxPenetration).toBeLessThanOrEqual(1e-3);
  });

  it('the kernel runs no phase of the mass-spring solver: its frame runs whole in the reference', () => {
    const sim = new Simulation(windyScene('xpbd'), { kernel: 'wasm' });
    sim.set('solver.type', 'mass-spring');
    expect(assignPhases(KERNEL_PHASES, sim.model, sim.params)).toBe(0);
  });

  it('a backend that shares memory and implements some phases: the rest in the reference, the cloth bit for bit', () => {
    // a backend whose integrate and tethers are the reference's own, handed over by the frame loop
    const ran: number[] = [];
    const partial: PhaseBackend = {
      phases: { name: 'partial', where: 'here', sharesMemory: true, solvers: ['xpbd', 'mass-spring'], phases: (1 << PHASE.integrate) | (1 << PHASE.tethers) },
      run(mask, model, state, params, frame, log) {
        for (let id = 0; id < PHASE_COUNT; id++) {
          if ((mask & (1 << id)) === 0) continue;
          ran.push(id);
          REFERENCE[id](model, state, params, frame);
          log?.push(id, false);
        }
      },
    };
    for (const solver of ['xpbd', 'mass-spring'] as const) {
      ran.length = 0;
      const a = new Simulation(windyScene(solver), { kernel: 'ts' });
      const b = new Simulation(windyScene(solver), { kernel: 'ts' });
      const log = new PhaseLog();
      for (let f = 0; f < 5; f++) {
        runFrame(a.model, a.state, a.params, FRAME_DT);
        runFrame(b.model, b.state, b.params, FRAME_DT, partial, f === 0 ? log : undefined);
      }
      expect([...b.state.positions]).toEqual([...a.state.positions]);
      expect([...b.state.velocities]).toEqual([...a.state.velocities]);
      expect(new Set(ran)).toEqual(new Set([PHASE.integrate, PHASE.tethers]));
      const names = log.names();
      expect(names).toContain('integrate');
      expect(names).toContain('wind (reference)');
      expect(names.filter((n) => n === 'tethers')).toHaveLength(3);
    }
  });

  it('a backend that does not share memory cannot leave a phase to the reference: refused, naming the phase', () => {
    const sim = new Simulation(windyScene('xpbd'), { kernel: 'ts' });
    const all = (1 << PHASE_COUNT) - 1;
    const remote: BackendPhases = { name: 'remote', where: 'remotely', sharesMemory: false, solvers: ['xpbd'], phases: all & ~(1 << PHASE.tethers) };
    expect(() => assignPhases(remote, sim.model, sim.params)).toThrow(/remote: it does not implement phase 'tethers'/);
    expect(() => assignPhases({ ...remote, phases: all, refusal: () => 'no such shape' }, sim.model, sim.params)).toThrow(/remote: no such shape/);
    expect(() => assignPhases({ ...remote, solvers: ['mass-spring'] }, sim.model, sim.params)).toThrow(/remote: only the mass-spring solver runs remotely \(params.solver is 'xpbd'\)/);
    // not the phases these params never make a frame run: no carried pins, no collider that needs triangle contact,
    // no stencil bending (solver.bending 'springs'), no global stretch step and no coarse correction (solver.stretch
    // 'gauss-seidel'), no self-contact (solver.selfContact false)
    expect(assignPhases({ ...remote, phases: all }, sim.model, sim.params))
      .toBe(all & ~(1 << PHASE.springForces) & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles) &
        ~(1 << PHASE.bending) & ~(1 << PHASE.globalBending) & ~(1 << PHASE.globalStretch) & ~(1 << PHASE.coarseStretch) & ~(1 << PHASE.selfContact));
    // with the coarse correction (solver.stretch 'two-level'), its phase before the sweep, which stays
    const coarse = new Simulation(windyScene('xpbd', (s) => { s.solver.stretch = 'two-level'; }), { kernel: 'ts' });
    expect(assignPhases({ ...remote, phases: all }, coarse.model, coarse.params))
      .toBe(all & ~(1 << PHASE.springForces) & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles) &
        ~(1 << PHASE.bending) & ~(1 << PHASE.globalBending) & ~(1 << PHASE.globalStretch) & ~(1 << PHASE.selfContact));
    expect(() => assignPhases({ ...remote, phases: all & ~(1 << PHASE.coarseStretch) }, coarse.model, coarse.params)).toThrow(/remote: it does not implement phase 'coarseStretch'/);
    // with the springs solved together, the global step instead of the sweep, the tethers and the stretch limit
    const together = new Simulation(windyScene('xpbd', (s) => { s.solver.stretch = 'global'; }), { kernel: 'ts' });
    expect(assignPhases({ ...remote, phases: all }, together.model, together.params))
      .toBe(all & ~(1 << PHASE.springForces) & ~(1 << PHASE.carry) & ~(1 << PHASE.contactTriangles) &
        ~(1 << PHASE.bending) & ~(1 << PHASE.globalBending) & ~(1 << PHASE.distance) & ~(1 << PHASE.tethers) & ~(1 << PHASE.stretchLimit) &
        ~(1 << PHASE.coarseStretch) & ~(1 << PHASE.selfContact));
    // with self-contact, its phase too: a backend without it that keeps the cloth elsewhere is refused by name
    const selfy = new Simulation(windyScene('xpbd', (s) => { s.solver.selfContact = true; }), { kernel: 'ts' });
    expect(() => assignPhases({ ...remote, phases: all & ~(1 << PHASE.selfContact) }, selfy.model, selfy.params))
      .toThrow(/remote: it does not implement phase 'selfContact'/);
    // so a backend without the bending phase takes the springs' bending, and is refused the hinges' and the Laplacian's
    const noStencils = { ...remote, phases: all & ~(1 << PHASE.bending) };
    expect(() => assignPhases(noStencils, sim.model, sim.params)).not.toThrow();
    for (const bending of ['hinges', 'laplacian'] as const) {
      const bent = new Simulation(windyScene('xpbd', (s) => { s.solver.bending = bending; }), { kernel: 'ts' });
      expect(() => assignPhases(noStencils, bent.model, bent.params)).toThrow(/remote: it does not implement phase 'bending'/);
      // solved together, the global bending step instead of the sweep
      const together = new Simulation(windyScene('xpbd', (s) => { s.solver.bending = bending; s.solver.bendingSolve = 'global'; }), { kernel: 'ts' });
      expect(() => assignPhases(noStencils, together.model, together.params)).not.toThrow();
      expect(() => assignPhases({ ...remote, phases: all & ~(1 << PHASE.globalBending) }, together.model, together.params)).toThrow(/remote: it does not implement phase 'globalBending'/);
      expect(assignPhases({ ...remote, phases: all }, together.model, together.params) & ((1 << PHASE.bending) | (1 << PHASE.globalBending))).toBe(1 << PHASE.globalBending);
    }
    // with the skip-one springs there are no stencils: solver.bendingSolve changes nothing
    const springs = new Simulation(windyScene('xpbd', (s) => { s.solver.bendingSolve = 'global'; }), { kernel: 'ts' });
    expect(assignPhases({ ...remote, phases: all }, springs.model, springs.params)).toBe(assignPhases({ ...remote, phases: all }, sim.model, sim.params));
  });
});
