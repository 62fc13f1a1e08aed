/**
 * `drape`: the headless front end over the same core and scenes as the app.
 *   drape run [SCENE|file.json] [--frames N] [--solver S] [--backend cpu] [--set PATH=VALUE]… [--json] [--export out.obj|out.glb]
 *             [--bake out.glb [--bake-stride K]]
 *   drape scenes | drape bench [...] | drape schema
 * Bad input exits with code 2 and one line on stderr; nothing prints a stack trace.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { basename, resolve } from 'node:path';
import { parseArgs } from 'node:util';
import {
  bakeBytes, builtinScene, FABRIC_NAMES, exportCloths, FRAME_DT, isBuiltinScene, parseSetValue, plainText, safeJson, SCENE_NAMES, sceneDocument, sceneSchema,
  modelCloths, setScenePath, Simulation, toGLB, toMTL, toOBJ, type GlbBake, type MeshResolver, type Scene, type SimulationOptions,
} from '../core/index.js';
import { EXIT, UsageError } from './errors.js';
import { checkOutputPath } from './files.js';
import { loadSceneFile, meshReader } from './node.js';
import { gpuRefusal, openGpu, type Gpu } from './gpu.js';
import { cpuOptions, runBench, runGpuBench, runHangingBench, runSceneBench, runSelfContactBench } from './bench.js';
import { maxThreads } from './threads.js';

const HELP: Record<string, string> = {
  main: `drape — real-time cloth simulation, headless

Usage:
  drape run [SCENE|file.json] [options]   simulate a scene and print a summary
  drape scenes                            list the built-in scenes
  drape bench [options]                   speed benchmark (CPU solvers against JoltPhysics.js)
  drape schema                            print the scene JSON schema
  drape <command> --help                  options of a command

Built-in scenes: ${SCENE_NAMES.join(', ')}`,
  run: `drape run [SCENE|file.json] [options]

Simulates a built-in scene (default: custom) or a scene file for N frames of 1/60 s.
  --frames N            frames to simulate (default: the scene's duration, 3 s unless it says; 0 reports the start)
  --solver S            xpbd | mass-spring (same as --set solver.type=S)
  --backend B           cpu (default) or gpu (WebGPU through Dawn; XPBD only)
  --kernel K            CPU XPBD kernel: wasm (WebAssembly SIMD, the default where available) or ts
  --threads N           threads of the wasm kernel (default: automatic, the cores available up to 8, but one
                        for cloths under 2500 particles; more than the cores is clamped)
  --set PATH=VALUE      change any scene path, e.g. material.fabric=silk, wind.direction=[1,0,0],
                        colliders=[] ; VALUE is JSON when it parses, else a string (repeatable)
  --json                print exactly one JSON object
  --export FILE         write the cloths at the last frame: FILE.obj (Wavefront, with FILE.mtl beside it) or
                        FILE.glb (binary glTF): positions, texture coordinates, normals, each fabric's material
  --bake FILE.glb       write the run as an animated binary glTF: one morph target per baked frame, played
                        by the file's animation at the frames' times (needs --frames ≥ 1; CPU backend)
  --bake-stride K       bake every K-th frame (default 1; the last frame always): a bake is about
                        24 bytes per vertex per baked frame (a 64² cloth: 101 kB a frame)
  --specimens N         a standard test read on N specimens, as the standards ask (BS 5058: three): the scene's,
                        then cloth.perturbation.seed + 1 … + N − 1 (the cusick scene's 1 mm waviness; elsewhere
                        set its amplitude); each specimen's test and their mean (--export, --bake: the first's)
A scene with a resolutionSweep (e.g. 'resolution') runs once per resolution unless cloth.resolution is set.`,
  scenes: `drape scenes [--json]\n\nLists the built-in scenes with their descriptions.`,
  bench: `drape bench [options]

Times the CPU solvers on a cloth dropped on a sphere and a floor, with JoltPhysics.js on the same cloth.
  --sizes A,B,…         particles per side (default 64,128; with --backend gpu 64,128,256,512,1024)
  --substeps N          XPBD substeps per 1/60 s frame; Jolt iterations (default 10)
  --frames N            timed frames per run (default 120), after --warmup N frames (default 30)
  --backend B           cpu (default: both CPU solvers and JoltPhysics.js) or gpu (the WebGPU solver, with
                        the CPU XPBD solver beside it up to 256 per side, and the memory-bandwidth floor)
  --threads N           threads of Drape's wasm XPBD kernel (default: automatic, the cores available up to 8, one
                        for a small cloth); a 1-thread and a TypeScript column are printed too
  --scenes A,B,…        time these built-in scenes as they are instead (e.g. cape,skirt: the mannequin): XPBD in
                        the wasm kernel and in TypeScript, mass-spring, and whether the GPU takes the scene
  --self-contact        time self-contact instead: each of --scenes (default fold) with every cloth at --sizes
                        faces per side (default 64), run from its start for --frames (default 180) with
                        solver.selfContact off and on, and the crossing triangle pairs of each; then the
                        Ten Minute Physics 15 demo's strip (30 × 200 particles) by its particle-hash method
                        and by Drape (--no-peer skips it)
  --hanging             time the stretch instead: a 1 m sheet of --sizes faces per side (default 64) hanging from
                        its top edge, for each of --fabrics (default rubber,cotton): the simulated and the wall time
                        until its elongation stays within 25 % of ρ_A·g·L²/(2k), for Drape at its defaults and
                        with solver.stretch global, and for JoltPhysics.js with the fewest of --jolt-iterations
                        (default 10,20,40,80,160,320) that settles; each run at most --seconds (default 10,
                        at least 2: a run must stay settled a second)
  --no-peer             skip JoltPhysics.js
  --no-contention       skip the busy-machine table (the default threads against one thread while other
                        processes, started and stopped by the bench, keep every core busy)
  --set PATH=VALUE      change a scene path of the fabric-model rows only (the like-for-like rows stay), e.g.
                        --set solver.bending=hinges --set solver.bendingSolve=global; with --backend gpu, of the
                        GPU's scene and of the CPU solver timed beside it
  --json                print exactly one JSON object`,
  schema: `drape schema\n\nPrints the JSON schema every scene file is validated against (also published as scene.schema.json).`,
};

/** A count flag: decimal digits only (not '', '0x10', '1e3' or ' 5'), within min…max. */
function intArg(name: string, raw: string | undefined, fallback: number, min: number, max: number): number {
  if (raw === undefined) return fallback;
  const v = /^[0-9]{1,10}$/.test(raw) ? Number(raw) : NaN;
  if (!(v >= min && v <= max)) throw new UsageError(`--${name}: must be an integer in ${min}…${max}, got '${raw}'`);
  return v;
}

/**
 * --threads: an integer ≥ 1, more than the cores available clamped with a note; absent, 'auto' (the cores, or one
 * thread for a small cloth).
 */
function threadsArg(raw: string | undefined): { threads: number | 'auto'; note?: string } {
  if (raw === undefined) return { threads: 'auto' };
  const max = maxThreads();
  const t = intArg('threads', raw, max, 1, 1024);
  return { threads: Math.min(t, max), ...(t > max ? { note: `--threads ${t}: using ${max}, the cores available` } : {}) };
}

/**
 * The flags a run takes but does not use, as notes: a CPU kernel's on the GPU, the kernel's on the mass-spring solver
 * (it runs in TypeScript, on one thread), a thread count on the TypeScript kernel.
 */
function ignoredFlags(values: { kernel?: string; threads?: string }, scene: Scene, backend: 'cpu' | 'gpu'): string[] {
  const given = [values.kernel !== undefined ? `--kernel ${values.kernel}` : '', values.threads !== undefined ? `--threads ${values.threads}` : ''].filter(Boolean);
  if (!given.length) return [];
  if (backend === 'gpu') return [`${given.join(' and ')}: not used: --backend gpu runs the GPU solver`];
  if (scene.solver.type === 'mass-spring') return [`${given.join(' and ')}: not used: the mass-spring solver runs in TypeScript, on one thread`];
  if (values.kernel === 'ts' && values.threads !== undefined) return [`--threads ${values.threads}: not used: the TypeScript kernel runs on one thread`];
  return [];
}

function checkKernel(raw: string | undefined): 'wasm' | 'ts' | 'auto' {
  if (raw === undefined) return 'auto';
  if (raw === 'wasm' || raw === 'ts') return raw;
  throw new UsageError(`--kernel: must be wasm or ts, got '${raw}'`);
}

function checkBackend(raw: string | undefined): 'cpu' | 'gpu' {
  if (raw === undefined || raw === 'cpu' || raw === 'gpu') return raw ?? 'cpu';
  throw new UsageError(`--backend: must be cpu or gpu, got '${raw}'`);
}

/**
 * A built-in scene by name or a scene file, with the reader of the mesh files it may name (relative to the scene
 * file's folder; to the working folder for a built-in scene given a mesh with --set).
 */
export function loadScene(arg: string | undefined): { scene: Scene; meshes: MeshResolver } {
  const name = arg ?? 'custom';
  if (name.endsWith('.json') || name.includes('/') || name.includes('\\')) return loadSceneFile(name);
  if (!isBuiltinScene(name)) throw new UsageError(`unknown scene '${name}' (built-in scenes: ${SCENE_NAMES.join(', ')}; or give a .json file)`);
  return { scene: builtinScene(name), meshes: meshReader() };
}

function applySets(scene: Scene, sets: string[]): Scene {
  for (const s of sets) {
    const eq = s.indexOf('=');
    if (eq <= 0) throw new UsageError(`--set ${s}: expected PATH=VALUE`);
    scene = setScenePath(scene, s.slice(0, eq), parseSetValue(s.slice(eq + 1)));
  }
  return scene;
}

const round = (v: number, digits = 6) => Number(v.toPrecision(digits));
const vec = (v: readonly number[]) => v.map((x) => round(x));

interface RunResult {
  resolution: number;
  particles: number;
  triangles: number;
  constraints: number;
  msPerFrame: number;
  /** substeps per frame the run took: solver.substeps, or more where self-contact needs them (a note in clamps) */
  substeps: number;
  /** CPU kernel and threads ('gpu' on the GPU) */
  kernel: string;
  threads: number;
  finite: boolean;
  maxStrain: number;
  maxPenetration: number;
  /** pairs of triangles sharing no vertex that cross each other at the last frame */
  intersections: number;
  /** particles pressed nearer than half the self-contact distance to a triangle not their own (Report.squeezed) */
  squeezed: number;
  centroid: number[];
  bounds: { min: number[]; max: number[] };
  energy: { kinetic: number; gravitational: number; elastic: number; bending: number };
  /** the scene's standard fabric test, measured at the last frame (numbers rounded as the rest) */
  test?: Record<string, string | number>;
  /** each cloth's figures at the last frame, for a scene of several (Report.cloths, rounded) */
  cloths?: { name: string; first: number; particles: number; triangles: number; centroid: number[]; bounds: { min: number[]; max: number[] } }[];
  clamps: string[];
  sim: Simulation;
  /** the run's frames for --bake: its start and every stride-th frame after it (the last always) */
  bake?: GlbBake & { first: Float32Array; frames: Float32Array[] };
}

/**
 * The MTL file an OBJ export writes beside it: its name with `.mtl` for `.obj`, and white space and control
 * characters as `_`, so that the OBJ's `mtllib` line (names end at white space) names the file that is written.
 */
const mtlPath = (obj: string) => {
  const name = basename(obj);
  return obj.slice(0, obj.length - name.length) + name.replace(/\.obj$/i, '.mtl').replace(/[\s\p{C}]/gu, '_');
};

/** Most bytes a bake may have: past this --bake is refused before the run, naming a stride that fits. */
const MAX_BAKE_BYTES = 2 ** 30;

/** Which frames a bake of `frames` frames at `stride` keeps after frame 0: every stride-th, and the last. */
function bakedFrames(frames: number, stride: number): number[] {
  const kept: number[] = [];
  for (let f = stride; f <= frames; f += stride) kept.push(f);
  if (kept[kept.length - 1] !== frames) kept.push(frames);
  return kept;
}

async function simulate(scene: Scene, frames: number, gpu: Gpu | undefined, options: SimulationOptions, bakeStride?: number): Promise<RunResult> {
  let sim: Simulation, ms: number, kernel = 'gpu', threads = 1, bake: RunResult['bake'];
  const kept = bakeStride === undefined ? [] : bakedFrames(frames, bakeStride);
  // a bake too large for memory is refused before the run, naming a stride that fits
  const fitBake = (n: number) => {
    if (bakeStride === undefined || bakeBytes(n, kept.length) <= MAX_BAKE_BYTES) return;
    let fits = bakeStride + 1;
    while (bakeBytes(n, Math.ceil(frames / fits)) > MAX_BAKE_BYTES) fits++;
    throw new UsageError(`--bake: ${kept.length} frames of ${n} particles would be ${(bakeBytes(n, kept.length) / 2 ** 30).toFixed(1)} GiB, more than 1 GiB; give --bake-stride ${fits} or more, or fewer --frames`);
  };
  if (gpu) {
    let first: Float32Array | undefined, shapes: Float32Array[];
    ({ sim, msPerFrame: ms, shapes } = await gpu.simulate(scene, frames, options.meshes, kept, (s) => {
      fitBake(s.model.particleCount);
      first = s.state.positions.slice();
    }));
    if (bakeStride !== undefined) bake = { first: first!, frames: shapes, times: kept.map((f) => f * FRAME_DT), frameNumbers: kept };
  } else {
    sim = new Simulation(scene, options);
    try {
      await sim.whenReady();
      kernel = sim.kernel;
      threads = sim.threads;
      fitBake(sim.model.particleCount);
      const first = sim.state.positions.slice(), shapes: Float32Array[] = [];
      const t0 = performance.now();
      let done = 0;
      for (const f of kept) {
        // a cloth that blew up stops advancing; the caller reports it and writes nothing
        if (!sim.advance(f - done)) break;
        done = f;
        shapes.push(sim.state.positions.slice());
      }
      sim.advance(frames - done);
      if (bakeStride !== undefined) bake = { first, frames: shapes, times: kept.map((f) => f * FRAME_DT), frameNumbers: kept };
      ms = sim.frame > 0 ? (performance.now() - t0) / sim.frame : 0;
    } finally {
      sim.dispose();
    }
  }
  const r = sim.report();
  return {
    resolution: scene.cloth.resolution,
    particles: r.particles,
    triangles: r.triangles,
    constraints: r.constraints,
    msPerFrame: round(ms, 4),
    substeps: sim.params.substeps,
    kernel,
    threads,
    finite: r.finite,
    maxStrain: round(r.maxStrain),
    maxPenetration: round(r.maxPenetration),
    intersections: r.intersections,
    squeezed: r.squeezed,
    centroid: vec(r.centroid),
    bounds: { min: vec(r.bounds.min), max: vec(r.bounds.max) },
    energy: { kinetic: round(r.energy.kinetic), gravitational: round(r.energy.gravitational), elastic: round(r.energy.elastic), bending: round(r.energy.bending) },
    ...(r.test ? { test: Object.fromEntries(Object.entries(r.test).map(([k, v]) => [k, typeof v === 'number' ? round(v) : v])) } : {}),
    ...(r.cloths ? { cloths: r.cloths.map((c) => ({ ...c, centroid: vec(c.centroid), bounds: { min: vec(c.bounds.min), max: vec(c.bounds.max) } })) } : {}),
    clamps: sim.notes,
    sim,
    ...(bake ? { bake } : {}),
  };
}

/** The one line that says a run blew up. */
function unstableLine(scene: Scene, run: RunResult, frames: number, gpu: boolean): string {
  // the CPU checks every frame; the GPU backend reads positions back once, after the last frame
  const when = !gpu && run.sim.unstableFrame !== null ? `at frame ${run.sim.unstableFrame} of ${frames}` : `by frame ${frames}`;
  const res = scene.resolutionSweep ? ` (${run.resolution} faces per side)` : '';
  return `${plainText(scene.name, 100)}${res}: the simulation became unstable ${when} (positions are no longer finite); nothing was exported`;
}

/** What the CLI does to the file system, replaceable in tests. */
export interface CliIo {
  writeFile(path: string, data: string | Uint8Array): void;
}
const nodeIo: CliIo = { writeFile: (path, text) => writeFileSync(path, text) };

/**
 * argv with `--name -1` written `--name=-1` for the options that take a value: parseArgs reads a value that starts
 * with a dash as an option of its own ("argument is ambiguous"), where the user meant a (negative) number, which
 * the option's own check then names ("--frames: must be an integer in 0…1000000, got '-1'").
 */
function negativeValues(argv: string[], options: Record<string, { type: 'string' | 'boolean' }>): string[] {
  const out: string[] = [];
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i], next = argv[i + 1];
    if (a.startsWith('--') && !a.includes('=') && options[a.slice(2)]?.type === 'string' && next !== undefined && /^-(\d|\.\d|Infinity$|NaN$)/i.test(next)) {
      out.push(`${a}=${next}`);
      i++;
    } else {
      out.push(a);
    }
  }
  return out;
}

async function cmdRun(argv: string[], out: (s: string) => void, err: (s: string) => void, io: CliIo): Promise<number> {
  const runOptions = {
    frames: { type: 'string' }, solver: { type: 'string' }, backend: { type: 'string' },
    kernel: { type: 'string' }, threads: { type: 'string' },
    set: { type: 'string', multiple: true }, json: { type: 'boolean' }, export: { type: 'string' },
    bake: { type: 'string' }, 'bake-stride': { type: 'string' }, specimens: { type: 'string' }, help: { type: 'boolean', short: 'h' },
  } as const;
  const { values, positionals } = parseArgs({
    args: negativeValues(argv, runOptions),
    allowPositionals: true,
    options: runOptions,
  });
  if (values.help) { out(HELP.run); return 0; }
  if (positionals.length > 1) throw new UsageError(`run: one scene at a time, got ${positionals.join(', ')}`);
  // checked before anything is loaded; without --frames the scene's duration decides (below)
  const framesAsked = values.frames === undefined ? undefined : intArg('frames', values.frames, 180, 0, 1_000_000);
  const backend = checkBackend(values.backend);
  const threads = threadsArg(values.threads);
  const options: SimulationOptions = { ...cpuOptions(threads.threads), kernel: checkKernel(values.kernel) };
  // every destination is checked before simulating: a bad one costs nothing
  if (values.export !== undefined) {
    if (!/\.(obj|glb)$/i.test(values.export)) throw new UsageError(`--export: .obj or .glb files only, got '${values.export}'`);
    checkOutputPath(values.export, '--export');
    if (/\.obj$/i.test(values.export)) checkOutputPath(mtlPath(values.export), '--export (its .mtl)');
  }
  if (values['bake-stride'] !== undefined && values.bake === undefined) throw new UsageError('--bake-stride: bakes with --bake FILE.glb; give --bake too');
  const bakeStride = intArg('bake-stride', values['bake-stride'], 1, 1, 1_000_000);
  const specimens = intArg('specimens', values.specimens, 1, 1, 20);
  if (values.bake !== undefined) {
    if (!/\.glb$/i.test(values.bake)) throw new UsageError(`--bake: writes a .glb file, got '${values.bake}'`);
    if (framesAsked === 0) throw new UsageError('--bake: --frames 0 runs no frame to bake; give --frames 1 or more');
    checkOutputPath(values.bake, '--bake');
    if (values.export !== undefined && resolve(values.export) === resolve(values.bake)) throw new UsageError(`--bake: ${values.bake} is the --export file too; give two names`);
  }
  const loaded = loadScene(positionals[0]);
  let scene = loaded.scene;
  options.meshes = loaded.meshes;
  const sets = values.set ?? [];
  // --solver is its own flag, and its errors say so (they named '--set solver.type', which the user never wrote)
  if (values.solver !== undefined) scene = setScenePath(scene, 'solver.type', values.solver, '--solver');
  scene = applySets(scene, sets);
  // the flags the run does not use, or else the threads' clamp to the cores (not both: they would contradict)
  const ignored = ignoredFlags(values, scene, backend);
  for (const note of ignored.length ? ignored : threads.note ? [threads.note] : []) err(`drape: note: ${note}`);
  const frames = framesAsked ?? Math.max(1, Math.round(scene.duration / FRAME_DT));

  // a --set of the cloth's resolution (or of the whole cloth) runs that resolution, not the sweep
  const setPaths = sets.map((s) => s.slice(0, Math.max(0, s.indexOf('='))).replace(/\[(\d+)\]/g, '.$1').split('.').filter(Boolean).join('.'));
  const sweepAsked = scene.resolutionSweep && !setPaths.some((p) => p === 'cloth.resolution' || p === 'cloth') ? scene.resolutionSweep : undefined;
  // a mesh file has its own resolution: the sweep would run the same cloth again and again
  const sweep = scene.cloth.shape === 'mesh' || scene.cloths ? undefined : sweepAsked;
  if (sweepAsked && !sweep) {
    err(scene.cloths ? 'drape: note: resolutionSweep skipped: the scene has a list of cloths, each with its own resolution'
      : `drape: note: resolutionSweep skipped: the cloth is the mesh file ${plainText(scene.cloth.mesh ?? '', 200)}, which has its own resolution`);
  }
  const specimenScenes = specimens > 1 ? specimenRuns(scene, specimens, !!sweep) : [];
  if (backend === 'gpu') {
    const why = await gpuRefusal(scene);
    if (why) throw new UsageError(why);
  }
  const gpu = backend === 'gpu' ? await openGpu() : undefined;
  const main = await simulate(scene, frames, gpu, options, values.bake === undefined ? undefined : bakeStride);
  const sweepRuns: RunResult[] = [];
  for (const resolution of sweep ?? []) sweepRuns.push(await simulate({ ...scene, cloth: { ...scene.cloth, resolution } }, frames, gpu, options));
  const others: RunResult[] = [];
  for (const s of specimenScenes) others.push(await simulate(s, frames, gpu, options));
  const unstable = [main, ...sweepRuns, ...others].find((r) => !r.finite);
  if (unstable) {
    const line = unstableLine(scene, unstable, frames, !!gpu);
    // --json still prints one object: what blew up and when, with no NaN in it
    if (values.json) {
      out(safeJson({
        scene: scene.name, solver: scene.solver.type, backend, frames, substeps: unstable.substeps, resolution: unstable.resolution,
        finite: false, unstableFrame: gpu ? null : unstable.sim.unstableFrame, error: line,
      }));
    }
    err(`drape: ${line}`);
    return EXIT.unstable;
  }

  const errors: string[] = [];
  const write = (flag: string, path: string, data: () => string | Uint8Array): boolean => {
    try {
      io.writeFile(path, data());
      return true;
    } catch (e) {
      errors.push(`${flag}: could not write ${path} (${(e as NodeJS.ErrnoException).code ?? (e as Error).message.split('\n')[0]})`);
      return false;
    }
  };
  const { model, state } = main.sim, dress = exportCloths(scene), name = scene.name;
  const cloths = modelCloths(model, state.positions, dress);
  const exported = values.export !== undefined && (/\.glb$/i.test(values.export)
    ? write('--export', values.export, () => toGLB({ name, cloths }))
    : write('--export', values.export, () => toOBJ({ name, cloths, mtllib: basename(mtlPath(values.export!)) }))
      && write('--export', mtlPath(values.export), () => toMTL({ name, cloths })));
  const bake = main.bake;
  const baked = values.bake !== undefined && bake !== undefined
    && write('--bake', values.bake, () => toGLB({ name, cloths: modelCloths(model, bake.first, dress, bake.frames), bake }));
  const bakeSummary = bake && `frame 0 and ${bake.frames.length} more (stride ${bakeStride}), ${(bakeBytes(model.particleCount, bake.frames.length) / 1e6).toFixed(1)} MB of morph targets`;
  const exportError = errors.length ? errors.join('; ') : undefined;
  const { sim: _sim, resolution: _r, bake: _b, clamps, ...fields } = main;
  const specimenTests = others.length ? [main, ...others].map((r) => ({ seed: r.sim.scene.cloth.perturbation.seed, test: r.test! })) : undefined;
  const mean = specimenTests && meanTest(specimenTests.map((t) => t.test));
  if (values.json) {
    out(safeJson({
      scene: scene.name, solver: scene.solver.type, backend, frames, ...fields, clamps,
      ...(sweep ? { sweep: sweepRuns.map(({ sim: _s, ...r }) => ({ faces: r.triangles / 2, ...r })) } : {}),
      ...(specimenTests ? { specimens: specimenTests, testMean: mean } : {}),
      ...(exported ? { exported: values.export } : {}),
      ...(baked ? { baked: values.bake, bakedFrames: bake!.frameNumbers.length + 1 } : {}),
      ...(exportError ? { exportError } : {}),
      resolvedScene: sceneDocument(scene),
    }));
  } else {
    for (const c of clamps) err(`drape: note: ${c}`);
    // the sweep's runs clamp what their own resolution needs (a finer mesh softens more springs): said once each
    const said = new Set(clamps);
    for (const r of sweepRuns) {
      for (const c of r.clamps) if (!said.has(c)) { said.add(c); err(`drape: note: at cloth.resolution ${r.resolution}: ${c}`); }
    }
    const f = (v: number) => (Math.abs(v) < 1e-3 && v !== 0 ? v.toExponential(2) : v.toFixed(4));
    const where = backend === 'gpu' ? 'gpu' : `cpu (${main.kernel === 'wasm' ? `wasm SIMD, ${main.threads} thread${main.threads === 1 ? '' : 's'}` : 'TypeScript'})`;
    out(`scene ${plainText(scene.name, 100)}: ${scene.solver.type} on ${where}, ${main.substeps} substeps, ${frames} frames (${(frames / 60).toFixed(2)} s)`);
    out(`  cloth        ${main.particles} particles, ${main.triangles} triangles, ${main.constraints} springs`);
    for (const c of main.cloths ?? []) {
      out(`    ${plainText(c.name, 40)}: particles ${c.first}…${c.first + c.particles - 1}, ${c.triangles} triangles, centroid [${c.centroid.map(f).join(', ')}] m`);
    }
    out(`  speed        ${main.msPerFrame.toFixed(3)} ms per frame`);
    out(`  finite       yes`);
    out(`  max strain   ${(main.maxStrain * 100).toFixed(2)} % (structural)`);
    out(`  penetration  ${(main.maxPenetration * 1000).toFixed(3)} mm`);
    out(`  intersections ${main.intersections} pairs of triangles crossing each other (sharing no vertex)`);
    out(`  squeezed     ${main.squeezed} particles pressed nearer than half the self-contact distance to the cloth`);
    out(`  centroid     [${main.centroid.map(f).join(', ')}] m`);
    out(`  energy       kinetic ${f(main.energy.kinetic)} J, gravitational ${f(main.energy.gravitational)} J, elastic ${f(main.energy.elastic)} J (bending ${f(main.energy.bending)} J)`);
    // (a null is a measure the cloth does not give yet: the cantilever's bending length before its tip drops)
    const testFields = (t: Record<string, unknown>) => Object.entries(t)
      .map(([k, v]) => `${k} ${typeof v === 'number' ? (Number.isInteger(v) ? v : f(v)) : v === null ? '— (not yet)' : plainText(String(v), 40)}`).join(', ');
    if (specimenTests) {
      specimenTests.forEach((t, k) => out(`  ${k ? '            ' : 'test        '} seed ${t.seed}: ${testFields(t.test)}`));
      out(`  mean of ${String(specimenTests.length).padEnd(4)} ${testFields(mean!)}`);
    } else if (main.test) {
      out(`  test         ${testFields(main.test)}`);
    }
    if (sweep) {
      out(`  resolution sweep (triangles → resting height of the centroid):`);
      for (const r of sweepRuns) out(`    ${String(r.triangles).padStart(6)} triangles  centroid y ${r.centroid[1].toFixed(3)} m  penetration ${(r.maxPenetration * 1000).toFixed(2)} mm  ${r.msPerFrame.toFixed(3)} ms/frame`);
    }
    if (exported) out(`  exported     ${values.export}${/\.obj$/i.test(values.export!) ? ` and ${mtlPath(values.export!)}` : ''}`);
    if (baked) out(`  baked        ${values.bake}: ${bakeSummary}`);
  }
  if (exportError) {
    err(`drape: ${exportError}; the results above are complete`);
    return EXIT.exportFailed;
  }
  return 0;
}

/**
 * --specimens N: the scene's specimens after its own (seed s of cloth.perturbation): seeds s + 1 … s + N − 1, each a
 * copy of the scene with its seed; refused with a UsageError where the specimens would not differ or not be tested.
 */
function specimenRuns(scene: Scene, n: number, sweep: boolean): Scene[] {
  if (!scene.test) throw new UsageError(`--specimens: reads a standard test's specimens (the cantilever, cusick scenes); scene '${plainText(scene.name, 100)}' has no test`);
  if (scene.cloths) throw new UsageError('--specimens: a scene of one cloth (each specimen is its cloth.perturbation.seed)');
  if (sweep) throw new UsageError('--specimens: not with a resolutionSweep; set cloth.resolution');
  const { amplitude, seed } = scene.cloth.perturbation;
  if (!(amplitude > 0)) throw new UsageError('--specimens: the specimens differ only in cloth.perturbation, whose amplitude is 0 here; give it one, e.g. --set cloth.perturbation.amplitude=0.001');
  if (seed + n - 1 > 2147483647) throw new UsageError(`--specimens: seeds ${seed}…${seed + n - 1} pass cloth.perturbation.seed's most, 2147483647`);
  return Array.from({ length: n - 1 }, (_, k) => ({ ...scene, cloth: { ...scene.cloth, perturbation: { amplitude, seed: seed + k + 1 } } }));
}

/** The mean of the specimens' tests, field by field: the numbers' mean, null where any is null, the rest as the first's. */
function meanTest(tests: Record<string, string | number | null>[]): Record<string, string | number | null> {
  const mean: Record<string, string | number | null> = {};
  for (const [k, v] of Object.entries(tests[0])) {
    const all = tests.map((t) => t[k]);
    mean[k] = typeof v !== 'number' ? v : all.some((x) => typeof x !== 'number') ? null
      : Number(((all as number[]).reduce((a, b) => a + b, 0) / all.length).toPrecision(6));
  }
  return mean;
}

function cmdScenes(argv: string[], out: (s: string) => void): number {
  const { values } = parseArgs({ args: argv, options: { json: { type: 'boolean' }, help: { type: 'boolean', short: 'h' } } });
  if (values.help) { out(HELP.scenes); return 0; }
  const list = SCENE_NAMES.map((name) => ({ name, description: builtinScene(name).description ?? '' }));
  if (values.json) out(safeJson(list));
  else for (const s of list) out(`${s.name.padEnd(16)}${s.description}`);
  return 0;
}

async function cmdBench(argv: string[], out: (s: string) => void, err: (s: string) => void): Promise<number> {
  const benchOptions = {
    sizes: { type: 'string' }, substeps: { type: 'string' }, frames: { type: 'string' }, warmup: { type: 'string' },
    backend: { type: 'string' }, threads: { type: 'string' }, 'no-peer': { type: 'boolean' }, 'no-contention': { type: 'boolean' },
    scenes: { type: 'string' }, 'self-contact': { type: 'boolean' },
    hanging: { type: 'boolean' }, fabrics: { type: 'string' }, seconds: { type: 'string' }, 'jolt-iterations': { type: 'string' },
    set: { type: 'string', multiple: true },
    json: { type: 'boolean' },
    help: { type: 'boolean', short: 'h' },
  } as const;
  const { values } = parseArgs({
    args: negativeValues(argv, benchOptions),
    options: benchOptions,
  });
  if (values.help) { out(HELP.bench); return 0; }
  const backend = checkBackend(values.backend);
  const { threads, note: threadsNote } = threadsArg(values.threads);
  if (threadsNote) err(`drape: note: ${threadsNote}`);
  const selfContact = values['self-contact'] ?? false;
  const hanging = values.hanging ?? false;
  if (selfContact && hanging) throw new UsageError('--hanging and --self-contact are two different benchmarks: give one');
  // flags that belong to one benchmark are refused by the others rather than passed over
  const given = (names: string[]) => names.filter((name) => (values as Record<string, unknown>)[name] !== undefined);
  const sets = values.set ?? [];
  if (sets.length && (hanging || selfContact || values.scenes !== undefined)) {
    throw new UsageError('--set: changes the fabric-model rows of the CPU bench and the GPU bench\'s scene (drape bench [--backend gpu] [--sizes …] --set PATH=VALUE); the other benchmarks take their scenes as they are');
  }
  if (hanging) {
    const stray = given(['scenes', 'frames', 'warmup', 'substeps', 'no-contention']);
    if (stray.length) throw new UsageError(`--hanging: runs each sheet until it settles or --seconds pass; --${stray[0]} is for the other benchmarks`);
  } else {
    const stray = given(['fabrics', 'seconds', 'jolt-iterations']);
    if (stray.length) throw new UsageError(`--${stray[0]}: belongs to --hanging; give --hanging too`);
  }
  const sizes = (values.sizes ?? (selfContact || hanging ? '64' : backend === 'gpu' ? '64,128,256,512,1024' : '64,128')).split(',')
    .map((s) => intArg('sizes', s.trim(), 0, selfContact ? 1 : 2, selfContact || hanging ? 256 : 1025));
  if (hanging) {
    if (backend === 'gpu') throw new UsageError('--hanging: times the CPU solvers, not the GPU solver; leave out --backend gpu');
    if (sizes.length !== 1) throw new UsageError('--hanging: one size, the sheet\'s faces per side (e.g. --sizes 64)');
    const fabrics = (values.fabrics ?? 'rubber,cotton').split(',').map((f) => f.trim());
    for (const f of fabrics) if (!(FABRIC_NAMES as readonly string[]).includes(f)) throw new UsageError(`--fabrics: unknown fabric '${plainText(f, 100)}' (named fabrics: ${FABRIC_NAMES.join(', ')})`);
    // tried in ascending order, each count once: the first that settles is the fewest
    const iterations = [...new Set((values['jolt-iterations'] ?? '10,20,40,80,160,320').split(',').map((s) => intArg('jolt-iterations', s.trim(), 0, 1, 10_000)))]
      .sort((a, b) => a - b);
    await runHangingBench({
      faces: sizes[0],
      fabrics,
      // a settled run stays in the band a further second, so a run shorter than 2 s could never settle
      seconds: intArg('seconds', values.seconds, 10, 2, 600),
      joltIterations: iterations,
      peer: !values['no-peer'],
      threads,
      json: values.json ?? false,
    }, out);
    return 0;
  }
  const sceneList = (raw: string) => {
    const scenes = raw.split(',').map((s) => s.trim());
    for (const s of scenes) if (!isBuiltinScene(s)) throw new UsageError(`--scenes: unknown scene '${plainText(s, 100)}' (built-in scenes: ${SCENE_NAMES.join(', ')})`);
    return scenes;
  };
  if (selfContact) {
    if (backend === 'gpu') throw new UsageError('--self-contact: times the CPU kernels, not the GPU solver; leave out --backend gpu');
    await runSelfContactBench({
      scenes: sceneList(values.scenes ?? 'fold'),
      sizes,
      frames: intArg('frames', values.frames, 180, 1, 100_000),
      threads,
      peer: !values['no-peer'],
      json: values.json ?? false,
    }, out);
    return 0;
  }
  if (values.scenes !== undefined) {
    if (backend === 'gpu') throw new UsageError('--scenes: times the CPU solvers; the GPU column says whether the GPU takes each scene (leave out --backend gpu)');
    await runSceneBench({
      scenes: sceneList(values.scenes),
      frames: intArg('frames', values.frames, 120, 1, 100_000),
      warmup: intArg('warmup', values.warmup, 30, 0, 100_000),
      threads,
      json: values.json ?? false,
    }, out);
    return 0;
  }
  if (backend === 'gpu') {
    await runGpuBench(await openGpu(), {
      sizes,
      substeps: intArg('substeps', values.substeps, 10, 1, 200),
      frames: intArg('frames', values.frames, 60, 1, 100_000),
      threads,
      model: sets.length ? checkedModel(sets) : undefined,
      sets,
      json: values.json ?? false,
    }, out);
    return 0;
  }
  await runBench({
    sizes,
    substeps: intArg('substeps', values.substeps, 10, 1, 200),
    frames: intArg('frames', values.frames, 120, 1, 100_000),
    warmup: intArg('warmup', values.warmup, 30, 0, 100_000),
    peer: !values['no-peer'],
    contention: !values['no-contention'],
    threads,
    // checked now, on the document the rows will use, so that a bad path is a usage error before anything is timed
    model: sets.length ? checkedModel(sets) : undefined,
    json: values.json ?? false,
  }, out);
  return 0;
}

/** The bench's fabric-model scene changed by the --set values, each checked once on a scene of the same shape. */
function checkedModel(sets: string[]): (scene: Scene) => Scene {
  applySets(builtinScene('cotton-basic'), sets);
  return (scene) => applySets(scene, sets);
}

/**
 * Text for the terminal: line by line through plainText, a safety net so that no escape sequence reaches it (strings
 * from scenes and files are made one line where they are inserted).
 */
const terminalText = (s: string) => s.split('\n').map((line) => plainText(line, Infinity)).join('\n');

/**
 * Runs the CLI; returns the exit code (EXIT: 0 done, 1 internal error, 2 bad input, 3 the simulation became
 * unstable, 4 the results are printed but the export failed). Output goes through `out`/`err` (tests capture it),
 * every line terminal-safe; `io` writes files.
 */
export async function main(
  argv: string[], toOut: (s: string) => void = console.log, toErr: (s: string) => void = console.error, io: CliIo = nodeIo,
): Promise<number> {
  const out = (s: string) => toOut(terminalText(s)), err = (s: string) => toErr(terminalText(s));
  const [cmd, ...rest] = argv;
  try {
    switch (cmd) {
      case undefined: case 'help': case '--help': case '-h': out(HELP.main); return 0;
      case '--version': case '-v': out(JSON.parse(readFileSync(new URL('../../package.json', import.meta.url), 'utf8')).version); return 0;
      case 'run': return await cmdRun(rest, out, err, io);
      case 'scenes': return cmdScenes(rest, out);
      case 'bench': return await cmdBench(rest, out, err);
      case 'schema':
        if (rest.includes('--help') || rest.includes('-h')) { out(HELP.schema); return 0; }
        if (rest.length) throw new UsageError(`schema: takes no arguments, got ${rest.join(' ')}`);
        out(JSON.stringify(sceneSchema, null, 2)); return 0;
      default: throw new UsageError(`unknown command '${cmd}' (commands: run, scenes, bench, schema; try drape --help)`);
    }
  } catch (e) {
    const error = e as Error & { code?: string };
    // parseArgs' own errors (unknown option, missing value) and ours are the user's to fix: one line, exit 2
    if (e instanceof UsageError || error.name === 'SceneError' || error.code?.startsWith('ERR_PARSE_ARGS')) {
      // parseArgs appends advice after the first sentence; the first sentence names the problem. Ours are one
      // line, but may quote what the user gave (a key, a path), which must stay on that line
      let line = error.code?.startsWith('ERR_PARSE_ARGS') ? error.message.split('\n')[0].split('. ')[0] : error.message;
      // a value that starts with a dash (not a number: those are joined to their option above) reads as an option
      const ambiguous = /^Option '(--[\w-]+)' argument is ambiguous/.exec(line);
      if (ambiguous) line = `${ambiguous[1]}: its value starts with a dash, which reads as an option; write ${ambiguous[1]}=VALUE`;
      err(`drape: ${plainText(line, 1000)}`);
      return EXIT.usage;
    }
    err(`drape: internal error: ${plainText(error.message.split('\n')[0], 1000)}`);
    return EXIT.internal;
  }
}
