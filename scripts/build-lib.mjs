#!/usr/bin/env node
// Builds the npm package's library, CLI and types into dist/ (npm runs it as "prepare", before every `npm pack` and
// `npm publish`): the JavaScript without comments (the package ships no sources, so the comments would only weigh),
// the declaration files with every doc comment (what editors show), and no source maps in the package (package.json
// "files"). Stale outputs of removed sources are cleared first, so the package holds only what today's sources build.
// src/cli/package.test.ts builds into a scratch folder with `buildLib(folder)` and packs that.
import { spawnSync } from 'node:child_process';
import { rmSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

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
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) buildLib();
