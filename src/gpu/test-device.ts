/**
 * The GPU device the Node tests run on: whatever adapter `createNodeDevice` finds (SwiftShader on the build
 * machines). No adapter: in CI (process.env.CI set) the test file fails with the reason; elsewhere its device tests
 * are skipped with the reason printed. A GPU test never passes without running.
 */
import type {} from 'webgpu';
import { centroid } from '../core/metrics.js';
import type { ClothState } from '../core/state.js';
import { createNodeDevice } from './node.js';

/** the device every GPU test file of this process shares (vitest.config.ts runs them in one, not isolated) */
let shared: Promise<{ device: GPUDevice; adapter: string }> | null = null;

/**
 * The device and adapter for `file`'s tests, or undefined (with a warning) where none is found outside CI. The files
 * share one device, so its kernels are compiled once for all of them (2.6 s on SwiftShader here): a file destroys
 * its solvers, never the device.
 */
export async function testDevice(file: string): Promise<{ device: GPUDevice; adapter: string } | undefined> {
  try {
    if (!shared) {
      const made = createNodeDevice();
      shared = made;
      // a lost device is not handed on: the next file makes its own
      void made.then(({ device }) => device.lost.then(() => { if (shared === made) shared = null; }), () => undefined);
    }
    return await shared;
  } catch (e) {
    shared = null;
    const reason = (e as Error).message;
    if (process.env.CI) throw new Error(`GPU tests need a WebGPU adapter in CI: ${reason}`);
    console.warn(`${file}: GPU tests skipped: ${reason}`);
    return undefined;
  }
}

/** Largest distance between corresponding particles of two position arrays (stride 3) [m]. */
export function maxDistance(a: Float32Array, b: Float32Array): number {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) worst = Math.max(worst, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  return worst;
}

/** Distance between the centroids of two cloth states [m]. */
export function centroidDistance(a: ClothState, b: ClothState): number {
  const p = centroid(a), q = centroid(b);
  return Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}
