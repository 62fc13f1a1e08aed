/**
 * `drape bench`: ms per 60 Hz frame for the CPU solvers on a cloth dropped on a sphere and a floor, and
 * JoltPhysics.js on the very same cloth (same particles, masses, constraints and compliances) in the same run.
 */
import { availableParallelism, cpus } from 'node:os';
import { builtinScene, centroid, countIntersections, FRAME_DT, isFinite3, plainText, sceneDocument, Simulation, validateScene, WasmBackend, type Scene, type SimulationOptions } from '../core/index.js';
import type { Gpu } from './gpu.js';
import type { PeerClothSpec } from './peers/jolt.js';
import { whileBusy } from './busy.js';
import { spawnNodeHelper } from './threads.js';
import { hangingStrip, ParticleHashCloth } from './peers/particle-hash.js';

export interface BenchOptions {
  /** particles per side */
  sizes: number[];
  /** XPBD substeps per frame (Jolt iterations) */
  substeps: number;
  frames: number;
  warmup: number;
  /** run JoltPhysics.js beside Drape */
  peer: boolean;
  /** also time Drape's XPBD (default threads and one thread) while other processes keep every core busy */
  contention: boolean;
  /** threads of the WebAssembly XPBD kernel in the main Drape column (a 1-thread column is always printed) */
  threads: number | 'auto';
  /**
   * the fabric-model rows' scene with these changes (the CLI's --set, applied to modelScene's document: e.g. another
   * bending model or solve); the like-for-like rows never take them
   */
  model?: (scene: Scene) => Scene;
  json: boolean;
}

interface Timing {
  msPerFrame: number;
  /** particles × substeps per second of wall time */
  particleSubstepsPerSecond: number;
  finite: boolean;
  /** finite, and the centroid still within 10 cloth sizes of where it started (a cloth that explodes can stay finite) */
  stable: boolean;
  centroid: number[];
}

/** Finite and not flown away: the centroid within 10 cloth sizes of the start centroid. */
function isStable(finite: boolean, centroid: readonly number[], start: readonly number[], size: number): boolean {
  return finite && Math.hypot(centroid[0] - start[0], centroid[1] - start[1], centroid[2] - start[2]) < 10 * size;
}

interface Row {
  particlesPerSide: number;
  particles: number;
  constraints: number;
  /** XPBD in the WebAssembly kernel with opts.threads threads */
  xpbd: Timing & { kernel: string; threads: number };
  /** XPBD in the WebAssembly kernel on one thread */
  xpbd1: Timing & { kernel: string };
  /** XPBD in TypeScript */
  xpbdTs: Timing;
  massSpring: Timing;
  jolt?: Timing & { name: string };
  /** Drape XPBD ms (opts.threads) / Jolt ms (lower is better) */
  ratio?: number;
  /** Drape XPBD ms (1 thread) / Jolt ms */
  ratio1?: number;
  peerError?: string;
  /** on a busy machine: Drape XPBD with the default threads and with one, and their ratio */
  busy?: { xpbd: Timing & { threads: number; aloneFraction: number }; xpbd1: Timing; ratio: number };
  /**
   * the same cloth with Drape's default fabric model (modelScene): its bending, stretch and substeps, on the default
   * threads, one thread and in TypeScript; `ratio1` its 1-thread ms over the like-for-like 1-thread ms
   */
  model: {
    bending: string; bendingSolve: string; stretch: string; substeps: number; xpbd: Timing & { threads: number }; xpbd1: Timing; xpbdTs: Timing; ratio1: number;
  };
}

export function benchScene(side: number, substeps: number, solver: 'xpbd' | 'mass-spring'): Scene {
  const scene = builtinScene('cotton-basic');
  scene.cloth.resolution = side - 1;
  // like for like with Jolt, which has no self-contact, bends with distance constraints and solves them one at a
  // time: the particles, the springs (bend springs too, whatever the default bending model), swept alone (whatever
  // the default stretch solve) and these substeps, no more
  scene.solver = { ...scene.solver, type: solver, substeps, iterations: 1, selfContact: false, bending: 'springs', stretch: 'gauss-seidel' };
  return scene;
}

/**
 * The bench's cloth with Drape's default fabric model instead: the scene's own bending model, stretch solve and
 * substeps, so that the cost of what a user gets by default stands beside the like-for-like rows. Self-contact off,
 * as there: it has its own bench (--self-contact).
 */
function modelScene(side: number): Scene {
  const scene = builtinScene('cotton-basic');
  scene.cloth.resolution = side - 1;
  scene.solver = { ...scene.solver, selfContact: false };
  return scene;
}

type DrapeTiming = Timing & { sim: Simulation; start: number[]; kernel: string; threads: number; aloneFraction: number };

/** What a timed simulation reports: ms per frame, whether it stayed put, and how its kernel ran. */
function drapeTiming(sim: Simulation, msPerFrame: number, start: number[]): DrapeTiming {
  // what the timing needs only (a full report also counts self-intersections, seconds on a large cloth)
  const finite = isFinite3(sim.state), c = centroid(sim.state);
  const mode = sim.backend instanceof WasmBackend ? sim.backend.kernel.mode : undefined;
  return {
    msPerFrame,
    particleSubstepsPerSecond: (sim.model.particleCount * sim.params.substeps * 1000) / msPerFrame,
    finite,
    stable: isStable(finite, c, start, sim.model.size),
    centroid: c,
    sim,
    start,
    kernel: sim.kernel,
    threads: sim.threads,
    aloneFraction: mode && mode.frames > 0 ? mode.framesAlone / mode.frames : sim.threads > 1 ? 0 : 1,
  };
}

/** Times `frames` frames after `warmup` (which also lets the WebAssembly code tier up) once helpers have started. */
async function timeDrape(scene: Scene, frames: number, warmup: number, options: SimulationOptions): Promise<DrapeTiming> {
  const sim = new Simulation(scene, options);
  try {
    await sim.whenReady();
    const start = centroid(sim.state);
    sim.advance(warmup);
    const f0 = sim.frame, t0 = performance.now();
    sim.advance(frames);
    return drapeTiming(sim, (performance.now() - t0) / Math.max(1, sim.frame - f0), start);
  } finally {
    sim.dispose();
  }
}

/**
 * Times two simulations of one scene in alternating blocks of frames, so that both meet the same machine (a busy
 * one changes from second to second): the fair way to compare two settings.
 */
async function timeDrapePair(scene: Scene, frames: number, warmup: number, a: SimulationOptions, b: SimulationOptions): Promise<[DrapeTiming, DrapeTiming]> {
  const sims = [new Simulation(scene, a), new Simulation(scene, b)];
  try {
    await Promise.all(sims.map((s) => s.whenReady()));
    const starts = sims.map((s) => centroid(s.state));
    for (const s of sims) s.advance(warmup);
    const ms = [0, 0], f0 = sims.map((s) => s.frame);
    const block = 10;
    for (let done = 0, k = 0; done < frames; done += block, k++) {
      const n = Math.min(block, frames - done);
      for (const i of k % 2 ? [1, 0] : [0, 1]) {
        const t0 = performance.now();
        sims[i].advance(n);
        ms[i] += performance.now() - t0;
      }
    }
    const per = (i: number) => ms[i] / Math.max(1, sims[i].frame - f0[i]);
    return [drapeTiming(sims[0], per(0), starts[0]), drapeTiming(sims[1], per(1), starts[1])];
  } finally {
    for (const s of sims) s.dispose();
  }
}

const timing = ({ msPerFrame, particleSubstepsPerSecond, finite, stable, centroid }: Timing): Timing =>
  ({ msPerFrame, particleSubstepsPerSecond, finite, stable, centroid });

/** The options of the fastest CPU XPBD Drape has here: the wasm kernel on `threads` threads. */
export function cpuOptions(threads: number | 'auto'): SimulationOptions {
  return { kernel: 'auto', threads, spawnHelper: spawnNodeHelper };
}

/**
 * The cloth of `sim` as Jolt takes it: the same particles (pinned ones held), masses, distance constraints and
 * compliances; with `colliders`, the scene's sphere and floor (the drop the bench times), else none.
 */
function peerSpec(sim: Simulation, iterations: number, colliders = true): PeerClothSpec {
  const { model, params, scene, state } = sim;
  const sphere = scene.colliders.find((c) => c.type === 'sphere');
  const floor = scene.colliders.find((c) => c.type === 'floor');
  if (colliders && (!sphere || sphere.type !== 'sphere' || !floor || floor.type !== 'floor')) throw new Error('bench scene needs a sphere and a floor');
  return {
    positions: model.restPositions,
    invMass: Float32Array.from(params.particleInvMass, (w, i) => (state.pinned[i] ? 0 : w)),
    edges: model.springs,
    compliance: params.compliance,
    triangles: model.triangles,
    sphere: colliders && sphere?.type === 'sphere' ? { center: sphere.center, radius: sphere.radius } : null,
    floorY: colliders && floor?.type === 'floor' ? floor.height : null,
    gravity: scene.gravity,
    iterations,
    friction: params.friction,
    vertexRadius: params.thickness,
  };
}

const fmt = (v: number, d = 2) => v.toFixed(d);
const sci = (v: number) => v.toExponential(2);
/** A timed run's stability, as the tables say it. */
const stability = (t: Timing) => (t.stable ? 'yes' : t.finite ? 'NO (flew off)' : 'NO (NaN)');

/** An error's first line, for a table cell or a note. */
const firstLine = (e: unknown): string => (e as Error).message.split('\n')[0];

/** The machine a bench ran on, for its header. */
const machineLine = () => `${cpus()[0]?.model ?? 'unknown CPU'} × ${cpus().length}, Node ${process.version}`;

/**
 * The JoltPhysics.js peer module, loaded lazily when `wanted` (an optional dependency): the module, or why it did
 * not load (one line), or neither when not wanted.
 */
async function loadJoltPeer(wanted: boolean): Promise<{ peer?: typeof import('./peers/jolt.js'); error?: string }> {
  if (!wanted) return {};
  try {
    return { peer: await import('./peers/jolt.js') };
  } catch (e) {
    return { error: firstLine(e) };
  }
}

export async function runBench(opts: BenchOptions, out: (s: string) => void): Promise<Row[]> {
  const { peer, error: peerError } = await loadJoltPeer(opts.peer);
  const runJolt = peer?.runJoltCloth;
  const rows: Row[] = [];
  for (const side of opts.sizes) {
    const scene = benchScene(side, opts.substeps, 'xpbd');
    const xpbd = await timeDrape(scene, opts.frames, opts.warmup, cpuOptions(opts.threads));
    const xpbd1 = await timeDrape(scene, opts.frames, opts.warmup, cpuOptions(1));
    const xpbdTs = await timeDrape(scene, opts.frames, opts.warmup, { kernel: 'ts' });
    const ms = await timeDrape(benchScene(side, opts.substeps, 'mass-spring'), opts.frames, opts.warmup, { kernel: 'ts' });
    const model = opts.model ? opts.model(modelScene(side)) : modelScene(side);
    const [mx, mx1, mts] = [
      await timeDrape(model, opts.frames, opts.warmup, cpuOptions(opts.threads)),
      await timeDrape(model, opts.frames, opts.warmup, cpuOptions(1)),
      await timeDrape(model, opts.frames, opts.warmup, { kernel: 'ts' }),
    ];
    const row: Row = {
      particlesPerSide: side,
      particles: xpbd.sim.model.particleCount,
      constraints: xpbd.sim.model.restLengths.length,
      xpbd: { ...timing(xpbd), kernel: xpbd.kernel, threads: xpbd.threads },
      xpbd1: { ...timing(xpbd1), kernel: xpbd1.kernel },
      xpbdTs: timing(xpbdTs),
      massSpring: timing(ms),
      model: {
        bending: mx.sim.params.bending, bendingSolve: mx.sim.params.bendingSolve, stretch: mx.sim.params.stretch, substeps: mx.sim.params.substeps,
        xpbd: { ...timing(mx), threads: mx.threads }, xpbd1: timing(mx1), xpbdTs: timing(mts), ratio1: mx1.msPerFrame / xpbd1.msPerFrame,
      },
    };
    if (runJolt) {
      try {
        const j = await runJolt(peerSpec(xpbd.sim, xpbd.sim.params.substeps), opts.frames, opts.warmup);
        row.jolt = {
          name: j.name,
          msPerFrame: j.msPerFrame,
          particleSubstepsPerSecond: (row.particles * opts.substeps * 1000) / j.msPerFrame,
          finite: j.finite,
          stable: isStable(j.finite, j.centroid, xpbd.start, xpbd.sim.model.size),
          centroid: j.centroid,
        };
        row.ratio = xpbd.msPerFrame / j.msPerFrame;
        row.ratio1 = xpbd1.msPerFrame / j.msPerFrame;
      } catch (e) {
        row.peerError = firstLine(e);
      }
    } else if (peerError) {
      row.peerError = peerError;
    }
    rows.push(row);
  }
  if (opts.contention) {
    // every core busy with another process, each bounded (ten minutes per size is far more than a run takes)
    const cores = availableParallelism();
    await whileBusy(cores, 600_000 * opts.sizes.length, async () => {
      for (const row of rows) {
        const scene = benchScene(row.particlesPerSide, opts.substeps, 'xpbd');
        const [xpbd, xpbd1] = await timeDrapePair(scene, opts.frames, opts.warmup, cpuOptions(opts.threads), cpuOptions(1));
        row.busy = {
          xpbd: { ...timing(xpbd), threads: xpbd.threads, aloneFraction: xpbd.aloneFraction },
          xpbd1: timing(xpbd1),
          ratio: xpbd.msPerFrame / xpbd1.msPerFrame,
        };
      }
    });
  }

  const machine = machineLine();
  if (opts.json) {
    out(JSON.stringify({ machine, substeps: opts.substeps, frames: opts.frames, warmup: opts.warmup, threads: opts.threads, rows }));
    return rows;
  }
  const first = rows[0]?.xpbd;
  const kernel = (k: string, t: number) => (k === 'wasm' ? `wasm SIMD, ${t} thread${t === 1 ? '' : 's'}` : 'TypeScript');
  out(`drape bench — cotton dropped on sphere + floor, XPBD ${opts.substeps} substeps (Jolt: ${opts.substeps} iterations),`);
  out(`structural + shear + bend constraints; ${opts.frames} timed frames after ${opts.warmup}; ${machine}`);
  out(`Drape XPBD: ${first ? kernel(first.kernel, first.threads) : ''}; also on 1 thread and in TypeScript. Jolt: 1 thread.`);
  out('stable = finite and the centroid within 10 cloth sizes of its start');
  out('');
  out('| particles | constraints | Drape XPBD ms/frame | particle-substeps/s | Jolt ms/frame | Drape/Jolt | 1 thread ms/frame | 1 thread/Jolt | TypeScript ms/frame | Drape mass-spring ms/frame | stable (Drape / Jolt) | centroid y (Drape / Jolt) |');
  out('|---|---|---|---|---|---|---|---|---|---|---|---|');
  for (const r of rows) {
    const j = r.jolt;
    out(`| ${r.particlesPerSide}×${r.particlesPerSide} | ${r.constraints} | ${fmt(r.xpbd.msPerFrame)} | ${sci(r.xpbd.particleSubstepsPerSecond)} | ` +
      `${j ? fmt(j.msPerFrame) : 'n/a'} | ${r.ratio !== undefined ? fmt(r.ratio) : 'n/a'} | ` +
      `${fmt(r.xpbd1.msPerFrame)} | ${r.ratio1 !== undefined ? fmt(r.ratio1) : 'n/a'} | ${fmt(r.xpbdTs.msPerFrame)} | ${fmt(r.massSpring.msPerFrame)} | ` +
      `${stability(r.xpbd)} / ${j ? stability(j) : 'n/a'} | ` +
      `${fmt(r.xpbd.centroid[1], 3)} / ${j ? (j.finite ? fmt(j.centroid[1], 3) : 'NaN') : 'n/a'} |`);
  }
  const errs = [...new Set(rows.map((r) => r.peerError).filter(Boolean))];
  for (const e of errs) out(`peer: ${e}`);
  out('');
  out(opts.model
    ? "Drape's fabric model with --set on the same cloth (not like for like: the scenes' default bending, stretch and substeps as set, self-contact off unless set):"
    : "Drape's default fabric model on the same cloth (not like for like: the scenes' default bending, stretch and substeps, self-contact off):");
  out('');
  out('| particles | bending | bending solve | stretch | substeps | XPBD ms/frame | threads | 1 thread ms/frame | TypeScript ms/frame | 1 thread / like-for-like 1 thread | stable |');
  out('|---|---|---|---|---|---|---|---|---|---|---|');
  for (const r of rows) {
    const m = r.model;
    out(`| ${r.particlesPerSide}×${r.particlesPerSide} | ${m.bending} | ${m.bendingSolve} | ${m.stretch} | ${m.substeps} | ${fmt(m.xpbd.msPerFrame)} | ${m.xpbd.threads} | ` +
      `${fmt(m.xpbd1.msPerFrame)} | ${fmt(m.xpbdTs.msPerFrame)} | ${fmt(m.ratio1)} | ${stability(m.xpbd)} |`);
  }
  if (opts.contention) {
    out('');
    out(`Busy machine: ${availableParallelism()} other processes keep every core busy (started by the bench, each bounded in time).`);
    out('Drape XPBD with its default threads (each frame with the helpers or alone, whichever measures faster) against one thread:');
    out('');
    out('| particles | default threads ms/frame | threads | frames run alone | 1 thread ms/frame | default / 1 thread |');
    out('|---|---|---|---|---|---|');
    for (const r of rows) {
      const b = r.busy!;
      out(`| ${r.particlesPerSide}×${r.particlesPerSide} | ${fmt(b.xpbd.msPerFrame)} | ${b.xpbd.threads} | ${fmt(100 * b.xpbd.aloneFraction, 0)} % | ${fmt(b.xpbd1.msPerFrame)} | ${fmt(b.ratio)} |`);
    }
  }
  return rows;
}

export interface SceneBenchOptions {
  /** built-in scene names, timed as they are (their cloth, resolution, substeps and colliders) */
  scenes: string[];
  frames: number;
  warmup: number;
  /** threads of the WebAssembly XPBD kernel */
  threads: number | 'auto';
  json: boolean;
}

/** One built-in scene timed on each CPU solver, and what the GPU says of it. */
interface SceneRow {
  scene: string;
  particles: number;
  colliders: number;
  substeps: number;
  xpbd: Timing & { kernel: string; threads: number };
  xpbdTs: Timing;
  massSpring: Timing;
  /** why the GPU solver refuses the scene, null when it takes it (not timed here), 'n/a' when the GPU module does not load */
  gpuRefusal: string | null;
}

/**
 * `drape bench --scenes A,B`: built-in scenes as they are (the app's resolution and substeps), ms per frame for
 * XPBD in the WebAssembly kernel (with the TypeScript phases it leaves, e.g. contact with moving or non-sphere
 * colliders), XPBD in TypeScript and mass-spring; and whether the GPU solver takes the scene. A 60 Hz frame has
 * 16.7 ms: below it the scene runs in real time.
 */
export async function runSceneBench(opts: SceneBenchOptions, out: (s: string) => void): Promise<SceneRow[]> {
  const rows: SceneRow[] = [];
  // the GPU module is loaded only when asked for (as `drape run` does): a machine without it still times the CPU
  let refusal: (scene: Scene) => string | null = () => 'n/a';
  try {
    ({ sceneRefusal: refusal } = await import('../gpu/index.js'));
  } catch { /* the 'n/a' above */ }
  for (const name of opts.scenes) {
    const scene = builtinScene(name);
    const ms = { ...scene, solver: { ...scene.solver, type: 'mass-spring' as const } };
    const xpbd = await timeDrape(scene, opts.frames, opts.warmup, cpuOptions(opts.threads));
    rows.push({
      scene: name,
      particles: xpbd.sim.model.particleCount,
      colliders: scene.colliders.length,
      substeps: xpbd.sim.params.substeps,
      xpbd: { ...timing(xpbd), kernel: xpbd.kernel, threads: xpbd.threads },
      xpbdTs: timing(await timeDrape(scene, opts.frames, opts.warmup, { kernel: 'ts' })),
      massSpring: timing(await timeDrape(ms, opts.frames, opts.warmup, { kernel: 'ts' })),
      gpuRefusal: refusal(scene),
    });
  }
  const machine = machineLine();
  if (opts.json) {
    out(JSON.stringify({ machine, frames: opts.frames, warmup: opts.warmup, threads: opts.threads, rows }));
    return rows;
  }
  const budget = 1000 * FRAME_DT;
  out(`drape bench --scenes — built-in scenes as they are; ${opts.frames} timed frames after ${opts.warmup}; ${machine}`);
  out(`real time: a frame in under ${fmt(budget, 1)} ms; stable = finite and the centroid within 10 cloth sizes of its start`);
  out('');
  out('| scene | particles | colliders | substeps | XPBD (wasm kernel) ms/frame | XPBD TypeScript ms/frame | mass-spring ms/frame | stable (XPBD / TS / mass-spring) | GPU |');
  out('|---|---|---|---|---|---|---|---|---|');
  for (const r of rows) {
    out(`| ${r.scene} | ${r.particles} | ${r.colliders} | ${r.substeps} | ${fmt(r.xpbd.msPerFrame)} (${r.xpbd.kernel}, ${r.xpbd.threads} thread${r.xpbd.threads === 1 ? '' : 's'}) | ` +
      `${fmt(r.xpbdTs.msPerFrame)} | ${fmt(r.massSpring.msPerFrame)} | ${stability(r.xpbd)} / ${stability(r.xpbdTs)} / ${stability(r.massSpring)} | ` +
      `${r.gpuRefusal === null ? 'takes it (time with --backend gpu)' : r.gpuRefusal === 'n/a' ? 'n/a (GPU module not loaded)' : `refused: ${r.gpuRefusal}`} |`);
  }
  return rows;
}

export interface GpuBenchOptions {
  sizes: number[];
  substeps: number;
  frames: number;
  /** threads of the CPU XPBD solver timed beside the GPU */
  threads: number | 'auto';
  /** the scene's changes (the CLI's --set), on the GPU and on the CPU beside it alike; `sets`: their text, for the header */
  model?: (scene: Scene) => Scene;
  sets?: readonly string[];
  json: boolean;
}

/** Largest cloth the CPU solver is timed on beside the GPU (particles per side): beyond it a frame takes seconds. */
const CPU_PEER_MAX_SIDE = 256;

/**
 * `drape bench --backend gpu`: the WebGPU XPBD solver at each size (ms per frame, particle-substeps per second, the
 * bytes a substep moves against the device's measured copy bandwidth), with the CPU XPBD solver in the same run.
 */
export async function runGpuBench(gpu: Gpu, opts: GpuBenchOptions, out: (s: string) => void): Promise<void> {
  const results = await gpu.bench(opts.sizes, opts.substeps, opts.frames, opts.model);
  const cpu: (number | undefined)[] = [];
  for (const r of results) {
    const scene = benchScene(r.size, opts.substeps, 'xpbd');
    cpu.push(r.size <= CPU_PEER_MAX_SIDE
      ? (await timeDrape(opts.model ? opts.model(scene) : scene, Math.max(5, Math.min(opts.frames, 30)), 5, cpuOptions(opts.threads))).msPerFrame
      : undefined);
  }
  const machine = `${gpu.adapter}; host ${machineLine()}`;
  if (opts.json) {
    out(JSON.stringify({ machine, substeps: opts.substeps, frames: opts.frames, sets: opts.sets ?? [], rows: results.map((r, k) => ({ ...r, cpuMsPerFrame: cpu[k] ?? null })) }));
    return;
  }
  const changed = opts.sets?.length ? `, with ${opts.sets.map((s) => plainText(s, 200)).join(' ')}` : '';
  out(`drape bench --backend gpu — cotton on sphere + floor, XPBD ${opts.substeps} substeps${changed}, ${opts.frames} timed frames; ${machine}`);
  out(`CPU column: XPBD in the WebAssembly kernel on ${opts.threads === 'auto' ? 'its automatic thread count' : `up to ${opts.threads} thread${opts.threads === 1 ? '' : 's'}`}`);
  out('');
  out('| particles | springs | dispatches/frame | GPU ms/frame (wall) | GPU ms/frame (timestamps) | particle-substeps/s | MB/substep | copy GB/s | bandwidth floor ms | of floor | CPU XPBD ms/frame | GPU speed-up |');
  out('|---|---|---|---|---|---|---|---|---|---|---|---|');
  results.forEach((r, k) => {
    const c = cpu[k];
    out(`| ${r.size}×${r.size} | ${r.springs} | ${r.dispatchesPerFrame} | ${fmt(r.msPerFrame)} | ${r.gpuMsPerFrame === null ? 'n/a' : fmt(r.gpuMsPerFrame)} | ` +
      `${sci(r.particleSubstepsPerSecond)} | ${fmt(r.bytesPerSubstep / 1e6, 1)} | ${fmt(r.copyBandwidthGBs, 0)} | ${fmt(r.bandwidthFloorMs, 3)} | ` +
      `${fmt(100 * r.fractionOfBandwidthFloor, 1)} % | ${c === undefined ? 'n/a' : fmt(c)} | ${c === undefined ? 'n/a' : `${fmt(c / r.msPerFrame, 1)}×`} |`);
  });
}

export interface SelfContactBenchOptions {
  /** built-in scene names, each timed with solver.selfContact off and on */
  scenes: string[];
  /** faces per side of every cloth of the scene */
  sizes: number[];
  /** frames run from the scene's start (no warm-up: the landing, where the contacts are made, is what costs) */
  frames: number;
  /** threads of the WebAssembly XPBD kernel */
  threads: number | 'auto';
  /** also run the Ten Minute Physics demo's strip with its method and with Drape's (peers/particle-hash.ts) */
  peer: boolean;
  json: boolean;
}

/** One method on the Ten Minute Physics demo's strip: ms per frame and what crosses. */
interface StripRow {
  method: string;
  particles: number;
  msPerFrame: number;
  /** crossing triangle pairs: the most at any 10th frame, and at the last */
  maxIntersections: number;
  intersections: number;
  /** the highest particle at the last frame [m] (the pile's height) */
  top: number;
  finite: boolean;
}

/** The demo's strip: 30 × 200 particles 1 cm apart, hanging with its lowest row 1 cm above the floor, rows waving ±4 mm. */
const STRIP = () => hangingStrip(30, 200, 0.01, 0.01, 0.004);

/**
 * The Ten Minute Physics 15 demo's strip falling into a pile, run for `frames` frames by its own method (a particle
 * hash, in TypeScript) and by Drape (XPBD, cotton, the strip as a mesh cloth) with self-contact on and off. Each run
 * is timed alone, its crossing pairs counted every 10th frame outside the timing.
 */
async function stripComparison(frames: number, threads: number | 'auto'): Promise<StripRow[]> {
  const rows: StripRow[] = [];
  const grid = STRIP();
  const count = (x: Float32Array) => countIntersections(grid.triangles, x);
  const top = (x: Float32Array) => { let m = -Infinity; for (let i = 1; i < x.length; i += 3) m = Math.max(m, x[i]); return m; };
  {
    const cloth = new ParticleHashCloth(grid);
    let ms = 0, most = 0;
    for (let f = 0; f < frames; f++) {
      const t0 = performance.now();
      cloth.step(FRAME_DT);
      ms += performance.now() - t0;
      if (f % 10 === 9) most = Math.max(most, count(cloth.positions));
    }
    rows.push({
      method: 'Ten Minute Physics 15: particle hash, 1 cm particles, speed cap (TypeScript)', particles: cloth.n, msPerFrame: ms / frames,
      maxIntersections: most, intersections: count(cloth.positions), top: top(cloth.positions), finite: cloth.positions.every(Number.isFinite),
    });
  }
  for (const on of [true, false]) {
    const scene = validateScene({
      name: 'strip', cloth: { shape: 'mesh', mesh: 'strip.obj', position: [0, 1.005, 0] }, material: { fabric: 'cotton' },
      solver: { selfContact: on }, colliders: [{ type: 'floor', height: 0 }],
    });
    const sim = new Simulation(scene, { ...cpuOptions(threads), meshes: () => ({ positions: grid.positions, triangles: grid.triangles }) });
    try {
      await sim.whenReady();
      let ms = 0, most = 0;
      for (let f = 0; f < frames; f++) {
        const t0 = performance.now();
        sim.advance(1);
        ms += performance.now() - t0;
        if (f % 10 === 9) most = Math.max(most, countIntersections(sim.model.triangles, sim.state.positions));
      }
      rows.push({
        method: `Drape XPBD, cotton, self-contact ${on ? 'on' : 'off'} (${sim.kernel}, ${sim.threads} thread${sim.threads === 1 ? '' : 's'})`,
        particles: sim.model.particleCount, msPerFrame: ms / frames, maxIntersections: most,
        intersections: countIntersections(sim.model.triangles, sim.state.positions), top: top(sim.state.positions), finite: isFinite3(sim.state),
      });
    } finally {
      sim.dispose();
    }
  }
  return rows;
}

/** One scene at one resolution, with self-contact and without. */
interface SelfContactRow {
  scene: string;
  /** faces per side of each cloth */
  resolution: number;
  particles: number;
  kernel: string;
  threads: number;
  /** substeps per frame without self-contact and with it (raised for it where solver.selfContactSpeed needs more) */
  offSubsteps: number;
  onSubsteps: number;
  /** ms per frame without self-contact, and with it, timed in alternating blocks of 10 frames */
  offMsPerFrame: number;
  onMsPerFrame: number;
  /** on / off */
  ratio: number;
  /** crossing triangle pairs (countIntersections) at the last frame without self-contact */
  offIntersections: number;
  /** with self-contact: the most at any 10th frame, and at the last */
  onMaxIntersections: number;
  onIntersections: number;
  finite: boolean;
}

/** `scene` (a built-in's validated copy) with every cloth at `resolution` faces per side and self-contact `on`. */
function selfContactScene(name: string, resolution: number, on: boolean): Scene {
  const doc = sceneDocument(builtinScene(name)) as Record<string, unknown> & { cloth?: Record<string, unknown>; cloths?: { cloth?: Record<string, unknown> }[] };
  for (const entry of doc.cloths ?? [doc]) entry.cloth = { ...entry.cloth, resolution };
  doc.solver = { ...(doc.solver as object), selfContact: on };
  return validateScene(doc, `scene '${name}'`);
}

/**
 * `drape bench --self-contact`: each scene at each resolution run from its start with self-contact off and on, the
 * two in alternating blocks of 10 frames (so both meet the same machine), the crossing triangle pairs counted
 * between blocks (outside the timing): the cost of self-contact and what it saves.
 */
export async function runSelfContactBench(opts: SelfContactBenchOptions, out: (s: string) => void): Promise<SelfContactRow[]> {
  const rows: SelfContactRow[] = [];
  for (const name of opts.scenes) {
    for (const resolution of opts.sizes) {
      const sims = [false, true].map((on) => new Simulation(selfContactScene(name, resolution, on), cpuOptions(opts.threads)));
      try {
        await Promise.all(sims.map((s) => s.whenReady()));
        const ms = [0, 0];
        let onMax = 0;
        for (let done = 0, k = 0; done < opts.frames; done += 10, k++) {
          const n = Math.min(10, opts.frames - done);
          for (const i of k % 2 ? [1, 0] : [0, 1]) {
            const t0 = performance.now();
            sims[i].advance(n);
            ms[i] += performance.now() - t0;
          }
          onMax = Math.max(onMax, countIntersections(sims[1].model.triangles, sims[1].state.positions));
        }
        const [off, on] = sims, frames = Math.max(1, opts.frames);
        rows.push({
          scene: name,
          resolution,
          particles: on.model.particleCount,
          kernel: on.kernel,
          threads: on.threads,
          offSubsteps: off.params.substeps,
          onSubsteps: on.params.substeps,
          offMsPerFrame: ms[0] / frames,
          onMsPerFrame: ms[1] / frames,
          ratio: ms[1] / ms[0],
          offIntersections: countIntersections(off.model.triangles, off.state.positions),
          onMaxIntersections: onMax,
          onIntersections: countIntersections(on.model.triangles, on.state.positions),
          finite: isFinite3(off.state) && isFinite3(on.state),
        });
      } finally {
        for (const s of sims) s.dispose();
      }
    }
  }
  const strip = opts.peer ? await stripComparison(opts.frames, opts.threads) : undefined;
  const machine = machineLine();
  if (opts.json) {
    out(JSON.stringify({ machine, frames: opts.frames, threads: opts.threads, rows, ...(strip ? { strip } : {}) }));
    return rows;
  }
  out(`drape bench --self-contact — each scene from its start for ${opts.frames} frames, self-contact off and on in alternating blocks of 10 frames; ${machine}`);
  out('crossing pairs: triangles sharing no vertex that cross (countIntersections), with self-contact the most at any 10th frame');
  out('');
  out('| scene | faces per side | particles | XPBD kernel | substeps off / on | off ms/frame | on ms/frame | on / off | crossing pairs off (last frame) | on (most at a 10th frame) | on (last frame) | finite |');
  out('|---|---|---|---|---|---|---|---|---|---|---|---|');
  for (const r of rows) {
    out(`| ${r.scene} | ${r.resolution} | ${r.particles} | ${r.kernel}, ${r.threads} thread${r.threads === 1 ? '' : 's'} | ${r.offSubsteps} / ${r.onSubsteps} | ${fmt(r.offMsPerFrame)} | ${fmt(r.onMsPerFrame)} | ` +
      `${fmt(r.ratio, 1)}× | ${r.offIntersections} | ${r.onMaxIntersections} | ${r.onIntersections} | ${r.finite ? 'yes' : 'NO'} |`);
  }
  if (strip) {
    out('');
    out(`The Ten Minute Physics 15 demo's strip (30 × 200 particles 1 cm apart) falling into a pile, ${opts.frames} frames, each method alone:`);
    out('');
    out('| method | particles | ms/frame | crossing pairs (most at a 10th frame) | (last frame) | pile height m | finite |');
    out('|---|---|---|---|---|---|---|');
    for (const r of strip) out(`| ${r.method} | ${r.particles} | ${fmt(r.msPerFrame)} | ${r.maxIntersections} | ${r.intersections} | ${fmt(r.top, 3)} | ${r.finite ? 'yes' : 'NO'} |`);
  }
  return rows;
}

export interface HangingBenchOptions {
  /** faces per side of the 1 m sheet */
  faces: number;
  /** the fabrics hung, by name (material.fabric) */
  fabrics: string[];
  /** simulated time a run may take to settle [s] */
  seconds: number;
  /** JoltPhysics.js iteration counts tried, ascending, until one settles */
  joltIterations: number[];
  /** run JoltPhysics.js beside Drape */
  peer: boolean;
  /** threads of the WebAssembly XPBD kernel */
  threads: number | 'auto';
  json: boolean;
}

/** How one solver's hanging sheet approached its static elongation. */
export interface Settling {
  /** what ran: 'Drape …' or 'Jolt, N iterations' */
  solver: string;
  /**
   * simulated time [s] from which the elongation stayed within 25 % of theory for the rest of the run, the run going
   * on for a further second to show it stays; null: never within the run's time
   */
  settledAt: number | null;
  /** wall time to simulate up to settledAt [s] (null: never) */
  wallSeconds: number | null;
  msPerFrame: number;
  /** elongation / theory at the end of the run (NaN once not finite: null in --json) */
  ratio: number;
}

interface HangingRow {
  fabric: string;
  faces: number;
  /** ρ_A·g·L²/(2k) [m]: how far a 1 m sheet of the fabric hanging from its top edge lengthens at rest */
  theory: number;
  runs: Settling[];
  peerError?: string;
}

/** Within this fraction of the static elongation counts as settled (issue 10: the stretch target's 25 %). */
const SETTLED_WITHIN = 0.25;

/** The 1 m hanging sheet: pinned along its top edge, no colliders, no self-contact (it never meets itself). */
function hangingSheet(fabric: string, faces: number, solver: Partial<Scene['solver']> = {}): Scene {
  return validateScene({
    name: 'hanging-sheet',
    description: 'A 1 m sheet hanging from its top edge, for its static elongation',
    cloth: { resolution: faces, width: 1, height: 1, orientation: 'hanging', position: [0, 1.5, 0] },
    material: { fabric },
    solver: { ...solver, selfContact: false },
    colliders: [],
    pins: ['top-edge'],
  });
}

/** The sheet's measure: its top and bottom rows' middle halves (the sides pull in, the corners do not count). */
function hangingRows(rest: Float32Array): { top: number[]; bottom: number[]; height: number } {
  let ymin = Infinity, ymax = -Infinity, xmin = Infinity, xmax = -Infinity;
  for (let i = 0; i < rest.length; i += 3) {
    ymin = Math.min(ymin, rest[i + 1]); ymax = Math.max(ymax, rest[i + 1]);
    xmin = Math.min(xmin, rest[i]); xmax = Math.max(xmax, rest[i]);
  }
  const mid = 0.5 * (xmin + xmax), quarter = 0.25 * (xmax - xmin) + 1e-9, eps = 1e-6 * (ymax - ymin);
  const top: number[] = [], bottom: number[] = [];
  for (let i = 0; i < rest.length / 3; i++) {
    if (Math.abs(rest[3 * i] - mid) > quarter) continue;
    if (rest[3 * i + 1] > ymax - eps) top.push(i);
    else if (rest[3 * i + 1] < ymin + eps) bottom.push(i);
  }
  return { top, bottom, height: ymax - ymin };
}

function elongation(x: Float32Array, rows: { top: number[]; bottom: number[]; height: number }): number {
  let t = 0, b = 0;
  for (const i of rows.top) t += x[3 * i + 1];
  for (const i of rows.bottom) b += x[3 * i + 1];
  return t / rows.top.length - b / rows.bottom.length - rows.height;
}

/**
 * Watches a hanging sheet settle: `step(n)` runs n frames and returns their wall ms, `read()` the positions. Stops a
 * second after the elongation entered the 25 % band for good, or at `seconds` of simulated time.
 */
function watchSettling(solver: string, theory: number, rows: ReturnType<typeof hangingRows>, seconds: number,
  step: (frames: number) => number, read: () => Float32Array): Settling {
  const frames = Math.round(seconds / FRAME_DT), hold = Math.round(1 / FRAME_DT);
  let wall = 0, since = -1, wallAtSince = 0, ratio = NaN, f = 0;
  for (; f < frames; f++) {
    wall += step(1);
    ratio = elongation(read(), rows) / theory;
    if (!Number.isFinite(ratio)) { since = -1; f++; break; }
    if (Math.abs(ratio - 1) <= SETTLED_WITHIN) {
      if (since < 0) { since = f; wallAtSince = wall; }
      if (f - since >= hold) { f++; break; }
    } else since = -1;
  }
  const settled = since >= 0 && f - since > hold;
  return {
    solver,
    settledAt: settled ? (since + 1) * FRAME_DT : null,
    wallSeconds: settled ? wallAtSince / 1000 : null,
    msPerFrame: wall / Math.max(1, f),
    ratio,
  };
}

/**
 * `drape bench --hanging`: how long a 1 m sheet hanging from its top edge takes to reach its static elongation,
 * ρ_A·g·L²/(2k), within 25 % (issue 10's stretch target): Drape at its default solver settings (the sweep after the
 * coarse correction, solver.stretch 'two-level'), with the sweep alone ('gauss-seidel') and with the springs solved
 * together ('global'), and JoltPhysics.js on the same particles and constraints with
 * as many iterations as it needs (the first of --jolt-iterations that settles), or never within the run's time.
 */
export async function runHangingBench(opts: HangingBenchOptions, out: (s: string) => void): Promise<HangingRow[]> {
  const { peer, error: peerError } = await loadJoltPeer(opts.peer);
  const joltCloth = peer?.JoltCloth;
  const rows: HangingRow[] = [];
  for (const fabric of opts.fabrics) {
    const base = hangingSheet(fabric, opts.faces);
    // the sheet as the TypeScript reference builds it: its weight per area for the theory, its constraints for Jolt
    const ref = new Simulation(base, { kernel: 'ts' });
    let row: HangingRow;
    try {
      let mass = 0;
      for (const m of ref.params.particleMass) mass += m;
      const theory = ((mass / ref.model.area) * Math.hypot(...base.gravity) * base.cloth.height ** 2) / (2 * base.material.structuralStiffness);
      row = { fabric, faces: opts.faces, theory, runs: [] };
      const rowsOf = hangingRows(ref.model.restPositions);
      const settings: [string, Partial<Scene['solver']>][] = [
        [`Drape default (xpbd, ${base.solver.substeps} substeps × ${base.solver.iterations}, ${base.solver.stretch})`, {}],
        ['Drape solver.stretch gauss-seidel', { stretch: 'gauss-seidel' }],
        ['Drape solver.stretch global', { stretch: 'global' }],
      ];
      for (const [name, solver] of settings) {
        const sim = new Simulation(hangingSheet(fabric, opts.faces, solver), cpuOptions(opts.threads));
        try {
          await sim.whenReady();
          row.runs.push(watchSettling(name, theory, rowsOf, opts.seconds, (n) => {
            const t0 = performance.now();
            sim.advance(n);
            return performance.now() - t0;
          }, () => sim.state.positions));
        } finally {
          sim.dispose();
        }
      }
      if (joltCloth) {
        try {
          const x = new Float32Array(3 * ref.model.particleCount);
          for (const iterations of opts.joltIterations) {
            const cloth = await joltCloth.create(peerSpec(ref, iterations, false));
            try {
              const run = watchSettling(`Jolt, ${iterations} iterations`, theory, rowsOf, opts.seconds, (n) => cloth.step(n), () => cloth.positions(x));
              row.runs.push(run);
              if (run.settledAt !== null) break;
            } finally {
              cloth.dispose();
            }
          }
        } catch (e) {
          row.peerError = firstLine(e);
        }
      } else if (peerError) row.peerError = peerError;
    } finally {
      ref.dispose();
    }
    rows.push(row);
  }
  const machine = machineLine();
  if (opts.json) {
    out(JSON.stringify({ machine, faces: opts.faces, seconds: opts.seconds, within: SETTLED_WITHIN, threads: opts.threads, rows }));
    return rows;
  }
  out(`drape bench --hanging — a 1 m sheet of ${opts.faces}² faces hanging from its top edge: the simulated time until its`);
  out(`elongation stays within ${100 * SETTLED_WITHIN} % of ρ_A·g·L²/(2k) (checked for a second more), and the wall time to get there;`);
  out(`each run at most ${opts.seconds} s of simulated time; Jolt on the same particles and constraints, the fewest iterations that settle; ${machine}`);
  out('');
  out('| fabric | theory [mm] | solver | settled after [s simulated] | wall time to settle [s] | ms/frame | elongation / theory at the end |');
  out('|---|---|---|---|---|---|---|');
  for (const r of rows) {
    for (const run of r.runs) {
      out(`| ${r.fabric} | ${fmt(1000 * r.theory, 3)} | ${run.solver} | ${run.settledAt === null ? `never (${opts.seconds} s)` : fmt(run.settledAt)} | ` +
        `${run.wallSeconds === null ? '—' : fmt(run.wallSeconds)} | ${fmt(run.msPerFrame)} | ${Number.isFinite(run.ratio) ? fmt(run.ratio) : 'NaN'} |`);
    }
    if (r.peerError) out(`| ${r.fabric} | ${fmt(1000 * r.theory, 3)} | Jolt | n/a: ${r.peerError} | | | |`);
  }
  return rows;
}
