/**
 * Helper threads for the WebAssembly XPBD kernel in Node: one worker thread per helper, each instantiating the
 * kernel module over the shared memory and serving substeps (core/wasm/xpbd-wasm.ts) until the kernel stops it.
 */
import { availableParallelism } from 'node:os';
import { Worker } from 'node:worker_threads';
import type { HelperSpawner, KernelHelperInit } from '../core/wasm/xpbd-wasm.js';

// The worker's whole program (CommonJS, evaluated): instantiate the kernel with the imports of core/wasm
// kernelImports() (a worker thread may block, so wait always sleeps) and enter its helper loop.
const HELPER_SOURCE = `
const { workerData } = require('node:worker_threads');
const { module, memory, layout, thread } = workerData;
const words = new Int32Array(memory.buffer);
const instance = new WebAssembly.Instance(module, { env: {
  memory,
  abort() { throw new Error('xpbd kernel abort'); },
  wait(address, expected, timeoutMs) { Atomics.wait(words, address >>> 2, expected, timeoutMs); },
  notify(address) { Atomics.notify(words, address >>> 2); },
} });
instance.exports.configure(...layout);
instance.exports.helperLoop(thread);
`;

/** Most threads the CLI gives the kernel: the cores Node may use (more would only take turns), at most 8. */
export function maxThreads(): number {
  return Math.min(8, Math.max(1, availableParallelism()));
}

/** Starts a kernel helper on a Node worker thread that does not keep the process alive. */
export const spawnNodeHelper: HelperSpawner = Object.assign((init: KernelHelperInit, onError: (error: Error) => void) => {
  const worker = new Worker(HELPER_SOURCE, { eval: true, workerData: init });
  worker.on('error', onError);
  worker.unref();
  return { terminate: () => void worker.terminate() };
}, { cores: maxThreads() });
