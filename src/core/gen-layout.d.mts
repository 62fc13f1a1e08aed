/** Types of gen-layout.mjs (plain JS so that it runs under Node 20 without a TypeScript loader). */
export declare const TS_FILE: string;
export declare const AS_FILE: string;
export declare const CONSTANTS: readonly (readonly [name: string, value: number, doc: string])[];
export declare const CONTROL: readonly (readonly [name: string, type: 'i32' | 'i64' | 'f64', count: number, doc: string, line?: boolean])[];
export declare function layoutControl(): { offsets: Record<string, number>; bytes: number };
export declare function generateLayoutModules(): { ts: string; as: string };
export declare function layoutFilesCurrent(): boolean;
export declare const PHASES: readonly (readonly [
  name: string, scope: 'frame-start' | 'substep' | 'frame-end', solvers: readonly string[], when: 'always' | 'wind' | 'grab',
  repeat: readonly string[], doc: string,
])[];
export declare const DESC: readonly (readonly [field: string, shift: number, bits: number, doc: string])[];
