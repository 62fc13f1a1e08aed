/**
 * A WebGPU device in Node through the `webgpu` package (Dawn). Finds a real GPU when the system's Vulkan loader
 * and driver offer one; otherwise falls back to SwiftShader from Debian's `chromium` package (a CPU Vulkan driver:
 * correct, slow) by pointing the Vulkan loader at it — no environment needed beforehand, so plain `npx vitest run`
 * works. See /work/shared/testing.md and docs/gpu.md.
 */
import type {} from 'webgpu';
import { existsSync } from 'node:fs';
import { constants } from 'node:os';
import { delimiter, join } from 'node:path';

/** Objects Dawn must keep alive: if V8 collects the `create()` result, Dawn crashes at random. */
const keepAlive: unknown[] = [];

/** Where Debian's chromium puts SwiftShader and its own Vulkan loader (override: DRAPE_SWIFTSHADER_DIR). */
function swiftShaderDir(): string | undefined {
  const dir = process.env.DRAPE_SWIFTSHADER_DIR ?? '/usr/lib/chromium';
  return existsSync(join(dir, 'vk_swiftshader_icd.json')) && existsSync(join(dir, 'libvulkan.so.1')) ? dir : undefined;
}

/** Whether the dynamic linker can find a Vulkan loader by itself (LD_LIBRARY_PATH or the usual system places). */
function systemVulkan(): boolean {
  if (process.platform !== 'linux') return true;
  const dirs = [
    ...(process.env.LD_LIBRARY_PATH ?? '').split(delimiter).filter(Boolean),
    '/usr/lib/x86_64-linux-gnu', '/lib/x86_64-linux-gnu', '/usr/lib64', '/lib64', '/usr/lib', '/lib', '/usr/local/lib',
    '/usr/lib/aarch64-linux-gnu',
  ];
  return dirs.some((d) => existsSync(join(d, 'libvulkan.so.1')));
}

/**
 * Loads SwiftShader's Vulkan loader into the process under its soname, so that Dawn's later
 * dlopen("libvulkan.so.1") finds it without LD_LIBRARY_PATH (which the dynamic linker reads only at start-up).
 * process.dlopen throws "did not self-register" for a non-Node library; RTLD_NODELETE keeps it loaded anyway.
 */
function preloadVulkan(dir: string): void {
  const RTLD_NODELETE = 0x1000; // glibc
  const flags = constants.dlopen.RTLD_NOW | constants.dlopen.RTLD_GLOBAL | RTLD_NODELETE;
  try {
    process.dlopen({ exports: {} }, join(dir, 'libvulkan.so.1'), flags);
  } catch {
    // expected: not a Node addon; the library stays loaded (RTLD_NODELETE)
  }
}

type WebGpuModule = { create(options: string[]): GPU; globals: object };

async function loadWebGpu(): Promise<WebGpuModule> {
  try {
    return (await import('webgpu')) as WebGpuModule;
  } catch (e) {
    const err = e as NodeJS.ErrnoException;
    if (err.code === 'ERR_MODULE_NOT_FOUND' && /'webgpu'/.test(err.message)) {
      // an optional peer dependency: `npm install drape` leaves it out (Dawn is ~130 MB)
      throw new Error("no WebGPU in Node: the GPU backend needs the 'webgpu' package (Dawn); install it beside drape: npm install webgpu");
    }
    throw new Error(`no WebGPU in Node: the 'webgpu' package does not load (${err.message.split('\n')[0]})`);
  }
}

async function tryAdapter(mod: WebGpuModule): Promise<GPUAdapter | null> {
  const gpu = mod.create([]);
  keepAlive.push(gpu);
  (globalThis as Record<string, unknown>).__drapeGpu = keepAlive;
  return gpu.requestAdapter({ powerPreference: 'high-performance' });
}

/**
 * Dawn's Node binding waits for the GPU (a buffer's mapAsync, the queue's onSubmittedWorkDone) by polling its
 * instance from a setImmediate callback that queues itself again: a busy loop on the JavaScript thread for as long
 * as the GPU works. On a software adapter (SwiftShader) that work runs on the same CPU cores, which the loop then
 * competes for: a 2-core machine ran 40 frames of two 10² sheets with self-contact in 9.2 s so, and in 6.5 s with
 * the polls a timer apart (`src/gpu/self-contact.test.ts`'s scene, 2026-12-06). So on such an adapter Dawn's polls
 * (its own native callbacks, the only ones a script cannot write) are queued with setTimeout(0), about a
 * millisecond apart; every other setImmediate is left as it was. Not on a real GPU, whose waits are short and whose
 * frame times the benchmark reads.
 */
function pollGently(): void {
  const key = Symbol.for('drape.gentleDawnPolling');
  const g = globalThis as unknown as Record<symbol, boolean> & { setImmediate: (...a: unknown[]) => unknown };
  if (g[key]) return;
  g[key] = true;
  const immediate = g.setImmediate;
  const source = Function.prototype.toString;
  const replaced = (fn: unknown, ...args: unknown[]) =>
    typeof fn === 'function' && source.call(fn).endsWith('{ [native code] }')
      ? setTimeout(fn as () => void, 0, ...args)
      : immediate(fn, ...args);
  g.setImmediate = Object.assign(replaced, immediate);
}

function describeAdapter(a: GPUAdapter): string {
  const i = a.info;
  return [i.vendor, i.architecture, i.device, i.description].filter(Boolean).join(' / ') || 'unknown adapter';
}

/**
 * A GPUDevice from the `webgpu` package, with the adapter's storage-buffer and buffer-size limits (large cloths
 * need more than the 128 MiB default binding). Throws an Error with a one-line message when there is no adapter.
 * `adapter` names it, e.g. "google / swiftshader / … / SwiftShader driver 5.0.0" or "nvidia / …".
 */
export async function createNodeDevice(): Promise<{ device: GPUDevice; adapter: string }> {
  const mod = await loadWebGpu();
  Object.assign(globalThis, mod.globals); // GPUBufferUsage, GPUMapMode, GPUShaderStage, ...
  const swift = swiftShaderDir();
  const userDriver = process.env.VK_ICD_FILENAMES !== undefined || process.env.VK_DRIVER_FILES !== undefined;
  let adapter: GPUAdapter | null = null;
  // 1. whatever the system offers (a real GPU, or the driver the user named)
  if (systemVulkan() || !swift) adapter = await tryAdapter(mod);
  // 2. SwiftShader from Debian's chromium
  if (!adapter && swift) {
    if (!userDriver) process.env.VK_ICD_FILENAMES = join(swift, 'vk_swiftshader_icd.json');
    preloadVulkan(swift);
    adapter = await tryAdapter(mod);
  }
  if (!adapter) {
    throw new Error(
      'no WebGPU adapter: Dawn found no Vulkan device (install a GPU driver, or Debian\'s chromium for SwiftShader: apt-get install -y chromium)',
    );
  }
  const want = (name: 'maxStorageBufferBindingSize' | 'maxBufferSize') => adapter.limits[name];
  const device = await adapter.requestDevice({
    label: 'drape',
    requiredFeatures: adapter.features.has('timestamp-query') ? ['timestamp-query'] : [],
    requiredLimits: {
      maxStorageBufferBindingSize: want('maxStorageBufferBindingSize'),
      maxBufferSize: want('maxBufferSize'),
    },
  });
  keepAlive.push(adapter, device);
  if (adapter.info.isFallbackAdapter) pollGently();
  device.lost.then((info) => {
    if (info.reason !== 'destroyed') console.error(`drape: GPU device lost: ${info.message}`);
  }, () => undefined);
  return { device, adapter: describeAdapter(adapter) };
}
