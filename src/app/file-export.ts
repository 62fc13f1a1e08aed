/**
 * Downloads: the scene as a JSON document, a PNG screenshot, the cloths at their current shape as OBJ or binary
 * glTF, and a recording as animated glTF (never a file with NaN in it): one object per cloth (a scene of several:
 * each by its name, with its fabric's look), its vertices in the scene's particle order (an OBJ's numbering is the
 * scene's). The files are the core's writers' (core/mesh/obj-export.ts, core/mesh/glb.ts), as the CLI's; the .glb
 * files embed each look's texture. File names come from the scene's name, made safe.
 */
import {
  clothEntries, clothName, FRAME_DT, LOOKS, modelCloths, plainText, sceneDocument, toGLB, toOBJ, type ClothModel, type ExportCloth,
  type FabricKind, type GlbBake, type GlbMaterial, type Scene,
} from '../core/index.js';
import type { FabricLook } from '../render/textures.js';
import type { App } from './app.js';
import { baseName, meshNames } from './meshes.js';
import type { Take } from './recorder.js';

/**
 * A screenshot's pixel size: 'W×H' (written with an x) as it says, or 'view': the free part of the window, `viewW` ×
 * `viewH` CSS px, at the screen's pixel `ratio` (the panel's sizes: ui/panel.ts PNG_SIZES); between 16 and 4096 px a
 * side, never NaN.
 */
export function pngSize(size: string, viewW: number, viewH: number, ratio: number): [number, number] {
  const m = /^(\d+)x(\d+)$/.exec(size);
  const r = Number.isFinite(ratio) && ratio > 0 ? ratio : 1;
  const [w, h] = m ? [Number(m[1]), Number(m[2])] : [viewW * r, viewH * r];
  const side = (v: number) => Math.min(4096, Math.max(16, Math.round(Number.isFinite(v) ? v : 16)));
  return [side(w), side(h)];
}

/** The page's downloads. */
export class FileExport {
  /** each look's material with its texture as PNG, made once */
  private readonly materials = new Map<FabricKind, Promise<GlbMaterial>>();

  constructor(private readonly app: App) {}

  private download(blob: Blob, name: string): void {
    const url = URL.createObjectURL(blob);
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10_000);
  }

  /** a file name from the scene's name: letters, digits, '.', '_' and '-' only, never hidden or empty */
  private fileBase(name = this.app.scene.name): string {
    return plainText(name, 60).replace(/[^\w.-]+/g, '-').replace(/^[.-]+/, '') || 'scene';
  }

  /**
   * Downloads the scene document (what an import or a link reproduces). A document naming mesh files (cloth.mesh,
   * colliders[k].mesh) does not hold them: the notice says that the files go with it.
   */
  exportJson(): void {
    // the document form: a scene of several cloths as its list `cloths` (what an import or drape run takes back)
    const doc = { $schema: 'https://drape.dev/scene.schema.json', ...sceneDocument(this.app.scene) };
    const name = `${this.fileBase()}.json`;
    this.download(new Blob([JSON.stringify(doc, null, 2) + '\n'], { type: 'application/json' }), name);
    const meshes = meshNames(this.app.scene);
    if (meshes.length) {
      const one = meshes.length === 1;
      const files = meshes.map((m) => plainText(m, 80)).join(', ');
      const where = meshes.every((m) => baseName(m) === m) ? 'next to it' : `at ${one ? 'that path' : 'those paths'}, relative to it`;
      this.app.overlay.message(`Exported ${name}: it names the mesh file${one ? '' : 's'} ${files} and does not hold ${one ? 'it' : 'them'} — ` +
        `keep the file${one ? '' : 's'} ${where} (drape run reads ${one ? 'it' : 'them'} from there; the app needs ${one ? 'it' : 'them'} imported too)`, 'notice');
    }
  }

  /**
   * Downloads the view as PNG, without the part the panel covers: `size` 'view' is the free part of the window at
   * the screen's pixel ratio, or 'WxH' pixels, the subject centred as on screen.
   */
  screenshot(size: string = 'view'): void {
    const { stage, overlay } = this.app;
    const [w, h] = pngSize(size, stage.container.clientWidth - stage.viewInset, stage.container.clientHeight, stage.renderer.getPixelRatio());
    void stage.snapshot(w, h).then((blob) => {
      if (blob) this.download(blob, `drape-${this.fileBase()}.png`);
      else overlay.message('screenshot failed: the canvas could not be read');
    });
  }

  /** why the cloths cannot be exported or recorded now ('' when they can): never a file with NaN in it */
  exportProblem(): string {
    const app = this.app;
    for (const [k, m] of app.sim.mirrors.entries()) {
      if (m.unstableAt >= 0) return `${app.slots.clothName(k)} became unstable at frame ${m.unstableAt}; reset it first`;
      const x = m.sim.state.positions;
      for (let i = 0; i < x.length; i++) if (!Number.isFinite(x[i])) return `${app.slots.clothName(k)} has positions that are not finite; reset it first`;
    }
    return '';
  }

  /**
   * Says that `what` (an export, a recording) is refused for `problem` (exportProblem's): an unstable cloth, which
   * Reset mends, so the message keeps the Reset button the unstable cloth's own message had.
   */
  refuse(what: string, problem: string): void {
    this.app.overlay.message(`${what} refused: ${problem}.`, 'error', { label: 'Reset', run: () => this.app.commands.reset() });
  }

  /** Downloads the cloths as OBJ (the core's writer, as `drape run --export`, without the MTL); refused while one is unstable. */
  exportObj(): void {
    const problem = this.exportProblem();
    if (problem) { this.refuse('OBJ export', problem); return; }
    const cloths = this.app.sim.mirrors.flatMap((m) => modelCloths(m.sim.model, m.sim.state.positions,
      this.dress(m.sim.scene).map(({ name, look }) => ({ name, material: LOOKS[look.kind] }))));
    const text = toOBJ({ name: this.app.scene.name, cloths });
    this.download(new Blob([text], { type: 'model/obj' }), `${this.fileBase()}.obj`);
  }

  /**
   * A slot's cloths named as the files' objects (one cloth: `cloth`; a sweep's row: cloth-<resolution>; a scene of
   * several: each by its name), with their looks.
   */
  private dress(scene: Scene): { name: string; look: FabricLook }[] {
    const entries = clothEntries(scene), looks = this.app.slots.looks(scene), slots = this.app.sim.mirrors.length;
    return entries.map((e, c) => ({
      name: entries.length > 1 ? plainText(clothName(e, c), 60) : slots > 1 ? `cloth-${scene.cloth.resolution}` : 'cloth',
      look: looks[c],
    }));
  }

  /** A look's material for the .glb: its roughness and its texture (the canvas as PNG, repeated as on screen). */
  private material(look: FabricLook): Promise<GlbMaterial> {
    let m = this.materials.get(look.kind);
    if (!m) {
      const canvas = look.map.image as HTMLCanvasElement;
      m = new Promise<Blob | null>((done) => canvas.toBlob(done, 'image/png')).then(async (blob) => ({
        ...LOOKS[look.kind], roughness: look.roughness,
        ...(blob ? { texture: { png: new Uint8Array(await blob.arrayBuffer()), repeat: look.map.repeat.x } } : {}),
      }));
      this.materials.set(look.kind, m);
    }
    return m;
  }

  /** Each slot's cloths over `positions` (a recording's `frames` after them), named and dressed in their looks' textures. */
  private async cloths(scenes: readonly Scene[], models: readonly ClothModel[], positions: readonly Float32Array[], frames?: readonly Float32Array[][]): Promise<ExportCloth[]> {
    const slots = await Promise.all(scenes.map(async (scene, k) => {
      const dress = await Promise.all(this.dress(scene).map(async ({ name, look }) => ({ name, material: await this.material(look) })));
      return modelCloths(models[k], positions[k], dress, frames?.map((f) => f[k]));
    }));
    return slots.flat();
  }

  /** Writes and downloads a .glb; says so if the writer refuses (it never writes NaN). */
  private async downloadGlb(scene: string, file: string, cloths: ExportCloth[], bake?: GlbBake): Promise<void> {
    try {
      const glb = toGLB({ name: scene, cloths, ...(bake ? { bake } : {}) });
      this.download(new Blob([glb], { type: 'model/gltf-binary' }), file);
    } catch (e) {
      this.app.overlay.message(`glTF export failed: ${(e as Error).message}`);
    }
  }

  /** Downloads the cloths as binary glTF (.glb); refused while one is unstable. */
  exportGltf(): void {
    const problem = this.exportProblem();
    if (problem) { this.refuse('glTF export', problem); return; }
    // the shapes now: the mirrors move on while the textures are encoded
    const mirrors = this.app.sim.mirrors;
    const shapes = mirrors.map((m) => m.sim.state.positions.slice());
    void this.cloths(mirrors.map((m) => m.sim.scene), mirrors.map((m) => m.sim.model), shapes)
      .then((cloths) => this.downloadGlb(this.app.scene.name, `${this.fileBase()}.glb`, cloths));
  }

  /** Downloads a recording (recorder.ts) as an animated .glb: its first frame at time 0, the others at theirs. */
  async downloadTake(take: Take): Promise<void> {
    const cloths = await this.cloths(take.scenes, take.models, take.first, take.shapes);
    const times = take.frames.map((f) => (f - take.start) * FRAME_DT);
    await this.downloadGlb(take.name, `${this.fileBase(take.name)}-recording.glb`, cloths, { times, frameNumbers: take.frames });
  }
}
