/**
 * Whether a WebGPU adapter is a software fallback (SwiftShader, llvmpipe, lavapipe: the GPU drawn on the CPU), which
 * can draw and compute but runs the solver slower than the CPU worker: an 'auto' backend choice passes it by.
 */

/** What an adapter or a device says of itself (GPUAdapterInfo; older browsers put isFallbackAdapter on the adapter). */
export interface AdapterInfoLike {
  isFallbackAdapter?: boolean;
  vendor?: string;
  architecture?: string;
  description?: string;
}

/**
 * True for a software adapter: `isFallbackAdapter`, or a name that says so (Chromium has not always set the flag for
 * SwiftShader). `info`: the adapter's or the device's `info` / `adapterInfo`; `adapterFlag`: the adapter's own
 * isFallbackAdapter, where the browser still has it there.
 */
export function isSoftwareAdapter(info: AdapterInfoLike | undefined, adapterFlag?: boolean): boolean {
  if (info?.isFallbackAdapter ?? adapterFlag) return true;
  const text = `${info?.vendor ?? ''} ${info?.architecture ?? ''} ${info?.description ?? ''}`;
  return /swiftshader|llvmpipe|lavapipe/i.test(text);
}
