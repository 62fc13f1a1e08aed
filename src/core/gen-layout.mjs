#!/usr/bin/env node
// The one table of what the languages of Drape share — TypeScript (core, the GPU driver), AssemblyScript (the
// WebAssembly kernel) and WGSL (through src/gpu/layout.ts, which reads the TypeScript module): type ids, flags,
// limits, and the WebAssembly kernel's control block, whose byte offsets are laid out here and nowhere else.
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
  ['COLLIDER_SPHERE', 1, 'collider type id of a sphere: ColliderShape.kernelRecord[0], the GPU Collider.kind'],
  ['COLLIDER_FLOOR', 2, 'collider type id of a floor (a horizontal plane)'],
  ['MAX_COLLIDERS', 64, 'most colliders in a scene (schema), in the kernel\'s control block and in the GPU uniforms'],
  ['COLLIDER_RECORD_FLOATS', 6, 'f64 per collider record in the kernel: type id, then up to five shape numbers'],
  ['KERNEL_MAX_THREADS', 16, 'most threads one kernel runs (one run counter each in the control block)'],
  ['KERNEL_FLAG_FORCES', 1, 'kernel substep flag: external forces (wind) to integrate'],
  ['KERNEL_FLAG_CONTACT', 2, 'kernel substep flag: particle contact runs in the kernel'],
  ['KERNEL_FLAG_ACCUMULATE', 4, 'kernel substep flag: λ accumulates across iterations'],
  ['KERNEL_FLAG_STORE_LAMBDA', 8, 'kernel substep flag: λ is written back'],
];
const C = Object.fromEntries(CONSTANTS.map(([name, value]) => [name, value]));

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
  ['ITERATIONS', 'i32', 1, 'constraint passes per substep (8 bits in the phase list)'],
  ['COLLIDERS', 'i32', 1, 'collider records in use'],
  ['READY', 'i32', 1, 'helpers that entered helperLoop'],
  ['SPIN_LIMIT', 'i32', 1, 'polls of a word before a waiting thread sleeps'],
  ['DESC', 'i64', 1, 'the dispatched substep\'s phase list (xpbd.as.ts describe())'],
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
  ['COLLIDER_RECORDS', 'f64', C.MAX_COLLIDERS * C.COLLIDER_RECORD_FLOATS, 'MAX_COLLIDERS records of COLLIDER_RECORD_FLOATS: type id, then cx, cy, cz, r (sphere) or height (floor)'],
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

const HEADER = 'Generated by src/core/gen-layout.mjs from its tables: do not edit; run `npm run gen`.';

/** The two modules' text: { ts, as }. */
export function generateLayoutModules() {
  const { offsets, bytes } = layoutControl();
  const ts = [`// ${HEADER}`, ''];
  const as = [`// ${HEADER}`, ''];
  for (const [name, value, doc] of CONSTANTS) {
    ts.push(`/** ${doc} */`, `export const ${name} = ${value};`);
    as.push(`/** ${doc} */`, `export const ${name}: i32 = ${value};`);
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
