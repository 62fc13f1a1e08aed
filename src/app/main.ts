/**
 * Entry point of the page (index.html). Query options: `?webgl` forces the WebGL2 backend; `?lite` renders more
 * cheaply (no MSAA, pixel ratio 1, smaller shadow map) for software rasterisers; `?backend=auto|gpu|cpu` picks the
 * simulation backend when the link's hash does not; `?testhook` installs the test hook `window.drape` in a
 * production build (the dev server always has it).
 */
/// <reference types="vite/client" />
import '../ui/style.css';
import { App } from './app.js';
import { installHook } from './hook.js';
import { installTrustedTypesPolicy, wantsTestHook } from './security.js';

installTrustedTypesPolicy();
performance.mark('drape:start');
const viewport = document.getElementById('viewport');
if (!viewport) throw new Error('index.html: #viewport missing');

const params = new URLSearchParams(location.search);
App.create(document.body, viewport, { forceWebGL: params.has('webgl'), lite: params.has('lite'), backend: params.get('backend') }).then(
  (app) => { if (wantsTestHook(location.search, import.meta.env.DEV)) installHook(app); },
  (e: unknown) => {
    const box = document.createElement('div');
    box.className = 'drape-fatal';
    box.setAttribute('role', 'alert');
    box.textContent = `Drape could not start: ${e instanceof Error ? e.message : String(e)}. ` +
      'It needs a browser with WebGPU or WebGL2.';
    document.body.append(box);
    console.error(e);
  },
);
