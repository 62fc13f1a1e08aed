#!/usr/bin/env node
// Issue 10 (converged stretch and bending): the Projective Dynamics prototype (scripts/pd-solver.mjs) on the two
// setups of scripts/solver-study-common.mjs, over the model and parameters the library builds for the same scenes.
//
//   hanging: a 1 m sheet pinned along its top row (rubber k = 600 N/m, ρ_A = 0.38; cotton k = 8600, ρ_A = 0.12):
//     elongation / theory ρ_A g L²/(2k), the middle half's strain / theory, and elongation / the discrete model's
//     converged equilibrium (a static PD solve, no inertia, 200 local/global iterations: what any converged solver
//     of this spring grid must give; the shear springs make it stiffer than k alone). Frames to settle (as
//     hanging-strain.mjs: chunks of 30 frames, drift < 0.1 % and kinetic energy < 1e-6·mgL), ms per frame while
//     settling, factor time, envelope size.
//   cantilever: the Peirce cantilever with hinge bending, 10 s, chord angle → c / c (1.00 wanted, ±10 %).
//   timing: ms per frame of the direct solver at 32², 64², 128² and of Chebyshev-Jacobi.
//
//   newton: the cantilever's converged answer for the same discrete energy (static Newton): the model's own error.
//   fabrics: the built-in cantilever scene's converged answer for every named fabric (static Newton), not in 'all'.
//   gn: the built-in cantilever scene stepped by the Gauss–Newton prototype (gn-solver.mjs), not in 'all'.
//   gn-hanging: the prototype on a hanging sheet and on a sheet swinging from one corner, not in 'all'.
//
// Parts (--part): hanging, cantilever, newton, all (default: those three, ~3 min on a free core; the 128² rows are
// most of it), jacobi (Chebyshev-accelerated Jacobi on both setups; not in 'all').
//   npx tsc -p tsconfig.build.json && node scripts/pd-study.mjs [--part hanging] [--faces 16,32,64,128]
//       [--settings 1x3,1x10] [--fabrics rubber,cotton] [--bending springs|hinges|laplacian (the hanging sheet's bending model)]
//       [--stencils hinges|laplacian (the cantilever's bending model in the newton part)]
//       [--clamp-hinges held|whole (fabrics: the hinges beside the clamp as the global bending step counts them, the
//       default, or whole as the sweep does)]
import { FABRICS, FABRIC_NAMES, builtinScene, measureTest, modelFor, resolveParams, scenePins, setScenePath, validateScene } from '../dist/core/index.js';
import { GNSolver } from './gn-solver.mjs';
import { PDSolver, newtonStatic, withHeldHinges } from './pd-solver.mjs';
import {
  arg, cantileverScene, hangingScene, hangingTheory, kinetic, measureCantilever, measureHanging, pct, CANTILEVER,
} from './solver-study-common.mjs';

const part = arg('part', 'all');

function solverFor(scene, opts, held = false) {
  const model = modelFor(scene);
  let params = resolveParams(model, scene);
  const pinned = new Uint8Array(model.particleCount);
  for (const i of scenePins(model, scene)) pinned[i] = 1;
  if (held) params = withHeldHinges(model, params, pinned);
  return new PDSolver(model, params, pinned, model.restPositions, opts);
}

/** Runs frames until settled (or maxFrames): returns { frames, ke, drift, ms }. */
function settle(pd, faces, maxFrames, mgl) {
  const t0 = performance.now();
  let frames = 0, prev = NaN, drift = NaN, ke = NaN;
  while (frames < maxFrames) {
    for (let f = 0; f < 30; f++) pd.frame();
    frames += 30;
    const m = measureHanging(pd.x, faces);
    ke = kinetic(pd.v, pd.mass);
    drift = (m.elongation - prev) / m.elongation;
    prev = m.elongation;
    if (frames >= 60 && Math.abs(drift) < 0.001 && ke < 1e-6 * mgl) break;
  }
  return { frames, ke, drift, ms: (performance.now() - t0) / frames };
}

function hanging(global) {
  const fabrics = arg('fabrics', 'rubber,cotton').split(',');
  const facesList = arg('faces', global === 'direct' ? '16,32,64,128' : '16,32,64').split(',').map(Number);
  const settings = arg('settings', global === 'direct' ? '1x3,1x10' : '1x20,1x50,4x20').split(',').map((s) => s.split('x').map(Number));
  console.log(`\nPD (${global === 'direct' ? 'direct envelope Cholesky, RCM order' : 'Chebyshev-accelerated Jacobi'}) hanging sheet`);
  for (const fabric of fabrics) {
    const th = hangingTheory(fabric);
    console.log(`\n${fabric}: theory elongation ${(1000 * th.elongation).toFixed(3)} mm`);
    console.log('| faces | substeps × iterations | converged discrete [mm] (/theory) | frames | KE [J] | elongation [mm] | ratio to theory | middle strain ratio | ratio to converged | ms/frame | factor ms | envelope | ρ |');
    console.log('|---|---|---|---|---|---|---|---|---|---|---|---|---|');
    for (const faces of facesList) {
      const scene = hangingScene(fabric, faces, 1, 1, arg('bending', 'springs')); // default 'springs': the energy of XPBD's run
      const ref = solverFor(scene, { static: true, iterations: 200 });
      ref.frame();
      const refEl = measureHanging(ref.x, faces).elongation;
      const mgl = scene.material.mass * 9.81;
      for (const [substeps, iterations] of settings) {
        const pd = solverFor(scene, { substeps, iterations, global });
        const s = settle(pd, faces, faces >= 128 ? 240 : 600, mgl);
        const m = measureHanging(pd.x, faces);
        console.log(`| ${faces}² | ${substeps} × ${iterations} | ${(1000 * refEl).toFixed(3)} (${(refEl / th.elongation).toFixed(2)}) | ${s.frames} | ${s.ke.toExponential(1)} | ` +
          `${(1000 * m.elongation).toFixed(3)} | ${(m.elongation / th.elongation).toFixed(2)} | ${(m.strainMid / th.strainMid).toFixed(2)} | ` +
          `${(m.elongation / refEl).toFixed(3)} | ${s.ms.toFixed(1)} | ${pd.factorMs.toFixed(0)} | ${pd.envelope ?? '-'} | ${pd.opts.rho?.toFixed(5) ?? '-'} |`);
      }
    }
  }
}

function cantilever(global) {
  const facesList = arg('faces', '16,32,64').split(',').map(Number);
  const settings = arg('settings', global === 'direct' ? '1x5,1x10,1x20,4x10' : '1x20,1x50,1x100').split(',').map((s) => s.split('x').map(Number));
  console.log(`\nPD (${global}) Peirce cantilever, hinges: B = ${CANTILEVER.B.toExponential(3)} N·m, c = ${(100 * CANTILEVER.c).toFixed(2)} cm; chord angle (41.5° wanted) → c / c, ms per frame`);
  console.log(`| faces | ${settings.map(([s, i]) => `${s} × ${i}`).join(' | ')} |`);
  console.log(`|---|${settings.map(() => '---').join('|')}|`);
  for (const faces of facesList) {
    const cells = settings.map(([substeps, iterations]) => {
      const { scene, free, L } = cantileverScene(faces, 1, 1, 'hinges');
      const pd = solverFor(scene, { substeps, iterations, global });
      const t0 = performance.now();
      for (let f = 0; f < 600; f++) pd.frame();
      const ms = (performance.now() - t0) / 600;
      const m = measureCantilever(pd.x, faces, free, L);
      return `${m.deg.toFixed(1)}° → ${m.ratio.toFixed(2)} (${ms.toFixed(1)} ms)`;
    });
    console.log(`| ${faces}² | ${cells.join(' | ')} |`);
  }
}

/**
 * The cantilever's converged answer for the same discrete energy (hinges, springs, gravity): Newton's method on the
 * static problem (pd-solver.mjs newtonStatic), started from where PD at 10 × 10 is after 10 s. Tells whether a miss
 * is the model's or the solver's.
 */
function newtonCantilever() {
  const facesList = arg('faces', '16,32,64').split(',').map(Number);
  console.log(`\nCantilever (${arg('stencils', 'hinges')}), converged static equilibrium of the discrete model (Newton, from PD 10 × 10 after 10 s)`);
  console.log('| faces | chord angle | c / c | Newton iterations | |gradient| [N] | seconds |');
  console.log('|---|---|---|---|---|---|');
  for (const faces of facesList) {
    const { scene, free, L } = cantileverScene(faces, 1, 1, arg('stencils', 'hinges'));
    const pd = solverFor(scene, { substeps: 10, iterations: 10 });
    for (let f = 0; f < 600; f++) pd.frame();
    const t0 = performance.now();
    const r = newtonStatic(pd, 150);
    const m = measureCantilever(pd.x, faces, free, L);
    console.log(`| ${faces}² | ${m.deg.toFixed(1)}° | ${m.ratio.toFixed(3)} | ${r.iterations} | ${r.gnorm.toExponential(1)} | ${((performance.now() - t0) / 1000).toFixed(1)} |`);
  }
}

/**
 * The built-in `cantilever` scene's converged answer for every named fabric (static Newton on its discrete energy,
 * from the flat strip): the bending length the scene's own measurement reads, as a ratio to c = (B/(ρ_A·g))^(1/3),
 * at several resolutions. What any solver that converges would report; the model's own error.
 */
function fabricCantilevers() {
  const facesList = arg('faces', '16,32,64').split(',').map(Number);
  const stencils = arg('stencils', 'hinges'), held = arg('clamp-hinges', 'held') === 'held';
  console.log(`\nThe cantilever scene (${stencils}${stencils === 'hinges' ? `, the clamp's hinges counted ${held ? 'on their free side (heldHingeShare)' : 'whole'}` : ''}), converged static equilibrium of the discrete model (Newton from the flat strip): c / c_theory`);
  console.log(`| fabric | c theory [cm] | ${facesList.map((f) => `${f} faces: chord → c / c_theory (Newton iterations)`).join(' | ')} |`);
  console.log(`|---|---|${facesList.map(() => '---|').join('')}`);
  for (const fabric of arg('fabrics', FABRIC_NAMES.join(',')).split(',')) {
    const f = FABRICS[fabric];
    const c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
    const cells = [];
    for (const faces of facesList) {
      let scene = setScenePath(builtinScene('cantilever'), 'material.fabric', fabric);
      scene = validateScene({ ...scene, cloth: { ...scene.cloth, resolution: faces }, solver: { ...scene.solver, bending: stencils } });
      const pd = solverFor(scene, { substeps: 1, iterations: 1 }, held);
      const r = newtonStatic(pd, 300);
      const t = measureTest(pd.model, { positions: pd.x, pinned: pd.pinned }, scene);
      cells.push(`${t.chordAngle.toFixed(1)}° → ${(t.bendingLength / c).toFixed(3)} (${r.iterations})`);
    }
    console.log(`| ${fabric} | ${(100 * c).toFixed(2)} | ${cells.join(' | ')} |`);
  }
}

/**
 * The cantilever scene for each fabric with the Gauss–Newton prototype (gn-solver.mjs) at the default 20 substeps:
 * where the strip is after the scene's 6 s, how far it still swings over the sixth second (nothing damps its
 * bending), the conjugate gradient iterations a substep took, and ms per frame.
 */
function gnCantilevers() {
  const facesList = arg('faces', '32').split(',').map(Number);
  const stencils = arg('stencils', 'hinges');
  console.log(`\nThe cantilever scene (${stencils}), Gauss–Newton prototype, ${arg('substeps', '20')} substeps × 1, conjugate gradients to 1e-3, preconditioner ${arg('precondition', 'diagonal')}`);
  console.log('| fabric | faces | chord at 6 s → c / c_theory | chord over the sixth second | CG iterations per substep | ms/frame |');
  console.log('|---|---|---|---|---|---|');
  for (const fabric of arg('fabrics', FABRIC_NAMES.join(',')).split(',')) {
    const f = FABRICS[fabric];
    const c = Math.cbrt(f.bendingRigidity / (f.arealDensity * 9.81));
    for (const faces of facesList) {
      let scene = setScenePath(builtinScene('cantilever'), 'material.fabric', fabric);
      scene = validateScene({ ...scene, cloth: { ...scene.cloth, resolution: faces }, solver: { ...scene.solver, bending: stencils } });
      const model = modelFor(scene);
      const params = resolveParams(model, scene);
      const pinned = new Uint8Array(model.particleCount);
      for (const i of scenePins(model, scene)) pinned[i] = 1;
      const gn = new GNSolver(model, params, pinned, { substeps: Number(arg('substeps', '20')), iterations: 1, precondition: arg('precondition', 'diagonal') });
      const read = () => measureTest(model, { positions: gn.x, pinned }, scene);
      const t0 = performance.now();
      let lo = Infinity, hi = -Infinity;
      for (let fr = 0; fr < 360; fr++) {
        gn.frame();
        if (fr >= 300) { const a = read().chordAngle; lo = Math.min(lo, a); hi = Math.max(hi, a); }
      }
      const ms = (performance.now() - t0) / 360;
      const t = read();
      console.log(`| ${fabric} | ${faces} | ${t.chordAngle.toFixed(1)}° → ${(t.bendingLength / c).toFixed(3)} | ${lo.toFixed(1)}–${hi.toFixed(1)}° | ${(gn.cgIterations / gn.substepsRun).toFixed(1)} | ${ms.toFixed(0)} |`);
    }
  }
}

/**
 * The Gauss–Newton prototype where its preconditioner is furthest from the truth: a hanging sheet (the stretch
 * converged?) and a horizontal sheet held by one corner, which falls and swings through 90° (every spring turned far
 * from its rest direction). Conjugate gradient iterations per substep and ms per frame at --substeps; --refresh N
 * refactors the 'woodbury' preconditioner at the cloth's directions after a substep that took more than N;
 * --precondition warped or primal: H₀ turned particle by particle (gn-solver.mjs; docs/physics.md, "Turning the rest
 * preconditioner does not help").
 */
function gnHanging() {
  const substeps = Number(arg('substeps', '5'));
  const precondition = arg('precondition', 'woodbury');
  console.log(`\nGauss–Newton prototype, ${substeps} substeps × 1, preconditioner ${precondition}, refactored past ${arg('refresh', 'Infinity')} iterations`);
  console.log('| case | faces | result | CG iterations per substep (most in a frame) | ms/frame |');
  console.log('|---|---|---|---|---|');
  for (const faces of arg('faces', '32,64').split(',').map(Number)) {
    for (const fabric of ['rubber', 'cotton']) {
      const scene = hangingScene(fabric, faces, substeps, 1, 'hinges');
      const model = modelFor(scene), params = resolveParams(model, scene);
      const pinned = new Uint8Array(model.particleCount);
      for (const i of scenePins(model, scene)) pinned[i] = 1;
      const gn = new GNSolver(model, params, pinned, { substeps, iterations: 1, precondition });
      const t0 = performance.now();
      let most = 0;
      for (let f = 0; f < 180; f++) { const c0 = gn.cgIterations; gn.frame(); most = Math.max(most, (gn.cgIterations - c0) / substeps); }
      const ratio = measureHanging(gn.x, faces).elongation / hangingTheory(fabric).elongation;
      console.log(`| hanging ${fabric}, 3 s | ${faces}² | elongation / theory ${ratio.toFixed(3)} | ${(gn.cgIterations / gn.substepsRun).toFixed(1)} (${most.toFixed(1)}) | ${((performance.now() - t0) / 180).toFixed(0)} |`);
    }
    // cotton held by one corner, horizontal at the start: it falls and swings down through 90°
    const scene = validateScene({
      cloth: { resolution: faces, width: 1, height: 1, position: [0, 1.5, 0] },
      material: { fabric: 'cotton' }, solver: { substeps, bending: 'hinges', selfContact: false }, colliders: [], pins: ['top-left'],
    });
    const model = modelFor(scene), params = resolveParams(model, scene);
    const pinned = new Uint8Array(model.particleCount);
    for (const i of scenePins(model, scene)) pinned[i] = 1;
    const gn = new GNSolver(model, params, pinned, { substeps, iterations: 1, precondition, refresh: Number(arg('refresh', 'Infinity')) });
    const t0 = performance.now();
    let most = 0, finite = true;
    // (it swings down through the bottom and up the other side within the 2 s: a pendulum the air does not damp)
    for (let f = 0; f < 120; f++) { const c0 = gn.cgIterations; gn.frame(); most = Math.max(most, (gn.cgIterations - c0) / substeps); }
    for (const v of gn.x) if (!Number.isFinite(v)) finite = false;
    console.log(`| cotton from one corner, 2 s | ${faces}² | ${finite ? 'finite' : 'not finite'}${gn.refactors ? `, ${gn.refactors} refactors` : ''} | ${(gn.cgIterations / gn.substepsRun).toFixed(1)} (${most.toFixed(1)}) | ${((performance.now() - t0) / 120).toFixed(0)} |`);
  }
}

if (part === 'fabrics') fabricCantilevers();
if (part === 'gn-hanging') gnHanging();
if (part === 'gn') gnCantilevers();
if (part === 'all' || part === 'hanging') hanging('direct');
if (part === 'all' || part === 'newton') newtonCantilever();
if (part === 'all' || part === 'cantilever') cantilever('direct');
if (part === 'jacobi') { hanging('jacobi'); cantilever('jacobi'); }
