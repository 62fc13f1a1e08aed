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
// Any other failure to write it (a full disk: ENOSPC) loses the output: one line says so, exit code 4 (README)
process.stdout.on('error', (e) => {
  if (e.code === 'EPIPE') process.exit(process.exitCode ?? 0);
  process.stderr.write(`drape: could not write the output to standard output (${String(e.code ?? e.message).replace(/[^\w .,:-]/g, '?')})\n`);
  process.exit(4);
});
const { main } = await import(entry.href);
process.exitCode = await main(process.argv.slice(2));
