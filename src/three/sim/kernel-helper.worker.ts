/**
 * One helper thread of the WebAssembly kernel in a browser (helpers.ts starts it): instantiates the kernel module
 * over the shared memory it is sent, with the kernel's imports (those of core/wasm/xpbd-wasm.ts kernelImports: a
 * worker may block, so `wait` sleeps), and serves substeps until the kernel stops it. Written out rather than
 * imported, so that the helper does not carry the kernel's bytes (the Node twin is cli/threads.ts).
 */
import type { KernelHelperInit } from '../../core/index.js';

interface HelperExports {
  configure(...layout: number[]): void;
  helperLoop(thread: number): void;
}

self.onmessage = (e: MessageEvent<KernelHelperInit>) => {
  const { module, memory, layout, thread } = e.data;
  const words = new Int32Array(memory.buffer);
  const kernel = new WebAssembly.Instance(module, {
    env: {
      memory,
      abort() { throw new Error('xpbd kernel abort'); },
      wait(address: number, expected: number, timeoutMs: number) { Atomics.wait(words, address >>> 2, expected, timeoutMs); },
      notify(address: number) { Atomics.notify(words, address >>> 2); },
    },
  }).exports as unknown as HelperExports;
  kernel.configure(...layout);
  kernel.helperLoop(thread);
};
