/** Types of build-lib.mjs (plain JS so that npm's "prepare" runs it under Node 20 without a TypeScript loader). */
export declare function buildLib(outDir?: string): void;
