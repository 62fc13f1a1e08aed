#!/usr/bin/env node
// The Peirce cantilever (ASTM D1388) table of docs/physics.md, "Bending at the hinges" (and "Isotropic bending"),
// for every bending model: a 10 cm square sheet of
// cotton (the fabric: ρ_A = 0.12 kg/m², B = 7.85·10⁻⁶ N·m) clamped along one side (the pinned rows) so that an overhang of
// about 2c sticks out, c = (B/(ρ_A·g))^(1/3) its bending length; after 10 s the chord from the clamp to the tip is
// measured, and c is recovered from Peirce's relation c = L·(cos(θ/2)/(8·tan θ))^(1/3) (θ = 41.5° where L = 2c).
// Per bending model, mesh size and solver setting. Needs `npm run build` (it reads dist/).
//   node scripts/cantilever.mjs
import { FABRICS, Simulation, validateScene } from '../dist/core/index.js';

const W = 0.1, RHO = FABRICS.cotton.arealDensity, B = FABRICS.cotton.bendingRigidity;
const c = Math.cbrt(B / (RHO * 9.81));

function measure(bending, faces, substeps, iterations) {
  const free = Math.round((2 * c) / (W / faces));
  const L = (free * W) / faces;
  const pins = [];
  for (let j = 0; j <= faces - free; j++) for (let i = 0; i <= faces; i++) pins.push(j * (faces + 1) + i);
  const scene = validateScene({
    cloth: { resolution: faces, width: W, height: W, position: [0, 1, 0] },
    material: { fabric: 'cotton', damping: 0.01 },
    solver: { bending, substeps, iterations },
    colliders: [],
    pins,
  });
  const sim = new Simulation(scene, { kernel: 'ts' });
  sim.advance(600);
  const x = sim.state.positions, j0 = faces - free;
  let theta = 0;
  for (let i = 0; i <= faces; i++) {
    const a = 3 * (j0 * (faces + 1) + i), b = 3 * (faces * (faces + 1) + i);
    theta += Math.atan2(x[a + 1] - x[b + 1], x[b + 2] - x[a + 2]);
  }
  theta /= faces + 1;
  const measured = L * Math.cbrt(Math.cos(theta / 2) / (8 * Math.tan(theta)));
  return `${((theta * 180) / Math.PI).toFixed(1)}° → ${(measured / c).toFixed(2)}`;
}

console.log(`cotton: B = ${B.toExponential(3)} N·m, c = ${(100 * c).toFixed(2)} cm; cells: chord angle (41.5° wanted) → measured c / c`);
const settings = [[20, 1], [100, 4]];
console.log(`| model | faces | ${settings.map(([s, i]) => `${s} substeps × ${i}`).join(' | ')} |`);
console.log(`|---|---|${settings.map(() => '---').join('|')}|`);
for (const bending of ['springs', 'hinges', 'laplacian']) {
  for (const faces of [16, 32, 64]) {
    console.log(`| ${bending} | ${faces}² | ${settings.map(([s, i]) => measure(bending, faces, s, i)).join(' | ')} |`);
  }
}
