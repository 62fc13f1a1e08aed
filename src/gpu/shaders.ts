/**
 * WGSL source of each kernel: the shared declarations generated from layout.ts, the kernel's storage bindings,
 * its libraries, then the kernel file itself. The .wgsl files under src/gpu/shaders are the source; they reach
 * this module through shaders.generated.ts (string constants, written by gen-shaders.mjs), which Node, Vitest
 * and Vite all load as ordinary TypeScript.
 */
import { KERNELS, wgslBindings, wgslPreamble, type KernelName, type KernelSpec } from './layout.js';
import { WGSL_SOURCES } from './shaders.generated.js';

function source(file: string): string {
  const text = WGSL_SOURCES[file];
  if (text === undefined) throw new Error(`GPU solver: shader ${file}.wgsl missing from shaders.generated.ts (run node src/gpu/gen-shaders.mjs)`);
  return text;
}

/** Complete WGSL module of one kernel (entry point `main`). */
export function kernelSource(kernel: KernelName): string {
  const spec: KernelSpec = KERNELS[kernel];
  const parts = [wgslPreamble(), `// ---- bindings of ${kernel} ----`, wgslBindings(kernel), ''];
  for (const lib of spec.libs ?? []) parts.push(`// ---- ${lib}.wgsl ----`, source(lib));
  const file = spec.file ?? kernel;
  parts.push(`// ---- ${file}.wgsl ----`, source(file));
  return parts.join('\n');
}
