/**
 * Procedural textures, drawn on canvases at start-up (no downloads): one look per fabric, the floor and the
 * studio backdrop.
 */
import { CanvasTexture, RepeatWrapping, SRGBColorSpace, type Texture } from 'three/webgpu';
import { LOOKS, mulberry32, type FabricKind } from '../core/index.js';

export interface FabricLook {
  kind: FabricKind;
  /** colour texture */
  map: Texture;
  roughness: number;
  /** fabric sheen (MeshPhysicalMaterial.sheen) */
  sheen: number;
  sheenColor: string;
  clearcoat: number;
}

/** Every procedural canvas with the code that paints it, so all can be repainted (see repaintTextures). */
const painted: { canvas: HTMLCanvasElement; paint: (g: CanvasRenderingContext2D, size: number) => void; size: number; textures: Texture[] }[] = [];

/** the fabrics' textures are painted at this many pixels a side, whatever size their painter draws in: sharp up close */
const FABRIC_PIXELS = 1024;

/**
 * A canvas painted by `paint` in a square of `size` units; its pixels are `detail` times as many a side (the
 * painter draws in its own units, scaled: its lines and edges stay sharp at any detail).
 */
function canvas(size: number, paint: (g: CanvasRenderingContext2D, size: number) => void, detail = 1): HTMLCanvasElement {
  const c = document.createElement('canvas');
  c.width = c.height = Math.round(size * detail);
  const g = c.getContext('2d', { willReadFrequently: true });
  if (!g) throw new Error('2D canvas unavailable');
  g.setTransform(detail, 0, 0, detail, 0, 0);
  paint(g, size);
  const entry = { canvas: c, paint, size, textures: [] as Texture[] };
  painted.push(entry);
  // a 2D canvas that lost its backing store (GPU process restart) comes back blank
  c.addEventListener('contextrestored', () => repaint(entry));
  return c;
}

/**
 * Paints every procedural texture again and re-uploads it. Needed after a WebGPU device loss: the GPU process
 * restarts and 2D canvases lose their pixels.
 */
export function repaintTextures(): void {
  for (const p of painted) repaint(p);
}

function repaint(p: (typeof painted)[number]): void {
  const g = p.canvas.getContext('2d', { willReadFrequently: true });
  if (!g) return;
  g.reset?.();
  const detail = p.canvas.width / p.size;
  g.setTransform(detail, 0, 0, detail, 0, 0);
  p.paint(g, p.size);
  for (const t of p.textures) t.needsUpdate = true;
}

function track(t: Texture, c: HTMLCanvasElement): Texture {
  painted.find((p) => p.canvas === c)?.textures.push(t);
  return t;
}

function noise(g: CanvasRenderingContext2D, size: number, alpha: number, seed: number, cell = 1): void {
  const r = mulberry32(seed);
  for (let y = 0; y < size; y += cell) {
    for (let x = 0; x < size; x += cell) {
      const v = r();
      g.fillStyle = v > 0.5 ? `rgba(255,255,255,${(v - 0.5) * alpha})` : `rgba(0,0,0,${(0.5 - v) * alpha})`;
      g.fillRect(x, y, cell, cell);
    }
  }
}

/** Fine woven texture: alternating over/under threads. */
function weave(g: CanvasRenderingContext2D, size: number, pitch: number, alpha: number): void {
  for (let y = 0; y < size; y += pitch) {
    for (let x = 0; x < size; x += pitch) {
      const over = ((x + y) / pitch) % 2 === 0;
      g.fillStyle = over ? `rgba(255,255,255,${alpha})` : `rgba(0,0,0,${alpha})`;
      g.fillRect(x, y, pitch, pitch / 2);
      g.fillStyle = over ? `rgba(0,0,0,${alpha})` : `rgba(255,255,255,${alpha})`;
      g.fillRect(x, y + pitch / 2, pitch, pitch / 2);
    }
  }
}

function finish(c: HTMLCanvasElement, repeat: number): Texture {
  const t = track(new CanvasTexture(c), c);
  t.colorSpace = SRGBColorSpace;
  t.wrapS = t.wrapT = RepeatWrapping;
  t.repeat.set(repeat, repeat);
  t.anisotropy = 8;
  return t;
}

function cotton(): FabricLook {
  const c = canvas(256, (g, size) => {
    g.fillStyle = '#f4efe6';
    g.fillRect(0, 0, size, size);
    // gingham: translucent bands both ways make the darker crossings
    g.fillStyle = 'rgba(46, 92, 160, 0.55)';
    for (let k = 0; k < 4; k++) {
      g.fillRect(k * 64, 0, 32, size);
      g.fillRect(0, k * 64, size, 32);
    }
    weave(g, size, 4, 0.05);
    noise(g, size, 0.08, 3, 2);
  }, FABRIC_PIXELS / 256);
  return { kind: 'cotton', map: finish(c, 4), roughness: LOOKS.cotton.roughness, sheen: 0.6, sheenColor: '#c9d8f0', clearcoat: 0 };
}

function silk(): FabricLook {
  const c = canvas(256, (g, size) => {
    const grad = g.createLinearGradient(0, 0, size, size);
    grad.addColorStop(0, '#8e1330');
    grad.addColorStop(0.5, '#a8203f');
    grad.addColorStop(1, '#8e1330');
    g.fillStyle = grad;
    g.fillRect(0, 0, size, size);
    // thin golden lattice with small diamonds at the crossings
    g.strokeStyle = 'rgba(232, 190, 110, 0.55)';
    g.lineWidth = 2;
    for (let k = -size; k <= 2 * size; k += 64) {
      g.beginPath(); g.moveTo(k, 0); g.lineTo(k + size, size); g.stroke();
      g.beginPath(); g.moveTo(k, size); g.lineTo(k + size, 0); g.stroke();
    }
    g.fillStyle = 'rgba(240, 205, 130, 0.8)';
    for (let y = 0; y <= size; y += 64) {
      for (let x = 32; x <= size + 32; x += 64) {
        g.beginPath();
        g.moveTo(x % size, y - 6); g.lineTo((x % size) + 6, y); g.lineTo(x % size, y + 6); g.lineTo((x % size) - 6, y);
        g.fill();
      }
    }
    noise(g, size, 0.03, 5, 1);
  }, FABRIC_PIXELS / 256);
  return { kind: 'silk', map: finish(c, 3), roughness: LOOKS.silk.roughness, sheen: 1, sheenColor: '#ffb3c4', clearcoat: 0 };
}

function leather(): FabricLook {
  const c = canvas(512, (g, size) => {
    g.fillStyle = '#6b3f22';
    g.fillRect(0, 0, size, size);
    // grain: many soft blotches
    const r = mulberry32(11);
    for (let k = 0; k < 2600; k++) {
      const x = r() * size, y = r() * size, rad = 2 + r() * 7;
      g.fillStyle = r() > 0.5 ? `rgba(40, 20, 8, ${0.08 + r() * 0.12})` : `rgba(150, 95, 55, ${0.06 + r() * 0.1})`;
      g.beginPath(); g.arc(x, y, rad, 0, Math.PI * 2); g.fill();
    }
    noise(g, size, 0.12, 12, 2);
    // stitched border (the map spans the whole cloth: repeat 1)
    g.strokeStyle = 'rgba(232, 210, 170, 0.9)';
    g.lineWidth = 3;
    g.setLineDash([10, 8]);
    g.strokeRect(18, 18, size - 36, size - 36);
  }, FABRIC_PIXELS / 512);
  // garment leather is satin, not lacquered: a faint, rough clearcoat (a strong one drew a whitish smear)
  return { kind: 'leather', map: finish(c, 1), roughness: LOOKS.leather.roughness, sheen: 0.2, sheenColor: '#d8a27a', clearcoat: 0.06 };
}

function rubber(): FabricLook {
  const c = canvas(256, (g, size) => {
    g.fillStyle = '#f2b705';
    g.fillRect(0, 0, size, size);
    const r = mulberry32(21);
    for (let k = 0; k < 500; k++) {
      g.fillStyle = `rgba(120, 70, 0, ${0.05 + r() * 0.1})`;
      g.fillRect(r() * size, r() * size, 1 + r() * 2, 1 + r() * 2);
    }
    // dotted pattern, like a printed latex sheet
    g.fillStyle = 'rgba(214, 72, 36, 0.85)';
    for (let y = 16; y < size; y += 32) for (let x = (y / 32) % 2 ? 32 : 16; x < size; x += 32) {
      g.beginPath(); g.arc(x, y, 6, 0, Math.PI * 2); g.fill();
    }
  }, FABRIC_PIXELS / 256);
  return { kind: 'rubber', map: finish(c, 3), roughness: LOOKS.rubber.roughness, sheen: 0, sheenColor: '#ffffff', clearcoat: 0.6 };
}

function flag(): FabricLook {
  const c = canvas(512, (g, size) => {
    const bands = ['#1d3f8f', '#f3efe4', '#c8322f'];
    bands.forEach((col, k) => { g.fillStyle = col; g.fillRect(0, (k * size) / 3, size, size / 3 + 1); });
    g.fillStyle = '#e7b931';
    g.beginPath();
    for (let k = 0; k < 10; k++) {
      const a = -Math.PI / 2 + (k * Math.PI) / 5, rad = k % 2 ? 28 : 70;
      g.lineTo(size / 2 + rad * Math.cos(a), size / 2 + rad * Math.sin(a));
    }
    g.fill();
    weave(g, size, 4, 0.04);
  }, FABRIC_PIXELS / 512);
  return { kind: 'flag', map: finish(c, 1), roughness: LOOKS.flag.roughness, sheen: 0.5, sheenColor: '#ffffff', clearcoat: 0 };
}

function hammock(): FabricLook {
  const c = canvas(256, (g, size) => {
    const cols = ['#e8dcc2', '#c0392b', '#e8dcc2', '#2c4a7a', '#e8dcc2', '#e6a23c'];
    const w = size / cols.length;
    cols.forEach((col, k) => { g.fillStyle = col; g.fillRect(k * w, 0, w + 1, size); });
    weave(g, size, 4, 0.07);
    noise(g, size, 0.06, 31, 2);
  }, FABRIC_PIXELS / 256);
  return { kind: 'hammock', map: finish(c, 2), roughness: LOOKS.hammock.roughness, sheen: 0.5, sheenColor: '#fff4dd', clearcoat: 0 };
}

function checker(): FabricLook {
  const c = canvas(256, (g, size) => {
    for (let y = 0; y < 8; y++) for (let x = 0; x < 8; x++) {
      g.fillStyle = (x + y) % 2 ? '#f1ede4' : '#e0703a';
      g.fillRect(x * 32, y * 32, 32, 32);
    }
    weave(g, size, 4, 0.04);
  }, FABRIC_PIXELS / 256);
  return { kind: 'checker', map: finish(c, 1), roughness: LOOKS.checker.roughness, sheen: 0.4, sheenColor: '#ffe2cc', clearcoat: 0 };
}

const makers: Record<FabricKind, () => FabricLook> = { cotton, silk, leather, rubber, flag, hammock, checker };
const cache = new Map<FabricKind, FabricLook>();

export function fabricLook(kind: FabricKind): FabricLook {
  let look = cache.get(kind);
  if (!look) { look = makers[kind](); cache.set(kind, look); }
  return look;
}

/** Floor: warm light grey with faint tiles, darkening towards the edge so it melts into the backdrop. */
export function floorTexture(): Texture {
  const c = canvas(1024, (g, size) => {
    g.fillStyle = '#bcb6ac';
    g.fillRect(0, 0, size, size);
    // a soft pool of light around the middle of the stage
    const pool = g.createRadialGradient(size / 2, size / 2, 0, size / 2, size / 2, size * 0.16);
    pool.addColorStop(0, 'rgba(255, 252, 246, 0.45)');
    pool.addColorStop(1, 'rgba(255, 252, 246, 0)');
    g.fillStyle = pool;
    g.fillRect(0, 0, size, size);
    g.strokeStyle = 'rgba(80, 76, 70, 0.16)';
    g.lineWidth = 2;
    const cells = 40; // 1 m tiles on a 40 m floor
    for (let k = 0; k <= cells; k++) {
      const p = (k * size) / cells;
      g.beginPath(); g.moveTo(p, 0); g.lineTo(p, size); g.stroke();
      g.beginPath(); g.moveTo(0, p); g.lineTo(size, p); g.stroke();
    }
  });
  const t = track(new CanvasTexture(c), c);
  t.colorSpace = SRGBColorSpace;
  t.anisotropy = 8;
  return t;
}

/** Studio backdrop: a soft vertical gradient. */
export function backdropTexture(): Texture {
  const c = canvas(256, (g, size) => {
    const grad = g.createLinearGradient(0, 0, 0, size);
    grad.addColorStop(0, '#9fb3c8');
    grad.addColorStop(0.55, '#dfe4ea');
    grad.addColorStop(1, '#ece9e4');
    g.fillStyle = grad;
    g.fillRect(0, 0, size, size);
  });
  const t = track(new CanvasTexture(c), c);
  t.colorSpace = SRGBColorSpace;
  return t;
}
