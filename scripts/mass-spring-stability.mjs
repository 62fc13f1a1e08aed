#!/usr/bin/env node
// Issue 10 (lumped masses, local stability limit): what stiffness the explicit mass-spring solver gives a cloth.
// For each shape × resolution × substeps, resolveParams (params.ts) on a cotton cloth (or --fabric): the clamp
// lines it reports, the fraction of each kind's springs left at full stiffness, the smallest and the median factor
// applied (stiffness / unclamped stiffness), and the factor on the structural spring nearest the cloth's centre.
// Reads params.stiffness only, so it measures any version of params.ts.
//
//   npx tsc -p tsconfig.build.json && node scripts/mass-spring-stability.mjs
//   options: --fabric cotton  --shapes rectangle,disc,tube  --faces 16,32,64  --substeps 10,20,40
import { modelFor, resolveParams, validateScene } from '../dist/core/index.js';

const arg = (name, dflt) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : dflt;
};
const fabric = arg('fabric', 'cotton');
const shapes = arg('shapes', 'rectangle').split(',');
const facesList = arg('faces', '16,32,64').split(',').map(Number);
const substepsList = arg('substeps', '10,20,40').split(',').map(Number);
const KINDS = ['structural', 'shear', 'bend'];

for (const shape of shapes) {
  for (const faces of facesList) {
    for (const substeps of substepsList) {
      const base = { cloth: { shape, resolution: faces }, material: { fabric }, colliders: [] };
      const scene = validateScene({ ...base, solver: { type: 'mass-spring', substeps } });
      // the same scene with the xpbd solver: no stability limit, so its stiffness is the material's
      const free = validateScene({ ...base, solver: { type: 'xpbd', substeps, bending: 'springs' } });
      const model = modelFor(scene);
      const p = resolveParams(model, scene), q = resolveParams(model, free);
      const rows = [];
      for (let kind = 0; kind < 3; kind++) {
        const f = [];
        for (let s = 0; s < model.restLengths.length; s++) {
          if (model.springKinds[s] === kind && q.stiffness[s] > 0) f.push(p.stiffness[s] / q.stiffness[s]);
        }
        if (f.length === 0) continue;
        f.sort((a, b) => a - b);
        const full = f.filter((v) => v > 1 - 1e-6).length / f.length;
        rows.push(`${KINDS[kind]} ${(100 * full).toFixed(1)} % full, min ×${f[0].toPrecision(3)}, median ×${f[f.length >> 1].toPrecision(3)}`);
      }
      // the structural spring nearest the centre of the rest shape
      const c = [0, 0, 0], x = model.restPositions, n = model.particleCount;
      for (let i = 0; i < n; i++) for (let k = 0; k < 3; k++) c[k] += x[3 * i + k] / n;
      let best = -1, bestD = Infinity;
      for (let s = 0; s < model.restLengths.length; s++) {
        if (model.springKinds[s] !== 0) continue;
        const a = model.springs[2 * s], b = model.springs[2 * s + 1];
        const d = Math.hypot(...[0, 1, 2].map((k) => (x[3 * a + k] + x[3 * b + k]) / 2 - c[k]));
        if (d < bestD) { bestD = d; best = s; }
      }
      console.log(`${shape} ${faces} faces, ${substeps} substeps: centre structural ${p.stiffness[best].toPrecision(4)} N/m of ${q.stiffness[best].toPrecision(4)}, damping ${(p.springDamping?.[best] ?? p.damping).toPrecision(3)} of ${q.damping} N·s/m`);
      console.log(`  ${rows.join('; ')}`);
      for (const line of p.clamps) console.log(`  clamp: ${line}`);
    }
  }
}
