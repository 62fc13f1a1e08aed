#!/usr/bin/env node
/**
 * Finds a Chromium/Chrome for the browser tests and prints its path. If none is found and we run as root on
 * Debian, installs Debian's chromium with apt-get; otherwise prints one line saying what to install and exits 1.
 * Importable too: findChromium() returns the path or null.
 */
import { execFileSync, execSync } from 'node:child_process';
import { accessSync, constants, existsSync, readFileSync } from 'node:fs';
import { delimiter, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const CANDIDATES = ['/usr/bin/chromium', '/usr/bin/chromium-browser', 'google-chrome', 'google-chrome-stable'];

function executable(p) {
  try { accessSync(p, constants.X_OK); return true; } catch { return false; }
}

function onPath(name) {
  for (const dir of (process.env.PATH ?? '').split(delimiter)) {
    if (dir && executable(join(dir, name))) return join(dir, name);
  }
  return null;
}

export function findChromium() {
  const env = process.env.CHROMIUM_PATH;
  if (env) return executable(env) ? env : null;
  for (const c of CANDIDATES) {
    const p = c.startsWith('/') ? (executable(c) ? c : null) : onPath(c);
    if (p) return p;
  }
  return null;
}

function isDebian() {
  try { return /^ID(_LIKE)?=.*debian/m.test(readFileSync('/etc/os-release', 'utf8')); } catch { return existsSync('/etc/debian_version'); }
}

function main() {
  if (process.env.CHROMIUM_PATH && !executable(process.env.CHROMIUM_PATH)) {
    console.error(`CHROMIUM_PATH=${process.env.CHROMIUM_PATH} is not an executable file: point it at chromium or chrome`);
    process.exit(1);
  }
  let path = findChromium();
  if (!path) {
    const root = typeof process.getuid === 'function' && process.getuid() === 0;
    if (root && isDebian()) {
      console.log('e2e: no Chromium found; installing Debian\'s chromium (apt-get install -y chromium)…');
      execSync('apt-get update && apt-get install -y chromium', { stdio: ['ignore', 'inherit', 'inherit'], env: { ...process.env, DEBIAN_FRONTEND: 'noninteractive' } });
      path = findChromium();
    }
    if (!path) {
      console.error('e2e: no Chromium or Chrome found: install one (Debian/Ubuntu: `sudo apt-get install chromium`) or set CHROMIUM_PATH to its executable');
      process.exit(1);
    }
  }
  let version = '';
  try { version = execFileSync(path, ['--version'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] }).trim(); } catch { /* wrapper noise */ }
  console.log(`e2e: using ${path}${version ? ` (${version})` : ''}`);
}

if (process.argv[1] && fileURLToPath(import.meta.url) === process.argv[1]) main();
