/**
 * Whether a scene's cloth can start where the scene puts it. A cloth whose start pose lies partly inside a
 * collider is pushed out at its first contact (at rest: phases.ts collideParticles() turns no push-out into velocity). That
 * is fine while the pushed-out cloth is still a cloth; the line is drawn where it is not:
 *   - a pinned particle inside a collider (a pin cannot be pushed out);
 *   - a particle that cannot be outside every collider at once (pushed out of one, it is inside another);
 *   - a cloth that, each particle moved to the nearest point of the surface it is inside, stretches a structural
 *     spring beyond its stretch limit (`material.stretchFactor`): the collider cuts through the cloth, as a sphere
 *     around or across its middle does.
 * So a cloth may start touching a collider or sunk into it a little (a floor above a horizontal cloth lifts it onto
 * the floor; a sphere of radius R may dip into it by about (stretchFactor − 1)·R), but not cut by it.
 */
import type { ColliderShape } from './colliders/shape.js';
import { STRUCTURAL, type ClothModel } from './model.js';
import { SceneError } from './scene.js';

const normal = new Float64Array(3);

/** Throws SceneError naming the collider when the cloth cannot start outside `colliders` (see above). */
export function checkPlacement(
  model: ClothModel, colliders: readonly ColliderShape[], pinned: readonly number[], stretchFactor: number, source = 'scene',
): void {
  const n = model.particleCount;
  const x = Float64Array.from(model.restPositions);
  const movedBy = new Int32Array(n).fill(-1);
  const isPinned = new Uint8Array(n);
  for (const p of pinned) isPinned[p] = 1;
  const name = (k: number) => `colliders[${k}] (${colliders[k].type})`;
  colliders.forEach((shape, k) => {
    for (let i = 0; i < n; i++) {
      const d = shape.signedDistance(x[3 * i], x[3 * i + 1], x[3 * i + 2], normal);
      if (d >= 0) continue;
      if (isPinned[i]) throw new SceneError(`${source}: ${name(k)}: pinned particle ${i} starts inside it, and a pin cannot be pushed out; move the collider, the cloth or the pin`);
      for (let c = 0; c < 3; c++) x[3 * i + c] -= d * normal[c];
      movedBy[i] = k;
    }
  });
  // pushed out of a later collider into an earlier one: no place outside both (1 µm of round-off allowed)
  colliders.forEach((shape, k) => {
    for (let i = 0; i < n; i++) {
      if (movedBy[i] < 0 || movedBy[i] === k) continue;
      if (shape.signedDistance(x[3 * i], x[3 * i + 1], x[3 * i + 2], normal) < -1e-6) {
        throw new SceneError(`${source}: ${name(k)} and ${name(movedBy[i])}: the cloth starts inside both and cannot be outside both at once; move a collider or the cloth`);
      }
    }
  });
  let worst = 0, worstSpring = -1;
  const sp = model.springs, rest = model.restLengths;
  for (let s = 0; s < rest.length; s++) {
    if (model.springKinds[s] !== STRUCTURAL) continue;
    const a = sp[2 * s], b = sp[2 * s + 1];
    if (movedBy[a] < 0 && movedBy[b] < 0) continue;
    const strain = Math.hypot(x[3 * a] - x[3 * b], x[3 * a + 1] - x[3 * b + 1], x[3 * a + 2] - x[3 * b + 2]) / rest[s] - 1;
    if (strain > worst) { worst = strain; worstSpring = s; }
  }
  if (worst > stretchFactor - 1 + 1e-6) {
    const k = Math.max(movedBy[sp[2 * worstSpring]], movedBy[sp[2 * worstSpring + 1]]);
    const pct = (v: number) => `${(100 * v).toPrecision(v < 0.1 ? 2 : 3)} %`;
    throw new SceneError(`${source}: ${name(k)} cuts through the cloth where it starts: pushed out of it, the cloth would stretch ${pct(worst)}, past its stretch limit of ${pct(stretchFactor - 1)}; move the collider or the cloth`);
  }
}
