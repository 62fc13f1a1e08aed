/**
 * The words of the panel's menus: the built-in scenes' labels and the cloth control's options (a scene's cloth
 * names, as text). Pure: unit-tested in menu-labels.test.ts.
 */
import { clothEntries, clothName, plainText, type Scene } from '../core/index.js';

/** The scene menu's label of each built-in scene (the others show by their name). */
export const SCENE_LABELS: Record<string, string> = {
  'cotton-basic': 'Cotton Basic',
  'silk-drape': 'Silk Drape',
  'leather-stiff': 'Leather Stiff',
  'rubber-stretch': 'Rubber Stretch',
  custom: 'Custom Parameters',
  wind: 'Wind',
  pins: 'Pins',
  tablecloth: 'Tablecloth',
  cape: 'Cape',
  skirt: 'Skirt',
  cantilever: 'Cantilever (ASTM D1388)',
  cusick: 'Cusick Drape (BS 5058)',
  resolution: 'Mesh Resolution',
  fold: 'Fold',
  layers: 'Layers (three cloths)',
};

/**
 * The cloth control's options: each cloth by its name (as text: plainText; 'cloth k' without one), unique (a name
 * two cloths share gets its number).
 */
export function clothOptions(scene: Scene): Record<string, number> {
  const entries = clothEntries(scene);
  const names = entries.map((e, k) => plainText(clothName(e, k), 40));
  const out: Record<string, number> = {};
  names.forEach((n, k) => { out[names.indexOf(n) === k && names.lastIndexOf(n) === k ? n : `${k}: ${n}`] = k; });
  return out;
}
