/**
 * The "explain" caption at the bottom of the view: what the scene on screen demonstrates and what to try, for a
 * class (the seed's purpose: to show how a cloth's characteristics and its resolution change it). A built-in
 * scene has its own words; an imported scene shows its own `description`, as text. E toggles it (app/layout.ts).
 */
import { plainText } from '../core/index.js';
import { append, h } from './dom.js';

/** What each built-in scene demonstrates, and what to try in it. */
export const SCENE_CAPTIONS: Record<string, string> = {
  'cotton-basic': 'A cotton sheet falls onto a sphere and folds where it slides off. Try: V to see the springs that ' +
    'hold it together; drag the cloth; change the fabric and drop it again (R).',
  'silk-drape': 'Silk is light and bends easily, so it clings to the sphere in many small folds. Compare it with ' +
    'leather: same shape, very different drape.',
  'leather-stiff': 'Leather is heavy and hard to bend: it falls into a few broad folds. Try lowering “bend” and ' +
    'watch the folds get finer.',
  'rubber-stretch': 'Rubber stretches visibly under its own weight. Press V until the strain view: red is stretched, ' +
    'blue compressed.',
  custom: 'Every parameter is yours: change a slider and the cloth reacts at once. Stiffer springs need more ' +
    'substeps with the mass-spring solver — the panel says when it had to soften them.',
  wind: 'A flag pinned along its pole, in gusty wind. Turn the wind off and it droops; raise the strength and it ' +
    'flutters harder.',
  pins: 'A hammock: four corners pinned. Press P and click a particle to pin or unpin it; unpin a corner to see it ' +
    'fall.',
  tablecloth: 'A tablecloth falls onto a box table: cloth meeting flat faces and sharp edges, with friction holding ' +
    'it on the top.',
  cape: 'A cape pinned to the shoulders of a turning mannequin: pins that move with a body. Change the pose or the ' +
    'animation in the Mannequin folder.',
  skirt: 'A silk skirt, a tube of cloth held at the waist of a walking mannequin: the cloth swings with the legs.',
  cantilever: 'The Peirce cantilever test (ASTM D1388): a strip pushed over an edge bends under its own weight. The ' +
    'tip’s angle gives the bending length, shown in the HUD; try other fabrics.',
  cusick: 'The Cusick drape test (BS 5058): a woven disc of fabric clamped on a pedestal. The drape coefficient (the ' +
    'share of the overhang its shadow still covers: 1 flat, 0 hanging straight down) and the folds are in the HUD: ' +
    'rubber and silk drape most, leather least.',
  resolution: 'The same cloth with 1 to 4096 faces, one after another (or side by side): the finer the mesh, the ' +
    'finer the folds it can make. Untick “scale with resolution” to see the seed’s raw spring constants.',
  fold: 'A cotton sheet dropped corner first onto the floor lands on itself in layers; self-contact keeps them ' +
    'apart. Untick “self-contact” in the Solver folder and drop it again (R): the layers pass through each other.',
  layers: 'Three cloths dropped one after another onto the sphere: stiff leather below, cotton, then light silk on ' +
    'top, each draped on the one below. Pick a cloth in Cloth & material to change its fabric; untick ' +
    '“self-contact” and they fall through each other.',
};

/**
 * The caption for the scene on screen: a built-in's words, else the scene's own description ('' when none), made
 * plain (no control or direction-changing characters, at most 400 characters).
 */
export function captionFor(sceneKey: string, description: string | undefined): string {
  return SCENE_CAPTIONS[sceneKey] ?? (description ? plainText(description, 400) : '');
}

/** The caption box (text only) with its close button. */
export class Caption {
  readonly el: HTMLElement;
  private readonly text: HTMLElement;
  private shown = '';

  /** `onClose`: the close button was pressed (the layout turns captions off) */
  constructor(parent: HTMLElement, onClose: () => void) {
    this.text = h('span', { testid: 'caption-text' });
    const close = h('button', { className: 'drape-caption-close', title: 'hide the explanation (E)' }, '×');
    close.addEventListener('click', onClose);
    this.el = h('div', { className: 'drape-caption', testid: 'caption' });
    append(this.el, [this.text, close]);
    parent.append(this.el);
  }

  /** Shows `text` (as text, never markup); nothing when it is empty. */
  set(text: string): void {
    if (text === this.shown) return;
    this.shown = text;
    this.text.textContent = text;
    this.el.classList.toggle('empty', text === '');
  }
}
