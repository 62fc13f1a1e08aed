/**
 * Helper threads for the WebAssembly kernel in a browser: a Web Worker per helper (kernel-helper.worker.ts), started
 * by the simulation worker when the page is cross-origin isolated (SharedArrayBuffer, and so a shared kernel memory,
 * exist only then). Elsewhere there is no spawner, and the kernel runs on the simulation worker's one thread.
 */
import type { HelperSpawner, KernelHelperInit } from '../../core/index.js';

/** Most threads a kernel gets in a browser (the core's own cap is 8). */
const MAX_BROWSER_THREADS = 8;

/** The spawner of kernel helpers for this context, or undefined when it is not cross-origin isolated. */
export function browserHelpers(): HelperSpawner | undefined {
  if (!(globalThis as { crossOriginIsolated?: boolean }).crossOriginIsolated || typeof SharedArrayBuffer === 'undefined') return undefined;
  const spawn = (init: KernelHelperInit, onError: (error: Error) => void) => {
    const worker = new Worker(new URL('./kernel-helper.worker.js', import.meta.url), { type: 'module', name: 'drape-kernel-helper' });
    worker.onerror = (e) => onError(new Error(`kernel helper thread: ${e.message || 'failed to start'}`));
    worker.postMessage(init);
    return { terminate: () => worker.terminate() };
  };
  return Object.assign(spawn, { cores: Math.max(1, Math.min(MAX_BROWSER_THREADS, navigator.hardwareConcurrency || 1)) });
}
