// Shared by scripts/hanging-strain.mjs and scripts/pd-study.mjs (issue 10, converged stretch and bending): the two
// test setups as scene documents, and what is measured on them. Not a script of its own.
//
// Hanging sheet: a 1 m square sheet hanging in the xy plane, pinned along its whole top row, no colliders, gravity.
// At rest the strain at distance s below the top is ε(s) = ρ_A·g·(L − s)/k (k the sheet's tensile stiffness,
// material.structuralStiffness [N/m]), so the bottom drops by ∫ε ds = ρ_A·g·L²/(2k) and the mean strain over the
// middle half of the height (s from L/4 to 3L/4) is ρ_A·g·L/(2k). Both are measured on the middle half of the
// columns (the sides contract sideways and the top row cannot).
//
// Peirce cantilever (ASTM D1388, as scripts/cantilever.mjs): a 10 cm square sheet of cotton clamped along one side
// (pinned rows) with an overhang of about 2c, c = (B/(ρ_A·g))^(1/3); from the chord angle θ of the overhang,
// Peirce's relation c = L·(cos(θ/2)/(8·tan θ))^(1/3) gives c back (θ = 41.5° where L = 2c).
import { BEND_SPRING_PER_RIGIDITY, validateScene } from '../dist/core/index.js';

export const G = 9.81;

export const FABRICS = {
  // the built-in fabrics of src/core/scenes.ts
  rubber: { mass: 0.38, structuralStiffness: 600, shearStiffness: 200, bendStiffness: 0.75, damping: 0.2, stretchFactor: 1.8, friction: 0.8, staticFriction: 1.0 },
  cotton: { mass: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendStiffness: 0.74, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 },
};

/** The hanging-sheet scene (1 m, pinned top row, no colliders). */
export function hangingScene(fabric, faces, substeps, iterations, bending = 'springs', stretch = 'gauss-seidel') {
  return validateScene({
    name: `hanging-${fabric}`,
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: FABRICS[fabric],
    solver: { type: 'xpbd', substeps, iterations, bending, stretch },
    colliders: [],
    pins: ['top-edge'],
  });
}

/** Theory for the hanging sheet: elongation ρ_A g L²/(2k) [m] and the middle half's mean strain ρ_A g L/(2k). */
export function hangingTheory(fabric) {
  const f = FABRICS[fabric];
  const rho = f.mass; // 1 m² sheet
  return { elongation: (rho * G) / (2 * f.structuralStiffness), strainMid: (rho * G) / (2 * f.structuralStiffness), strainTop: (rho * G) / f.structuralStiffness };
}

/**
 * Measures the hanging sheet from positions x (stride 3) of a (faces + 1)² grid, row 0 at the top:
 * elongation [m] (rest height 1 m) and the middle half's mean vertical strain, both over the middle half of the columns.
 */
export function measureHanging(x, faces) {
  const nx = faces + 1;
  const i0 = Math.round(faces / 4), i1 = Math.round((3 * faces) / 4);
  const j0 = Math.round(faces / 4), j1 = Math.round((3 * faces) / 4);
  let el = 0, mid = 0, n = 0;
  for (let i = i0; i <= i1; i++) {
    const top = x[3 * i + 1], bottom = x[3 * (faces * nx + i) + 1];
    el += top - bottom - 1;
    mid += (x[3 * (j0 * nx + i) + 1] - x[3 * (j1 * nx + i) + 1]) / ((j1 - j0) / faces) - 1;
    n++;
  }
  return { elongation: el / n, strainMid: mid / n };
}

export const CANTILEVER = (() => {
  const W = 0.1, RHO = 0.12, KB = 0.74;
  const B = KB / BEND_SPRING_PER_RIGIDITY;
  return { W, RHO, KB, B, c: Math.cbrt(B / (RHO * G)) };
})();

/** The Peirce cantilever scene (as scripts/cantilever.mjs) and its overhang: { scene, free, L }. */
export function cantileverScene(faces, substeps, iterations, bending = 'hinges', stretch = 'gauss-seidel') {
  const { W, RHO, KB, c } = CANTILEVER;
  const free = Math.round((2 * c) / (W / faces));
  const L = (free * W) / faces;
  const pins = [];
  for (let j = 0; j <= faces - free; j++) for (let i = 0; i <= faces; i++) pins.push(j * (faces + 1) + i);
  const scene = validateScene({
    cloth: { resolution: faces, width: W, height: W, position: [0, 1, 0] },
    material: { mass: RHO * W * W, bendStiffness: KB, damping: 0.01 },
    solver: { type: 'xpbd', bending, substeps, iterations, stretch },
    colliders: [],
    pins,
  });
  return { scene, free, L };
}

/** Chord angle θ [rad] of the overhang and the bending length it gives back, as a ratio to c. */
export function measureCantilever(x, faces, free, L) {
  const j0 = faces - free;
  let theta = 0;
  for (let i = 0; i <= faces; i++) {
    const a = 3 * (j0 * (faces + 1) + i), b = 3 * (faces * (faces + 1) + i);
    theta += Math.atan2(x[a + 1] - x[b + 1], x[b + 2] - x[a + 2]);
  }
  theta /= faces + 1;
  const measured = L * Math.cbrt(Math.cos(theta / 2) / (8 * Math.tan(theta)));
  return { theta, deg: (theta * 180) / Math.PI, ratio: measured / CANTILEVER.c };
}

/** Kinetic energy Σ ½ m |v|² of velocities v (stride 3) with particle masses m. */
export function kinetic(v, m) {
  let e = 0;
  for (let i = 0; i < m.length; i++) e += 0.5 * m[i] * (v[3 * i] ** 2 + v[3 * i + 1] ** 2 + v[3 * i + 2] ** 2);
  return e;
}

export const pct = (v, d = 2) => `${(100 * v).toFixed(d)} %`;

/** `--name value` from argv, or the default. */
export function arg(name, dflt) {
  const k = process.argv.indexOf(`--${name}`);
  return k >= 0 ? process.argv[k + 1] : dflt;
}
