#!/usr/bin/env node
// Builds the npm package's library, CLI and types into dist/ (npm runs it as "prepare", before every `npm pack` and
// `npm publish`): the JavaScript without comments and compressed module by module by the oxc minifier that Vite
// uses (rolldown's `minifySync`: whitespace and dead code only, every name kept, so stack traces stay readable;
// the package ships no sources, so the comments would only weigh), the declaration files with every doc comment
// (what editors show), and no source maps in the package (package.json "files"). Stale outputs of removed sources
// are cleared first, so the package holds only what today's sources build.
// src/cli/package.test.ts builds into a scratch folder with `buildLib(folder)` and packs that.
import { spawnSync } from 'node:child_process';
import { readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { minifySync } from 'rolldown/utils';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const tsc = createRequire(import.meta.url).resolve('typescript/bin/tsc');

/** Builds the package's part of dist/ into `outDir` (default: the repository's dist/). */
export function buildLib(outDir = join(root, 'dist')) {
  for (const dir of ['core', 'cli', 'gpu', 'three']) rmSync(join(outDir, dir), { recursive: true, force: true });
  for (const flags of [['--removeComments', '--declaration', 'false'], ['--emitDeclarationOnly']]) {
    const args = [tsc, '-p', join(root, 'tsconfig.build.json'), '--outDir', outDir, ...flags];
    const run = spawnSync(process.execPath, args, { stdio: 'inherit' });
    if (run.status !== 0) throw new Error(`tsc ${flags.join(' ')} failed (exit ${run.status})`);
  }
  for (const dir of ['core', 'cli', 'gpu', 'three']) {
    for (const file of files(join(outDir, dir)).filter((f) => f.endsWith('.js'))) {
      const out = minifySync(file, readFileSync(file, 'utf8'), { compress: true, mangle: false, module: true });
      if (out.errors.length) throw new Error(`minify ${file}: ${out.errors[0].message}`);
      writeFileSync(file, out.code);
    }
  }
}

/** Every file under `dir` (none when it does not exist). */
function files(dir) {
  let names;
  try { names = readdirSync(dir); } catch { return []; }
  return names.flatMap((f) => { const p = join(dir, f); return statSync(p).isDirectory() ? files(p) : [p]; });
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) buildLib();
