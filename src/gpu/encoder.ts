/**
 * The GPU as a backend of the frame loop (core/frame.ts): which phases of the schedule it implements (GPU_PHASES),
 * and the encoder that turns each phase of a frame into its kernel dispatches, all substeps of the frame in one
 * compute pass of one command buffer.
 */
import type {} from 'webgpu';
import { runFrame, type FrameVars, type PhaseBackend } from '../core/frame.js';
import { createColliders } from '../core/colliders/index.js';
import type { ClothModel } from '../core/model.js';
import { differingClothField, type Scene } from '../core/scene.js';
import { perClothRefusal, type SimParams } from '../core/params.js';
import { PHASE, PHASE_COUNT, phasePasses, type BackendPhases, type PhaseId, type PhaseLog } from '../core/schedule.js';
import type { ClothState } from '../core/state.js';
import type { ClothBuffers } from './buffers.js';
import { gpuCollider, type ColliderTables } from './colliders.js';
import { GlobalBendingTables } from './global-bending.js';
import { GlobalStretchTables } from './global-stretch.js';
import { CoarseTables } from './coarse-stretch.js';
import { meshRefusal } from './meshes.js';
import { RECORD_STRIDE, SCAN_BLOCK, SELF_EDGE_PASSES, WORKGROUP_SIZE, workgroupsFor, type KernelName } from './layout.js';
import type { SelfRecords, UniformTables } from './uniforms.js';

/** The coarse correction's kernels that make the matrix anew and solve again, in coarseArgs' order (coarse-stretch.ts). */
const COARSE_REMAKE = ['coarseTouch', 'coarseAssemble', 'coarseFactor', 'coarseInvert', 'coarseSolve'] as const;

/** The shapes the GPU has, for its refusals. */
const GPU_SHAPES = 'sphere, floor, plane, box, capsule, cylinder and mesh';

/**
 * Why the GPU cannot do contact against these colliders (a shape its kernels do not know, a mesh whose hierarchy
 * is deeper than their walks go), or null.
 */
function contactRefusal(params: SimParams): string | null {
  const colliders = params.colliders;
  for (let k = 0; k < colliders.length; k++) {
    if (gpuCollider(colliders[k]) === null) return `collider type '${colliders[k].type}' is not supported on the GPU (it has ${GPU_SHAPES})`;
    const mesh = meshRefusal(colliders[k]);
    if (mesh !== null) return `the mesh of colliders[${k}] does not fit the GPU's walk: ${mesh}`;
  }
  return null;
}

/**
 * Why the GPU cannot step this scene at all, in one line naming what it lacks (the solver, a collider shape and its
 * place in the list), or null. The CLI says it before opening a device; the app's backend choice says it when it
 * falls back to the CPU.
 */
export function sceneRefusal(scene: Scene): string | null {
  if (scene.solver.type !== 'xpbd') return `the ${scene.solver.type} solver runs on the CPU only`;
  const differs = differingClothField(scene);
  if (differs) return `cloths that differ in their contact or spring values run on the CPU only (${differs})`;
  return colliderRefusal(scene);
}

/**
 * The colliders' part of sceneRefusal: a shape the GPU's kernels do not know, named with its place in the list.
 * Every collider the GPU knows may move and carry pins. A mesh collider is taken by its type, without reading its
 * file: a mesh whose hierarchy is deeper than the GPU's walks go (layout.ts MESH_STACK, far deeper than binned SAH
 * makes of a million triangles) is refused with its params (contactRefusal).
 */
export function colliderRefusal(scene: Scene): string | null {
  const specs = scene.colliders;
  const k = specs.findIndex((spec) => spec.type !== 'mesh' && gpuCollider(createColliders([spec])[0]) === null);
  return k >= 0 ? `${specs[k].type} colliders run on the CPU only (colliders[${k}]; the GPU has ${GPU_SHAPES})` : null;
}

/**
 * The phases of the schedule the GPU implements: every phase of XPBD, the springs solved one at a time (after a
 * coarse correction or not) or together,
 * stencil bending (solver.bending 'hinges' or 'laplacian', one stencil at a time or together) and self-contact
 * included. Its cloth lives in GPU buffers, so it cannot leave a phase to the TypeScript reference: a frame that needs
 * one is refused (the mass-spring solver, a collider shape it does not know). Self-contact reads one thickness and
 * friction for the whole model, as contact does: cloths that differ in them are refused by the contact phase already.
 */
export const GPU_PHASES: BackendPhases = {
  name: 'GPU solver',
  where: 'on the GPU',
  sharesMemory: false,
  solvers: ['xpbd'],
  phases: (1 << PHASE.begin) | (1 << PHASE.wind) | (1 << PHASE.integrate) | (1 << PHASE.carry) | (1 << PHASE.grab) |
    (1 << PHASE.coarseStretch) | (1 << PHASE.distance) | (1 << PHASE.globalStretch) | (1 << PHASE.bending) | (1 << PHASE.globalBending) | (1 << PHASE.tethers) |
    (1 << PHASE.stretchLimit) |
    (1 << PHASE.selfContact) | (1 << PHASE.contact) | (1 << PHASE.contactTriangles) | (1 << PHASE.velocities),
  refusal: (id: PhaseId, _model: ClothModel, params: SimParams) =>
    (id === PHASE.contact || id === PHASE.contactTriangles ? contactRefusal(params) : null) ?? perClothRefusal(id, params),
};

const CARRY_OR_CONTACT = (1 << PHASE.carry) | (1 << PHASE.contact) | (1 << PHASE.contactTriangles);

/** Encodes a cloth's frames: the frame loop's phases as dispatches. */
export class FrameEncoder implements PhaseBackend {
  /** the phases it implements */
  readonly phases = GPU_PHASES;
  private readonly device: GPUDevice;
  private readonly model: ClothModel;
  private readonly pipelines: Record<KernelName, GPUComputePipeline>;
  private readonly buffers: ClothBuffers;
  private readonly uniforms: UniformTables;
  private readonly colliders: ColliderTables;
  /** the global bending step's tables (the CPU's factor on the GPU; GpuClothSolver.step makes them current) */
  readonly globalBending: GlobalBendingTables;
  /** the global stretch step's tables (the CPU's factor on the GPU; GpuClothSolver.step makes them current) */
  readonly globalStretch: GlobalStretchTables;
  /** the coarse correction's tables (GpuClothSolver.step makes them on the first frame that needs them) */
  readonly coarse: CoarseTables;
  /** the compute pass of the frame being encoded */
  private pass: GPUComputePassEncoder | undefined;

  /** An encoder over a cloth's buffers and uniform tables. */
  constructor(
    device: GPUDevice, model: ClothModel, pipelines: Record<KernelName, GPUComputePipeline>, buffers: ClothBuffers,
    uniforms: UniformTables, colliders: ColliderTables,
  ) {
    this.device = device;
    this.model = model;
    this.pipelines = pipelines;
    this.buffers = buffers;
    this.uniforms = uniforms;
    this.colliders = colliders;
    this.globalBending = new GlobalBendingTables(device, model, buffers);
    this.globalStretch = new GlobalStretchTables(device, model, buffers);
    this.coarse = new CoarseTables(device, model, buffers);
  }

  /**
   * Encodes and submits one frame of dt [s]: the frame's inputs written, the grabbed particle's start copied, the
   * frame loop's phases dispatched in one compute pass (timed with `timestampWrites` where given), then the vertex
   * normals; the colliders' poses of its substeps (made as they are encoded) written before the submit. The frame
   * loop counts state.time and state.substeps; `log` receives the phases encoded.
   */
  frame(state: ClothState, params: SimParams, dt: number, timestampWrites: GPUComputePassTimestampWrites | undefined, log: PhaseLog | undefined): void {
    this.uniforms.writeFrame(state, params, dt, this.colliders.beginFrame(params));
    const encoder = this.device.createCommandEncoder({ label: 'drape step' });
    const grabbed = state.grabbed;
    if (grabbed >= 0 && grabbed < this.model.particleCount) {
      encoder.copyBufferToBuffer(this.buffers.buffers.positions, grabbed * 16, this.buffers.buffers.grabStart, 0, 16);
    }
    this.pass = encoder.beginComputePass(timestampWrites ? { label: 'drape step', timestampWrites } : { label: 'drape step' });
    runFrame(this.model, state, params, dt, this, log);
    this.dispatch('normals', this.model.particleCount, 0, 0);
    this.pass.end();
    this.pass = undefined;
    this.colliders.endFrame(params);
    this.device.queue.submit([encoder.finish()]);
  }

  /** The phases of `mask` for substep frame.sub, as dispatches into the frame's pass, in schedule order. */
  run(mask: number, model: ClothModel, state: ClothState, params: SimParams, frame: FrameVars, log: PhaseLog | undefined): void {
    const so = frame.sub * RECORD_STRIDE;
    const particles = model.particleCount;
    const u = this.uniforms;
    // the colliders where they are at this substep's end (state.time is its start), for carry and contact
    if ((mask & CARRY_OR_CONTACT) !== 0) this.colliders.poseSubstep(params, frame.sub, state.time, frame.h);
    for (let id = 0; id < PHASE_COUNT; id++) {
      if ((mask & (1 << id)) === 0) continue;
      switch (id) {
        case PHASE.begin:
          // tethers are found on the CPU when the pins changed, as the reference's begin does
          if (state.tethersStale) this.buffers.writePins(state);
          this.dispatch('prepare', particles, so, 0);
          break;
        case PHASE.wind: this.dispatch('wind', model.triangles.length / 3, so, 0); break;
        case PHASE.integrate: this.dispatch('integrate', particles, so, 0); break;
        case PHASE.carry: this.dispatch('carry', params.carried.particles.length, so, 0); break;
        case PHASE.grab: {
          if (frame.sub === 0) {
            // where the grab carries its particle by the frame's end, kept out of the colliders as they stand then
            // (runFrame's grabFrameTarget and keepGrabOutside, on the GPU since the frame-start position is there):
            // the last substep's record holds the colliders' frame-end poses; over every particle run of colliders
            // in order, twice (keepGrabOutside's two rounds)
            const last = (frame.substeps - 1) * RECORD_STRIDE;
            this.dispatch('grabFrame', 1, last, 0);
            for (let round = 0; round < 2; round++) {
              for (const c of u.collidePasses) {
                if (c.triangles) continue;
                const kernel = c.kernel === 'collideMeshParticles' ? 'grabOutsideMesh' : 'grabOutside';
                this.dispatch(kernel, 1, last, c.record * RECORD_STRIDE);
              }
            }
          }
          this.dispatch('grab', 1, so, 0);
          break;
        }
        case PHASE.coarseStretch: {
          // each spring's direction and residual, each aggregate's row; in the frame's first substep the matrix
          // assembled, factored (a workgroup per cloth), its diagonal blocks inverted and both triangular solves made
          // (a workgroup per cloth); in the later ones the solve with the last factor, the check of its step, and the
          // same five kernels again, dispatched indirectly: no workgroups unless it overshoots (coarseArgs); each
          // spring's λ, the particles moved
          const t = this.coarse.layout!, springs = model.restLengths.length;
          this.dispatch('coarseDirections', springs, so, 0);
          this.dispatch('coarseRows', t.aggregates, so, 0);
          if (frame.sub > 0) {
            this.dispatchGroups('coarseSolve', t.cloths, so, 0);
            this.dispatch('coarseCheckParts', Math.max(particles, t.aggregates), so, 0);
            this.dispatchGroups('coarseCheck', 1, so, 0);
            for (let k = 0; k < COARSE_REMAKE.length; k++) this.bind(COARSE_REMAKE[k], so, 0).dispatchWorkgroupsIndirect(this.buffers.buffers.coarseArgs, 12 * k);
          } else {
            this.dispatch('coarseTouch', t.pairs, so, 0);
            this.dispatch('coarseAssemble', t.aggregates, so, 0);
            this.dispatchGroups('coarseFactor', t.cloths, so, 0);
            this.dispatch('coarseInvert', t.aggregates, so, 0);
            this.dispatchGroups('coarseSolve', t.cloths, so, 0);
          }
          this.dispatch('coarseLambda', springs, so, 0);
          this.dispatch('coarseMove', particles, so, 0);
          break;
        }
        case PHASE.distance: {
          // λ from 0 in the first pass, unless the coarse correction has just set it
          const passes = phasePasses(PHASE.distance, params), fromCoarse = params.stretch === 'two-level';
          for (let it = 0; it < passes; it++) {
            for (const r of u.batchRecords) this.dispatch('solve', r.count, so, (it === 0 && !fromCoarse ? r.first : r.later) * RECORD_STRIDE);
          }
          break;
        }
        case PHASE.globalStretch: {
          // y kept, then per pass: the springs' force terms, the right-hand side by row, both triangular solves (one
          // workgroup), x = y + Δx
          this.dispatch('stretchStart', particles, so, 0);
          const passes = phasePasses(PHASE.globalStretch, params);
          for (let it = 0; it < passes; it++) {
            this.dispatch('stretchForces', model.restLengths.length, so, 0);
            this.dispatch('stretchGather', particles, so, 0);
            this.dispatch('stretchSolve', 1, so, 0);
            this.dispatch('stretchApply', particles, so, 0);
          }
          break;
        }
        case PHASE.bending: {
          // batch by batch like the springs; stencilRecords is empty unless params.bending is a stencil model
          const passes = phasePasses(PHASE.bending, params);
          for (let it = 0; it < passes; it++) {
            for (const r of u.stencilRecords) {
              this.dispatch('bending', r.count, so, (it === 0 ? r.first : r.later) * RECORD_STRIDE);
            }
          }
          break;
        }
        case PHASE.globalBending: {
          // the stencils' force terms, the right-hand side by row, both triangular solves (one workgroup), Δx applied
          this.dispatch('bendingForces', this.globalBending.stencilCount, so, 0);
          this.dispatch('bendingGather', particles, so, 0);
          this.dispatch('factorSolve', 1, so, 0);
          this.dispatch('bendingApply', particles, so, 0);
          break;
        }
        case PHASE.tethers: if (this.buffers.hasTethers) this.dispatch('tethers', particles, so, 0); break;
        case PHASE.stretchLimit: {
          const passes = phasePasses(PHASE.stretchLimit, params);
          for (let it = 0; it < passes; it++) {
            for (const r of u.batchRecords) if (r.stretch) this.dispatch('limitStretch', r.count, so, r.first * RECORD_STRIDE);
          }
          break;
        }
        case PHASE.selfContact: {
          // the triangles' grid, the particles against it; then the edges' grid (from the positions the particle
          // pass left, as the CPU's edge boxes are), the edges against it (no records: a distance of 0, nothing to do)
          const r = u.selfRecords;
          if (!r) break;
          this.buildSelfGrid(r, r.triangles, r.triangleCount, so);
          this.dispatch('selfFindPoints', particles, so, 0);
          this.resolveSelfPairs('selfPoints', so, 1);
          this.buildSelfGrid(r, r.edges, r.edgeCount, so);
          this.dispatch('selfFindEdges', r.edgeCount, so, 0);
          this.resolveSelfPairs('selfEdges', so, SELF_EDGE_PASSES);
          break;
        }
        case PHASE.contact:
        case PHASE.contactTriangles: {
          // the particle passes (every collider, in order), then in the next phase the triangle passes
          const triangles = id === PHASE.contactTriangles;
          for (const c of u.collidePasses) if (c.triangles === triangles) this.dispatch(c.kernel, c.count, so, c.record * RECORD_STRIDE);
          break;
        }
        case PHASE.velocities: this.dispatch('velocities', particles, so, 0); break;
        default: continue; // not a GPU phase: assignPhases never hands it one
      }
      log?.push(id, false);
    }
  }

  /**
   * Dispatches one build of the self-contact grid (selfGrid.wgsl) over `count` primitives, those of Pass record
   * `record` (the triangles or the edges), in substep record `so`: boxes and cell size, counts, the prefix sum of
   * the buckets (blocks, their totals, the sum made global), the scatter.
   */
  private buildSelfGrid(r: SelfRecords, record: number, count: number, so: number): void {
    const po = record * RECORD_STRIDE;
    this.dispatch('selfBoxes', count, so, po);
    this.dispatch('selfCount', count, so, po);
    this.dispatch('selfScan', (r.buckets / SCAN_BLOCK) * WORKGROUP_SIZE, so, po);
    this.dispatch('selfScanTotals', WORKGROUP_SIZE, so, po);
    this.dispatch('selfScanAdd', r.buckets, so, po);
    this.dispatch('selfScatter', count, so, po);
  }

  /**
   * Dispatches `passes` self-contact pair passes over the candidates just listed: their indirect arguments from
   * their count (selfPairArgs), then `passes` times `kernel` over them (one pair per thread), every particle moved by
   * the mean of its corrections (selfApply) — Jacobi iterations over one list (SELF_EDGE_PASSES).
   */
  private resolveSelfPairs(kernel: 'selfPoints' | 'selfEdges', so: number, passes: number): void {
    this.dispatch('selfPairArgs', 1, so, 0);
    for (let k = 0; k < passes; k++) {
      this.bind(kernel, so, 0).dispatchWorkgroupsIndirect(this.buffers.buffers.selfArgs, 0);
      this.dispatch('selfApply', this.model.particleCount, so, 0);
    }
  }

  /** Recomputes the vertex normals from the current positions, in a submit of its own. */
  refreshNormals(): void {
    const encoder = this.device.createCommandEncoder({ label: 'drape normals' });
    this.pass = encoder.beginComputePass({ label: 'drape normals' });
    this.dispatch('normals', this.model.particleCount, 0, 0);
    this.pass.end();
    this.pass = undefined;
    this.device.queue.submit([encoder.finish()]);
  }

  /** The frame's pass with `kernel`'s pipeline and its bind groups set, at the given Substep and Pass records. */
  private bind(kernel: KernelName, substepOffset: number, passOffset: number): GPUComputePassEncoder {
    const pass = this.pass!;
    pass.setPipeline(this.pipelines[kernel]);
    pass.setBindGroup(0, this.uniforms.group, [substepOffset, passOffset]);
    pass.setBindGroup(1, this.buffers.storageGroups[kernel]);
    return pass;
  }

  /** Dispatches `groups` workgroups of `kernel` (one per cloth, or one) with the given Substep and Pass records. */
  private dispatchGroups(kernel: KernelName, groups: number, substepOffset: number, passOffset: number): void {
    if (groups > 0) this.bind(kernel, substepOffset, passOffset).dispatchWorkgroups(groups);
  }

  /** Dispatches `kernel` over `count` threads with the given Substep and Pass records (spilling into y when large). */
  private dispatch(kernel: KernelName, count: number, substepOffset: number, passOffset: number): void {
    if (count <= 0) return;
    const pass = this.bind(kernel, substepOffset, passOffset);
    const [x, y] = workgroupsFor(count);
    pass.dispatchWorkgroups(x, y);
  }
}
