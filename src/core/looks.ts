/**
 * How each cloth looks: which of the app's procedural looks it gets (fabricFor) and, per look, the plain colour
 * and roughness an exported material carries (LOOKS). The app paints its textures (render/textures.ts) with the
 * same roughness; the colour is the mean of the app's texture, for files that carry no texture (the CLI's exports);
 * exportCloths names and dresses a scene's cloths for the writers (mesh/glb.ts, mesh/obj-export.ts).
 */
import { clothEntries, clothName, type Scene } from './scene.js';

export type FabricKind = 'cotton' | 'silk' | 'leather' | 'rubber' | 'flag' | 'hammock' | 'checker';

/** An exported material: a name, a colour (sRGB, 0…1 per channel) and a PBR roughness [0, 1]. */
export interface LookMaterial {
  readonly name: string;
  readonly color: readonly [number, number, number];
  readonly roughness: number;
}

const hex = (s: string): [number, number, number] => [1, 3, 5].map((i) => parseInt(s.slice(i, i + 2), 16) / 255) as [number, number, number];

/**
 * Each look's exported material: the mean colour of the app's texture (its ground and pattern weighted by the area
 * each covers, worked out from the painter in render/textures.ts) and the roughness the app's material has.
 */
export const LOOKS: Readonly<Record<FabricKind, LookMaterial>> = {
  cotton: { name: 'cotton fabric', color: hex('#96a9c5'), roughness: 0.9 },
  silk: { name: 'silk fabric', color: hex('#9c1e3a'), roughness: 0.38 },
  leather: { name: 'leather fabric', color: hex('#6b3f22'), roughness: 0.62 },
  rubber: { name: 'rubber fabric', color: hex('#efad08'), roughness: 0.32 },
  flag: { name: 'flag fabric', color: hex('#9d758b'), roughness: 0.85 },
  hammock: { name: 'hammock fabric', color: hex('#c29f86'), roughness: 0.92 },
  checker: { name: 'checker fabric', color: hex('#e9af8f'), roughness: 0.85 },
};

/** the fabrics (fabrics.ts) that have a look of their own; the others (denim, wool) look like cotton */
const FABRIC_LOOKS: Partial<Record<string, FabricKind>> = { cotton: 'cotton', silk: 'silk', leather: 'leather', rubber: 'rubber' };

/**
 * Which look a cloth gets: the built-in scenes that are about one thing have theirs (the Wind scene's flag, the Pins
 * hammock, the Mesh Resolution checker); any other cloth its fabric's (`material.fabric`), or, without a named
 * fabric, the one its scene's name starts with ('silk…'); cotton when neither says.
 */
export function fabricFor(sceneName: string, fabric?: string): FabricKind {
  if (sceneName === 'wind') return 'flag';
  if (sceneName === 'pins') return 'hammock';
  if (sceneName === 'resolution') return 'checker';
  const own = fabric === undefined ? undefined : FABRIC_LOOKS[fabric];
  if (own) return own;
  if (fabric === undefined) {
    for (const kind of ['silk', 'leather', 'rubber'] as const) if (sceneName.startsWith(kind)) return kind;
  }
  return 'cotton';
}

/**
 * Each cloth of a scene as the exports name and dress it: 'cloth' alone, or each of a list by its name ('cloth k'
 * without one), in its look's material.
 */
export function exportCloths(scene: Scene): { name: string; material: LookMaterial }[] {
  return clothEntries(scene).map((e, k) => ({ name: scene.cloths ? clothName(e, k) : 'cloth', material: LOOKS[fabricFor(scene.name, e.material.fabric)] }));
}
