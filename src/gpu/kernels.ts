/**
 * The WebGPU solver's kernels compiled for a device: one pipeline per kernel of layout.ts, and the bind group
 * layouts they share. They depend on no model, so every solver on a device shares them (compiled once, on first use).
 */
import type {} from 'webgpu';
import { KERNELS, PASS, SUBSTEP, type KernelName, type KernelSpec } from './layout.js';
import { kernelSource } from './shaders.js';

const KERNEL_NAMES = Object.keys(KERNELS) as KernelName[];

/** A device's compiled kernels: every solver on the device shares them. */
export interface Kernels {
  /** group 0: the uniform tables every kernel reads */
  uniformLayout: GPUBindGroupLayout;
  /** each kernel's pipeline */
  pipelines: Record<KernelName, GPUComputePipeline>;
  /** group 1 of each kernel: its storage buffers */
  storageLayouts: Record<KernelName, GPUBindGroupLayout>;
}
const compiled = new WeakMap<GPUDevice, Promise<Kernels>>();

/** The kernels of `device`, compiled on first use (a failed compile is not kept: the next call tries again). */
export function kernelsFor(device: GPUDevice): Promise<Kernels> {
  let kernels = compiled.get(device);
  if (!kernels) {
    kernels = compileKernels(device);
    compiled.set(device, kernels);
    kernels.catch(() => compiled.delete(device));
  }
  return kernels;
}

/** Compiles every kernel of layout.ts for `device`, naming the kernel and line of any compile error. */
async function compileKernels(device: GPUDevice): Promise<Kernels> {
  const uniformLayout = device.createBindGroupLayout({
    label: 'drape uniforms',
    entries: [
      { binding: 0, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } },
      { binding: 1, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform', hasDynamicOffset: true, minBindingSize: SUBSTEP.size } },
      { binding: 2, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform', hasDynamicOffset: true, minBindingSize: PASS.size } },
    ],
  });
  const pipelines = {} as Record<KernelName, GPUComputePipeline>;
  const storageLayouts = {} as Record<KernelName, GPUBindGroupLayout>;
  await Promise.all(KERNEL_NAMES.map(async (kernel) => {
    const spec: KernelSpec = KERNELS[kernel];
    const layout = device.createBindGroupLayout({
      label: `drape ${kernel} storage`,
      entries: spec.bindings.map(([, access], i) => ({
        binding: i,
        visibility: GPUShaderStage.COMPUTE,
        buffer: { type: access === 'read' ? 'read-only-storage' as const : 'storage' as const },
      })),
    });
    storageLayouts[kernel] = layout;
    const code = kernelSource(kernel);
    const module = device.createShaderModule({ label: `drape ${kernel}.wgsl`, code });
    const info = await module.getCompilationInfo();
    const errors = info.messages.filter((m) => m.type === 'error');
    if (errors.length) {
      const lines = code.split('\n');
      const where = (m: GPUCompilationMessage) => `'${(lines[m.lineNum - 1] ?? '').trim()}': ${m.message}`;
      throw new Error(`GPU solver: ${kernel} kernel does not compile: ${errors.map(where).join('; ')}`);
    }
    pipelines[kernel] = await device.createComputePipelineAsync({
      label: `drape ${kernel}`,
      layout: device.createPipelineLayout({ bindGroupLayouts: [uniformLayout, layout] }),
      compute: { module, entryPoint: 'main' },
    });
  }));
  return { uniformLayout, pipelines, storageLayouts };
}
