/** The GPU solver's answer for the collider shapes it does not have: one line naming the shape, for the CLI and the app. */
import { cubeMesh } from '../core/colliders/mesh-shapes.js';
import { describe, expect, it } from 'vitest';
import { COLLIDER_TYPES, createColliders, validateScene } from '../core/index.js';
import { sceneRefusal } from './encoder.js';
import { gpuCollider } from './uniforms.js';

describe('sceneRefusal', () => {
  it('accepts spheres and floors, and names any other shape with its place in the list', () => {
    expect(sceneRefusal(validateScene({ colliders: [{ type: 'sphere' }, { type: 'floor' }] }))).toBeNull();
    for (const type of ['plane', 'box', 'capsule', 'cylinder']) {
      const why = sceneRefusal(validateScene({ colliders: [{ type: 'floor' }, { type }] }));
      expect(why).toBe(`${type} colliders run on the CPU only (colliders[1]; the GPU has sphere and floor)`);
    }
    expect(sceneRefusal(validateScene({ solver: { type: 'mass-spring' } }))).toBe('the mass-spring solver runs on the CPU only');
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
    expect(sceneRefusal(scene)).toBe('mesh colliders run on the CPU only (colliders[1]; the GPU has sphere and floor)');
  });
});
