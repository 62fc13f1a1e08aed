#!/usr/bin/env node
// Issue 10 (the flag that would not droop): the `wind` scene with the wind off, a 1.5 × 1 m cotton flag pinned along
// its left edge, hanging. How far its centroid and its free top corner drop in 10 s, per solver and CPU kernel, flat
// (cloth.imperfection 0) and with the scene's own bulge, beside two limits:
// - in plane (an exactly flat flag, gravity in its plane: it can only shear and stretch): the flag is a cantilever
//   shear beam; the shear force at x from the pole is ρ_A·g·H·(L − x), the shear strain ρ_A·g·(L − x)/G, so the
//   free end drops ρ_A·g·L²/(2G) and the centroid ρ_A·g·L²/(3G) (in-plane bending of the 1 m deep "beam" and the
//   stretch add about a millimetre);
// - limp: the flag's bottom half is in compression (the in-plane bending moment at the pole, ρ_A·g·H·L²/2, wants
//   ±8 N/m of fibre stress), and cotton buckles under a few hundredths of a N/m (π²B/λ² for folds of 10 cm), so a
//   flag that can leave its plane hangs from the pole: each fibre at most L/2 lower on average, the centroid ≤ 0.75 m.
//
//   npx tsc -p tsconfig.build.json && node scripts/flag-droop.mjs   (about 10 s)
//   options: --seconds 10  --cases xpbd/ts,xpbd/wasm,mass-spring/ts
import { Simulation, builtinScene, validateScene } from '../dist/core/index.js';

const arg = (name, def) => { const i = process.argv.indexOf(`--${name}`); return i > 0 ? process.argv[i + 1] : def; };
const seconds = Number(arg('seconds', '10'));
const cases = arg('cases', 'xpbd/ts,xpbd/wasm,mass-spring/ts').split(',').map((c) => c.split('/'));
const marks = [1, 2, 3, 10].filter((s) => s <= seconds);

const base = validateScene(builtinScene('wind'));
const { arealDensity: rho, shearStiffness: G } = base.material;
const L = base.cloth.width, g = 9.81;
console.log(`in plane (shear beam, G = ${G} N/m): free end ${(100 * rho * g * L * L / (2 * G)).toFixed(1)} cm, centroid ${(100 * rho * g * L * L / (3 * G)).toFixed(1)} cm; limp: centroid ≤ ${(L / 2).toFixed(2)} m`);
console.log(`| solver / kernel | cloth.imperfection | ${marks.map((s) => `centroid drop at ${s} s [m]`).join(' | ')} | free top corner drop at ${seconds} s [m] | max z [m] | clamps |`);
console.log(`|---|---|${marks.map(() => '---|').join('')}---|---|---|`);
for (const [solver, kernel] of cases) {
  for (const imperfection of [0, base.cloth.imperfection]) {
    const doc = builtinScene('wind');
    doc.wind = { ...doc.wind, enabled: false };
    // self-contact off, as the table was first measured (the scene has had it on since; it never meets itself here,
    // but the exactly flat mass-spring flag then drops 0.085–0.196 m instead of 0.218–0.259 m in 1–10 s)
    doc.solver = { ...doc.solver, type: solver, selfContact: false };
    doc.cloth = { ...doc.cloth, imperfection };
    const sim = new Simulation(validateScene(doc), { kernel });
    const R = sim.scene.cloth.resolution, corner = 3 * R + 1; // row 0 is the top, column R the free edge
    const cy = () => { const x = sim.state.positions; let s = 0; for (let i = 1; i < x.length; i += 3) s += x[i]; return s / (x.length / 3); };
    const c0 = cy(), k0 = sim.state.positions[corner];
    const drops = [];
    for (let s = 1; s <= seconds; s++) {
      sim.advance(60);
      if (marks.includes(s)) drops.push((c0 - cy()).toFixed(3));
    }
    let zmax = 0;
    for (let i = 2; i < sim.state.positions.length; i += 3) zmax = Math.max(zmax, Math.abs(sim.state.positions[i]));
    const clamps = sim.params.clamps.map((c) => c.replace(/ for stability.*$/, '')).join('; ');
    console.log(`| ${solver} / ${kernel} | ${imperfection} | ${drops.join(' | ')} | ${(k0 - sim.state.positions[corner]).toFixed(3)} | ${zmax.toFixed(3)} | ${clamps || '—'} |`);
    sim.dispose();
  }
}
