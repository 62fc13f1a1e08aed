/**
 * Where a simulation runs, and how its cloths move from one driver to another: the rule the app's backend
 * (src/app/backend.ts) and DrapeWorld (src/three/world.ts) share, so the page and the addon choose alike.
 */
import type { ClothState, Scene } from '../../core/index.js';
import { GpuSim } from './gpu-sim.js';
import { SimClient, type Mirror, type SimDriver } from './sim-client.js';

/** 'auto': the GPU where there is a hardware WebGPU device and the scene allows; 'gpu': any WebGPU device; 'cpu'. */
export type BackendChoice = 'auto' | 'gpu' | 'cpu';

/** What the page offers the GPU driver. */
export interface GpuOffer {
  /** why there is no WebGPU device to simulate on (null when there is one) */
  readonly missing: string | null;
  /** the device is a software fallback (SwiftShader, llvmpipe: gpu/adapter.ts), slower than the CPU worker */
  readonly software: boolean;
}

/** How the notes speak to whoever chose. */
export interface ChoiceWording {
  /** how to run on a software device anyway (the panel's or the option's words) */
  readonly override: string;
  /**
   * whether 'auto' says why it runs on the CPU when only the machine is the reason (no device); what the scene
   * needs is always said, whatever the machine
   */
  readonly explainAuto: boolean;
}

/** The driver kind `choice` gets for `scene` with what the page offers, and why it is not the GPU ('' when it is, or when nothing needs saying). */
export function chooseBackend(choice: BackendChoice, scene: Scene, gpu: GpuOffer, wording: ChoiceWording): { kind: 'cpu' | 'gpu'; note: string } {
  if (choice === 'cpu') return { kind: 'cpu', note: '' };
  // what the scene needs comes before the device: it is the reason on any machine
  const sceneWhy = GpuSim.supports(scene);
  const why = sceneWhy ?? gpu.missing;
  if (why) return { kind: 'cpu', note: choice === 'gpu' || why === sceneWhy || wording.explainAuto ? `GPU unavailable: ${why}` : '' };
  if (choice === 'auto' && gpu.software) {
    return { kind: 'cpu', note: `auto: the WebGPU device is a software fallback (e.g. SwiftShader), slower than the CPU worker; ${wording.override}` };
  }
  return { kind: 'gpu', note: '' };
}

/**
 * Slot `k` of the driver `to` goes on from `state` at `frame` (another driver's, of the same model): on the CPU with
 * its velocities; on the GPU, whose mirrors are read back as positions only, from those positions at rest.
 */
export function carryState(to: SimDriver, k: number, state: ClothState, frame: number): void {
  if (to instanceof SimClient) {
    to.setState(k, state, frame);
  } else if (to instanceof GpuSim) {
    const s = to.mirrors[k].sim.state;
    s.positions.set(state.positions);
    s.previousPositions.set(state.positions);
    s.velocities.fill(0);
    s.residuals.fill(0);
    s.previousResiduals.fill(0);
    to.upload(k, frame);
  }
}

/** whether mirror `from` can be carried into mirror `to` (the same particles, and finite) */
export function carriable(from: Mirror | undefined, to: Mirror | undefined): from is Mirror {
  return !!from && !!to && from.unstableAt < 0 && from.sim.model.particleCount === to.sim.model.particleCount;
}
