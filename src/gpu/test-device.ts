/**
 * The GPU device the Node tests run on: whatever adapter `createNodeDevice` finds (SwiftShader on the build
 * machines). No adapter: in CI (process.env.CI set) the test file fails with the reason; elsewhere its device tests
 * are skipped with the reason printed. A GPU test never passes without running.
 */
import type {} from 'webgpu';
import { createNodeDevice } from './node.js';

/** The device and adapter for `file`'s tests, or undefined (with a warning) where none is found outside CI. */
export async function testDevice(file: string): Promise<{ device: GPUDevice; adapter: string } | undefined> {
  try {
    return await createNodeDevice();
  } catch (e) {
    const reason = (e as Error).message;
    if (process.env.CI) throw new Error(`GPU tests need a WebGPU adapter in CI: ${reason}`);
    console.warn(`${file}: GPU tests skipped: ${reason}`);
    return undefined;
  }
}
