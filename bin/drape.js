#!/usr/bin/env node
// The CLI entry: the TypeScript sources are compiled to dist/ by `npm install` (prepare) or `npm run build`.
import { existsSync } from 'node:fs';

const entry = new URL('../dist/cli/main.js', import.meta.url);
if (!existsSync(entry)) {
  console.error('drape: not built yet; run `npm run build` in the package directory');
  process.exit(2);
}
// a reader that stops early (`drape run … | head`) closes the pipe: stop quietly, as other command-line tools do
// (with the exit code the run has set by then: an export that failed still says so)
process.stdout.on('error', (e) => {
  if (e.code !== 'EPIPE') throw e;
  process.exit(process.exitCode ?? 0);
});
const { main } = await import(entry.href);
process.exitCode = await main(process.argv.slice(2));
