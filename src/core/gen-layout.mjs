#!/usr/bin/env node
// The one table of what the languages of Drape share — TypeScript (core, the GPU driver), AssemblyScript (the
// WebAssembly kernel) and WGSL (through src/gpu/layout.ts, which reads the TypeScript module): type ids, flags,
// limits, the phase schedule every backend follows, and the WebAssembly kernel's control block and substep
// descriptor, whose layouts are made here and nowhere else.
// It writes two modules that say the same thing in two languages:
//   src/core/layout.generated.ts        (TypeScript)
//   src/core/wasm/layout.generated.as.ts (AssemblyScript, imported by xpbd.as.ts)
// Run `npm run gen` (this, then the kernel and the shaders); src/core/layout.test.ts fails when a file is stale.
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
export const TS_FILE = join(here, 'layout.generated.ts');
export const AS_FILE = join(here, 'wasm', 'layout.generated.as.ts');

/** Plain integer constants: [name, value, what it is]. */
export const CONSTANTS = [
  ['STRUCTURAL', 0, 'spring kind: along the grid lines (ClothModel.springKinds, colour batches, the kernel)'],
  ['SHEAR', 1, 'spring kind: across a quad'],
  ['BEND', 2, 'spring kind: skip-one, for bending (no stretch cap)'],
  ['COLLIDER_SPHERE', 1, 'collider type id of a sphere: PosedCollider.typeId, the kernel record\'s TYPE, the GPU Collider.kind'],
  ['COLLIDER_FLOOR', 2, 'collider type id of a floor (a horizontal plane)'],
  ['COLLIDER_PLANE', 3, 'collider type id of a plane: the half-space y < 0 of its own frame'],
  ['COLLIDER_BOX', 4, 'collider type id of a box: half extents along its own axes'],
  ['COLLIDER_CAPSULE', 5, 'collider type id of a capsule: its axis from y = −half length to + half length of its own frame, and radius'],
  ['COLLIDER_CYLINDER', 6, 'collider type id of a closed cylinder: radius and half height, its axis along its own y'],
  ['COLLIDER_MESH', 7, 'collider type id of a triangle mesh (colliders/mesh.ts) in its own frame: its BVH, triangles and pseudo-normals are tables of their own (the GPU\'s meshNodes, meshTriangles), not shape numbers'],
  ['MESH_SIGNED', 1, 'mesh collider triangle flag: the triangle belongs to a closed piece (signed distance by pseudo-normals; else a two-sided open shell)'],
  ['MESH_SHARP_EDGE', 2, 'mesh collider triangle flag: MESH_SHARP_EDGE << e where the triangle owns its edge e (corner e to e + 1) and that edge is sharp (triangle contact)'],
  ['MAX_COLLIDERS', 64, 'most colliders in a scene (schema) and in the kernel\'s control block'],
  ['TRIANGLE_SPREAD_MOST', 2, 'triangle contact: the most any corner moves, as a multiple of what the contact point is to move (phases.ts collideTriangles; on a grid of free particles the spread is at most 1.82, its inverse masses being 4 : 2 : 1 at a corner, an edge and inside, so only a point at or beside a pinned or grabbed corner is held to it)'],
  ['GOLDEN_ITERATIONS', 12, 'golden-section iterations of each of the two nested searches of triangle contact (colliders/convex.ts goldenDeepest, the GPU\'s triangleContact.wgsl)'],
  ['COARSE_OVERSHOOT', 1.5, 'the springs\' coarse correction (solvers/coarse-stretch.ts overshoots, coarse.as.ts, the GPU\'s coarseCheck.wgsl): how far a step solved with an earlier substep\'s factor may overshoot, its Rayleigh quotient under the matrix of the springs\' directions now over the factor\'s, before the matrix is made anew; a step along one direction of a quadratic converges below 2, 1.5 leaves a margin [-]'],
  ['SELF_SKIP_MARGIN', 1e-7, 'self-contact: how far beyond the contact distance a bound must say a pair is before the pair is skipped [m] (self-contact.ts, self-contact.as.ts)'],
  ['SELF_REACH_MARGIN', 0.25, 'self-contact: the least margin of a particle\'s reach box, as a share of the contact distance h [-] (self-contact.ts reachBox, self-search.as.ts reachOf)'],
  ['SELF_EDGE_SHARE', 0.5, 'self-contact: two edges\' contact distance at rest, as a share of the contact distance h; in motion it grows by the sum of the two edges\' largest end moves over the substep, up to h [-] (self-contact.ts resolveEdges and the search\'s edge boxes, self-contact.as.ts, self-search.as.ts, the GPU\'s selfEdges.wgsl)'],
  ['SELF_FRAME_SHARE', 0.5, 'self-contact: a search makes its reach boxes in a frame moving with the cloth where its particles move less than this share as much relative to it as they do at all [-] (self-contact.ts movingFrame, self-search.as.ts)'],
  ['KERNEL_MAX_THREADS', 16, 'most threads one kernel runs (one run counter each in the control block)'],
  ['KERNEL_FLAG_FORCES', 1, 'kernel substep flag: external forces (wind) to integrate'],
  ['KERNEL_FLAG_ACCUMULATE', 2, 'kernel substep flag: λ accumulates across iterations'],
  ['KERNEL_FLAG_STORE_LAMBDA', 4, 'kernel substep flag: λ is written back'],
  ['KERNEL_FLAG_TRACE', 8, 'kernel substep flag: thread 0 lists the phases it runs in TRACE (tests)'],
];

/**
 * A collider record of the WebAssembly kernel's control block (PosedCollider.writeRecord, contact.as.ts), f64s in
 * order: [field, count, what it is]. Generates COLLIDER_RECORD_<FIELD> (its first float) and
 * COLLIDER_RECORD_FLOATS (the record's length).
 */
export const COLLIDER_RECORD = [
  ['TYPE', 1, 'the shape\'s type id (COLLIDER_*)'],
  ['MOVING', 1, '1 where the surface moves over the substep (then RD, OD apply), else 0'],
  ['EXACT', 1, '1 where the collider also has triangle contact (then its particle contact runs in f64, one particle at a time), else 0'],
  ['SHAPE', 3, 'the shape\'s numbers in its own frame (PosedCollider.shapeParams) [m]'],
  ['R', 9, 'rotation of its frame at the substep\'s end, row-major: world = R·local + O'],
  ['O', 3, 'origin of its frame at the substep\'s end [m]'],
  ['RD', 9, 'where a surface point now at p was at the substep\'s start: RD·p + OD (row-major)'],
  ['OD', 3, 'the translation of that map [m]'],
];
{
  let at = 0;
  for (const [field, count, doc] of COLLIDER_RECORD) {
    CONSTANTS.push([`COLLIDER_RECORD_${field}`, at, `collider record field at this f64 offset: ${doc}`]);
    at += count;
  }
  CONSTANTS.push(['COLLIDER_RECORD_FLOATS', at, 'f64 per collider record in the kernel (COLLIDER_RECORD in gen-layout.mjs)']);
}
const C = Object.fromEntries(CONSTANTS.map(([name, value]) => [name, value]));

const BOTH = ['xpbd', 'mass-spring'];
/**
 * The phase schedule of one frame, in order: [name, scope, solvers, when, repeat, what it does]. A phase's id is its
 * row (0, 1, …), so ascending ids are the order and a set of phases is a bit mask. `scope`: 'frame-start' (once,
 * before the substeps), 'substep' (every substep), 'frame-end' (once, after them). `solvers`: the solver types whose
 * frame has it. `when`: 'always', 'wind' (the wind blows), 'grab' (a particle is grabbed), 'carried' (a collider carries pins), 'triangles' (a collider needs triangle contact at this mesh size: phases.ts needsTriangleContact), 'global' or 'local' (solver.stretch is 'global', or 'gauss-seidel' or 'two-level'), 'coarse' (solver.stretch is 'two-level'), 'stencils' and 'stencils-global' (a stencil bending model, solver.bendingSolve 'gauss-seidel' or 'global'), 'self' (solver.selfContact). `repeat`: the solvers
 * for which it runs solver.iterations passes per substep (else one). Every backend walks this list (core/frame.ts
 * runFrame); docs/architecture.md says where a new phase goes in each.
 */
export const PHASES = [
  ['begin', 'frame-start', BOTH, 'always', [], 'effective inverse masses (0 pinned or grabbed), tethers if the pins changed, x_prev = x − h·v'],
  ['wind', 'substep', BOTH, 'wind', [], 'wind force per triangle on the air velocity relative to it, into the force accumulator'],
  ['springForces', 'substep', ['mass-spring'], 'always', [], 'Hooke spring forces with damping along each spring'],
  ['integrate', 'substep', BOTH, 'always', [], 'position Verlet (Taylor start) with gravity and any accumulated forces'],
  ['carry', 'substep', BOTH, 'carried', [], 'particles pinned to a collider carried to where it is at the end of the substep'],
  ['grab', 'substep', BOTH, 'grab', [], 'the grabbed particle carried part of the way to its target'],
  ['globalStretch', 'substep', ['xpbd'], 'global', ['xpbd'], 'the springs solved together: a local/global pass (Projective Dynamics) on the prefactored system'],
  ['coarseStretch', 'substep', ['xpbd'], 'coarse', [], 'the springs\' multipliers from one coarse solve over aggregates of springs (cells of the cloth by direction), where the distance pass goes on from'],
  ['distance', 'substep', ['xpbd'], 'local', ['xpbd'], 'XPBD distance constraints, colour batch by colour batch'],
  ['bending', 'substep', ['xpbd'], 'stencils', ['xpbd'], 'XPBD bending on linear stencils (the hinges of Bergou et al. 2006 or the cotangent Laplacian at the vertices), colour batch by colour batch'],
  ['globalBending', 'substep', ['xpbd'], 'stencils-global', [], 'the bending stencils solved together: their backward-Euler step, one solve of the prefactored system'],
  ['tethers', 'substep', BOTH, 'local', [], 'long-range attachments to the nearest pin'],
  ['stretchLimit', 'substep', BOTH, 'local', ['mass-spring'], 'stretch limiting of structural and shear springs'],
  ['selfContact', 'substep', BOTH, 'self', [], 'the cloth against itself: each particle against the triangles near it, side memory and friction (self-contact.ts)'],
  ['contact', 'substep', BOTH, 'always', [], 'particle contact with friction against every collider, in order'],
  ['contactTriangles', 'substep', BOTH, 'triangles', [], 'triangle contact with friction against every collider whose surface can poke between the vertices at this mesh size'],
  ['velocities', 'frame-end', BOTH, 'always', [], 'v = (x − x_prev)/h of the last substep'],
];

/**
 * The word describing one kernel substep (the DESC control field, xpbd.as.ts describe()): [field, first bit, bits,
 * what it is]. Helpers read it in one atomic load.
 */
export const DESC = [
  ['SEQ', 0, 32, 'sequence number of the substep\'s first phase'],
  ['ITERATIONS', 32, 6, 'distance constraint passes'],
  ['THREADS', 38, 8, 'T, the threads of the substep'],
  ['PHASES', 46, 18, 'the phases it runs, a bit per phase id'],
];
if (PHASES.length > DESC.find(([name]) => name === 'PHASES')[2]) throw new Error('gen-layout: more phases than the descriptor has bits');
const descBits = (field) => DESC.find(([name]) => name === field)[2];
if (C.KERNEL_MAX_THREADS >= 2 ** descBits('THREADS')) throw new Error('gen-layout: KERNEL_MAX_THREADS does not fit the descriptor');

/** PHASE_WIND for 'wind', PHASE_STRETCH_LIMIT for 'stretchLimit': the AssemblyScript constant of a phase. */
const phaseConstant = (name) => `PHASE_${name.replace(/[A-Z]/g, (c) => `_${c}`).toUpperCase()}`;

/**
 * The WebAssembly kernel's control block, in order: [name, type, count, what it is, line?]. Types: i32, i64, f64.
 * `line` puts the field on its own 64-byte cache line (words threads write to while others read theirs).
 */
export const CONTROL = [
  ['DISPATCH', 'i32', 1, 'bumped by thread 0 to start a substep on the helpers (they sleep on it)'],
  ['DISPATCH_SLEEPERS', 'i32', 1, 'helpers asleep waiting for a dispatch'],
  ['THREADS', 'i32', 1, 'T, the threads of a substep; 1 makes thread 0 run it alone (helpers stay asleep)'],
  ['COMMAND', 'i32', 1, '1 substep, 2 exit'],
  ['GRABBED', 'i32', 1, 'grabbed particle or -1'],
  ['FLAGS', 'i32', 1, 'KERNEL_FLAG_* of this substep'],
  ['ITERATIONS', 'i32', 1, 'distance constraint passes per substep (at most KERNEL_MAX_ITERATIONS: the DESC field)'],
  ['SUBSTEP_PHASES', 'i32', 1, 'the phases the next substep() runs, a bit per phase id (consecutive in the schedule)'],
  ['COLLIDERS', 'i32', 1, 'collider records in use'],
  ['STENCILS', 'i32', 1, 'the bending stencils the bending phase solves: 0 none, 1 the hinges, 2 the Laplacian (model.stencils)'],
  ['READY', 'i32', 1, 'helpers that entered helperLoop'],
  ['SPIN_LIMIT', 'i32', 1, 'polls of a word before a waiting thread sleeps'],
  ['DESC', 'i64', 1, 'the dispatched substep, described by the DESC_* fields (xpbd.as.ts describe())'],
  ['TRACE_COUNT', 'i32', 1, 'phases listed in TRACE by the last substep() with KERNEL_FLAG_TRACE'],
  ['TRACE', 'i32', PHASES.length, 'the ids of those phases, in the order thread 0 ran them'],
  ['H', 'f64', 1, 'substep length [s]'],
  ['TAYLOR', 'f64', 1, '½ on the very first substep (Taylor start), else 1'],
  ['GRAVITY', 'f64', 3, 'gravitational acceleration [m/s²]'],
  ['GRAB_AT', 'f64', 3, 'where the grabbed particle is this substep [m]'],
  ['STRETCH', 'f64', 1, 'stretchFactor [-]'],
  ['DAMPING', 'f64', 1, 'damping β [N·s/m]'],
  ['THICKNESS', 'f64', 1, 'contact thickness [m]'],
  ['FRICTION', 'f64', 1, 'kinetic friction coefficient [-]'],
  ['STATIC_FRICTION', 'f64', 1, 'static friction coefficient [-]'],
  ['DEPENETRATION', 'f64', 1, 'depenetrationSpeed [m/s]'],
  ['WIND', 'f64', 3, 'the wind\'s velocity this substep [m/s] (wind.ts windVelocity at the substep\'s start)'],
  ['AIR_K', 'f64', 1, 'the air\'s ¼ρ/3 [kg/m³] (accumulateWind: ½ρ·|v|·(v·n)·area shared by three particles, |N| = 2·area)'],
  ['TRIANGLE_REACH', 'f64', 1, 'triangle contact: the thickness and two longest rest edges, the farthest a triangle point is from its first vertex [m]'],
  ['TRIANGLE_RECOVER', 'f64', 1, 'triangle contact: the most of an overlap a triangle undoes in a substep, depenetrationSpeed·h over the most triangles at a particle [m]'],
  ['COLLIDER_RECORDS', 'f64', C.MAX_COLLIDERS * C.COLLIDER_RECORD_FLOATS, 'MAX_COLLIDERS records of COLLIDER_RECORD_FLOATS (COLLIDER_RECORD: type id, moving, shape numbers, R, O, RD, OD), written per substep'],
  ['PHASE', 'i32', 1, 'sequence number of the open phase (grows by one per phase, wraps)', true],
  ['DONE', 'i32', 1, 'chunks of the open phase completed and reported', true],
  ['PHASE_SLEEPERS', 'i32', 1, 'threads asleep waiting for a phase', true],
  ['RUNS', 'i64', C.KERNEL_MAX_THREADS, 'per thread, on its own line: (phase << 32) | next chunk of its run (stride RUN_STRIDE)', true],
];
/** bytes between run counters: a cache line each */
const RUN_STRIDE = 64;

const SIZE = { i32: 4, i64: 8, f64: 8 };

/** Byte offsets of the control block's fields, and its size (a multiple of 64). */
export function layoutControl() {
  const offsets = {};
  let at = 0;
  for (const [name, type, count, , line] of CONTROL) {
    const align = line ? 64 : SIZE[type];
    at = Math.ceil(at / align) * align;
    offsets[name] = at;
    at += name === 'RUNS' ? RUN_STRIDE * count : line ? 64 : SIZE[type] * count;
  }
  return { offsets, bytes: Math.ceil(at / 64) * 64 };
}

/** A number, string or list of strings as TypeScript source. */
const tsValue = (v) => Array.isArray(v) ? `[${v.map(tsValue).join(', ')}]` : typeof v === 'string' ? `'${v.replace(/'/g, "\\'")}'` : String(v);

const HEADER = 'Generated by src/core/gen-layout.mjs from its tables: do not edit; run `npm run gen`.';

/** The two modules' text: { ts, as }. */
export function generateLayoutModules() {
  const { offsets, bytes } = layoutControl();
  const ts = [`// ${HEADER}`, ''];
  const as = [`// ${HEADER}`, ''];
  for (const [name, value, doc] of CONSTANTS) {
    ts.push(`/** ${doc} */`, `export const ${name} = ${value};`);
    as.push(`/** ${doc} */`, `export const ${name}: ${Number.isInteger(value) ? 'i32' : 'f64'} = ${value};`);
  }

  ts.push('', '/** Phase ids, in schedule order (PHASES in gen-layout.mjs): a set of phases is a mask of `1 << id`. */', 'export const PHASE = {');
  as.push('', '// Phase ids, in schedule order (PHASES in gen-layout.mjs): a set of phases is a mask of 1 << id.');
  PHASES.forEach(([name, scope, , , , doc], id) => {
    ts.push(`  /** ${scope}: ${doc} */`, `  ${name}: ${id},`);
    as.push(`/** ${scope}: ${doc} */`, `export const ${phaseConstant(name)}: i32 = ${id};`);
  });
  ts.push('} as const;', '/** Phases in the schedule. */', `export const PHASE_COUNT = ${PHASES.length};`);
  as.push('/** Phases in the schedule. */', `export const PHASE_COUNT: i32 = ${PHASES.length};`);
  ts.push('/** The phase schedule of one frame, in order (PHASES in gen-layout.mjs; core/schedule.ts gives it its types). */', 'export const SCHEDULE = [');
  PHASES.forEach(([name, scope, solvers, when, repeat, doc], id) => {
    const row = { id, name, scope, solvers, when, repeat, doc };
    ts.push(`  { ${Object.entries(row).map(([k, v]) => `${k}: ${tsValue(v)}`).join(', ')} },`);
  });
  ts.push('] as const;');
  const iterationBits = DESC.find(([name]) => name === 'ITERATIONS')[2];
  ts.push(`/** Most distance passes per substep the kernel's substep descriptor holds (its ITERATIONS field). */`,
    `export const KERNEL_MAX_ITERATIONS = ${2 ** iterationBits - 1};`);
  as.push('', '// The substep descriptor (DESC in gen-layout.mjs): first bit and mask of each field.');
  for (const [name, shift, bits, doc] of DESC) {
    as.push(`/** ${doc}: first bit */`, `export const DESC_${name}_SHIFT: i64 = ${shift};`);
    as.push(`/** ${doc}: mask after the shift (${bits} bits) */`, `export const DESC_${name}_MASK: i64 = ${2 ** bits - 1};`);
  }

  ts.push('', '/** Byte offsets of the WebAssembly kernel\'s control block (see CONTROL in gen-layout.mjs). */', 'export const CTRL = {');
  as.push('', '// Byte offsets of the control block (from CTRL = 0).');
  for (const [name, type, count, doc] of CONTROL) {
    const what = `${type}${count > 1 ? ` × ${count}` : ''}: ${doc}`;
    ts.push(`  /** ${what} */`, `  ${name}: ${offsets[name]},`);
    as.push(`/** ${what} */`, `export const ${name}: usize = ${offsets[name]};`);
  }
  ts.push('} as const;', '', '/** Bytes of the control block; the kernel\'s arrays follow it. */', `export const CTRL_BYTES = ${bytes};`);
  ts.push('/** Bytes between the threads\' run counters. */', `export const RUN_STRIDE = ${RUN_STRIDE};`, '');
  as.push('/** Bytes between the threads\' run counters. */', `export const RUN_STRIDE: usize = ${RUN_STRIDE};`, '');
  return { ts: ts.join('\n'), as: as.join('\n') };
}

/** Whether the files on disk are what the tables say. */
export function layoutFilesCurrent() {
  const { ts, as } = generateLayoutModules();
  const read = (f) => { try { return readFileSync(f, 'utf8'); } catch { return ''; } };
  return read(TS_FILE) === ts && read(AS_FILE) === as;
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) {
  const { ts, as } = generateLayoutModules();
  writeFileSync(TS_FILE, ts);
  writeFileSync(AS_FILE, as);
  console.log(`wrote ${TS_FILE}\nwrote ${AS_FILE}`);
}
