/** Types of gen-shaders.mjs (plain JS so that it runs under Node 20 without a TypeScript loader). */
export declare const SHADER_DIR: string;
export declare const GENERATED_FILE: string;
export declare function generateShaderModule(dir?: string): string;
