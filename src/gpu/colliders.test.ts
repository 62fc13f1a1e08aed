/**
 * The GPU solver's answer for the collider shapes it has and has not: every analytic shape, moving or not, carrying
 * pins or not, is taken; a shape its kernels do not know is named in one line, for the CLI and the app.
 */
import { cubeMesh } from '../core/colliders/mesh-shapes.js';
import { describe, expect, it } from 'vitest';
import { COLLIDER_TYPES, PosedCollider, Simulation, createColliders, validateScene, type ColliderShape } from '../core/index.js';
import { assignPhases } from '../core/schedule.js';
import { GPU_PHASES, sceneRefusal } from './encoder.js';
import { gpuCollider } from './colliders.js';

describe('sceneRefusal', () => {
  it('takes every analytic shape, moving, driven or carrying pins; refuses the mass-spring solver', () => {
    const analytic = COLLIDER_TYPES.filter((type) => type !== 'mesh');
    expect(sceneRefusal(validateScene({ colliders: analytic.map((type) => ({ type })) }))).toBeNull();
    const motion = { keyframes: [{ time: 0 }, { time: 1, translation: [0.1, 0, 0], rotation: [0, 30, 0] }] };
    for (const type of analytic) {
      expect(sceneRefusal(validateScene({ colliders: [{ type, motion, pins: ['top-left'] }] })), type).toBeNull();
    }
    expect(sceneRefusal(validateScene({ solver: { type: 'mass-spring' } }))).toBe('the mass-spring solver runs on the CPU only');
    expect(sceneRefusal(validateScene({ solver: { stretch: 'global' } }))).toBe("the global stretch step (solver.stretch 'global') runs on the CPU only");
    expect(sceneRefusal(validateScene({ solver: { selfContact: true } }))).toBe('self-contact (solver.selfContact) runs on the CPU only');
  });

  it('follows gpuCollider: a type is refused exactly when the GPU has no encoding for it', () => {
    for (const type of COLLIDER_TYPES) {
      // a mesh collider names its file (read here from memory)
      const scene = validateScene({ colliders: [type === 'mesh' ? { type, mesh: 'cube.obj' } : { type }] });
      expect(sceneRefusal(scene) === null, type).toBe(gpuCollider(createColliders(scene.colliders, () => cubeMesh())[0]) !== null);
    }
  });
  it('refuses a mesh collider by name and place, without reading its file', () => {
    const scene = validateScene({ colliders: [{ type: 'sphere' }, { type: 'mesh', mesh: 'never-read.obj' }] });
    expect(sceneRefusal(scene)).toBe('mesh colliders run on the CPU only (colliders[1]; the GPU has sphere, floor, plane, box, capsule and cylinder)');
  });

  it('a shape the kernels do not know: its contact refused by name', () => {
    const blob: ColliderShape = {
      type: 'blob', minCurvatureRadius: Infinity,
      signedDistance: (_x, y, _z, n) => { n[0] = 0; n[1] = 1; n[2] = 0; return y; },
    };
    const shape = new PosedCollider(blob, [1, 0, 0, 0, 1, 0, 0, 0, 1], [0, 0, 0]);
    expect(gpuCollider(shape)).toBeNull();
    const sim = new Simulation(validateScene({ cloth: { resolution: 4 }, colliders: [] }), { kernel: 'ts' });
    const params = { ...sim.params, colliders: [shape] };
    expect(() => assignPhases(GPU_PHASES, sim.model, params))
      .toThrow("GPU solver: collider type 'blob' is not supported on the GPU (it has sphere, floor, plane, box, capsule and cylinder)");
  });
});
