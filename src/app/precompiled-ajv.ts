/**
 * Build-time (Node) helper of vite.config.ts: the site's Content-Security-Policy has no 'unsafe-eval', and Ajv
 * compiles a schema into a validator with `new Function` — which that policy forbids. So the site build never
 * ships Ajv's compiler: `ajv` is resolved to the module made here, Ajv's own standalone code of the scene validator,
 * compiled once at build time with exactly the options the core uses, wrapped in a tiny `Ajv` class whose
 * `compile` hands it out. The core's `new Ajv(options).compile(sceneSchema)` then gets the same validator (the same
 * code Ajv would have generated at run time), with no code generated in the page or the worker.
 *
 * The wrapper checks that it is asked for what it was built for (same options, same schema) and throws a clear
 * error otherwise, so a core change that the build does not know about fails loudly, never silently.
 * `precompiled-ajv.test.ts` checks it validates exactly like the core's run-time validator.
 */
import { Ajv, type Options } from 'ajv';
import standaloneCodeModule from 'ajv/dist/standalone/index.js';
import { SCENE_VALIDATOR_OPTIONS } from '../core/scene.js';

/** the options the core creates its Ajv with (the wrapper refuses any other) */
export const CORE_AJV_OPTIONS: Options = SCENE_VALIDATOR_OPTIONS;

type StandaloneCode = (ajv: Ajv, validate: unknown) => string;
const standaloneCode: StandaloneCode =
  (standaloneCodeModule as unknown as { default?: StandaloneCode }).default ?? (standaloneCodeModule as unknown as StandaloneCode);

/**
 * ES module source exporting `Ajv` (a stand-in for ajv's class that only knows `schema`) and `validate`.
 * Ajv's standalone output `require`s its small run-time helpers (string length, deep equality): they become imports.
 */
export function precompiledAjvModule(schema: object, options: Options = CORE_AJV_OPTIONS): string {
  const ajv = new Ajv({ ...options, code: { source: true, esm: true } });
  const validate = ajv.compile(schema);
  let code = standaloneCode(ajv, validate);
  const imports: string[] = [];
  code = code.replace(/const (\w+) = require\(("[^"]+")\)(\.default)?;/g, (_m, name: string, from: string, dflt?: string) => {
    const ns = `__ajvRuntime${imports.length}`;
    // Node's ES modules want the file's extension
    imports.push(`import * as ${ns} from ${/\.js"$/.test(from) ? from : from.replace(/"$/, '.js"')};`);
    // a CommonJS module seen from ESM: its exports object may sit on `default` (Node) or be spread (bundlers)
    const mod = `(${ns}.default && typeof ${ns}.default === 'object' ? ${ns}.default : ${ns})`;
    return dflt ? `const ${name} = typeof ${ns}.default === 'function' ? ${ns}.default : ${mod}.default;` : `const ${name} = ${mod};`;
  });
  if (/\brequire\(/.test(code)) throw new Error('precompiled Ajv: the standalone code still requires a module');
  code = code.replace(/^"use strict";/, '');
  const head = /export const validate = (\w+);export default \1;/.exec(code);
  if (!head) throw new Error('precompiled Ajv: unexpected standalone code');
  const fn = head[1];
  return [
    '// generated at build time by src/app/precompiled-ajv.ts: Ajv\'s standalone validator of the scene schema',
    ...imports,
    code.replace(head[0], ''),
    `const OPTIONS = ${JSON.stringify(JSON.stringify(options))};`,
    `const SCHEMA = ${JSON.stringify(JSON.stringify(schema))};`,
    `export { ${fn} as validate };`,
    'export class Ajv {',
    '  constructor(options) {',
    '    if (JSON.stringify(options ?? {}) !== OPTIONS) throw new Error(`precompiled Ajv: built for the options ${OPTIONS}, asked for ${JSON.stringify(options)} (update src/app/precompiled-ajv.ts)`);',
    '  }',
    '  compile(schema) {',
    '    if (JSON.stringify(schema) !== SCHEMA) throw new Error("precompiled Ajv: asked for a schema it was not built for (rebuild the site)");',
    `    return ${fn};`,
    '  }',
    '}',
    '',
  ].join('\n');
}
