/** Types of gen-wasm.mjs (plain JS so that it runs under Node 20 without a TypeScript loader). */
export declare const KERNEL_SOURCE: string;
export declare const GENERATED_FILE: string;
export declare function generateKernelModule(source?: string): Promise<string>;
