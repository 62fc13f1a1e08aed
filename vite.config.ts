import { defineConfig } from 'vite';

// The browser app: index.html at the repository root, static build in dist/web (tsc writes dist/core, dist/cli).
export default defineConfig({
  root: '.',
  base: './',
  publicDir: 'public',
  build: {
    outDir: 'dist/web',
    emptyOutDir: true,
    target: 'es2022',
    chunkSizeWarningLimit: 1500,
  },
  worker: { format: 'es' },
  server: { open: false },
});
