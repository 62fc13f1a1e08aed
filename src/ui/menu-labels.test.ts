import { describe, expect, it } from 'vitest';
import { SCENE_NAMES, builtinScene, validateScene } from '../core/index.js';
import { SCENE_CAPTIONS } from './captions.js';
import { SCENE_LABELS, clothOptions } from './menu-labels.js';

describe("the panel's menus", () => {
  it("the cloth control: each cloth by its name (as text), unique, to its index", () => {
    expect(clothOptions(builtinScene('layers'))).toEqual({ leather: 0, cotton: 1, silk: 2 });
    expect(clothOptions(builtinScene('cotton-basic'))).toEqual({ 'cloth 0': 0 });
    const odd = validateScene({ cloths: [
      { name: 'top', cloth: { position: [0, 1, 0] } }, { name: 'top', cloth: { position: [0, 1.3, 0] } },
      { cloth: { position: [0, 1.6, 0] } }, { name: 'a\u202Eb\nc', cloth: { position: [0, 1.9, 0] } },
    ] });
    expect(clothOptions(odd)).toEqual({ '0: top': 0, '1: top': 1, 'cloth 2': 2, 'a\uFFFDb\uFFFDc': 3 });
  });

  it('every built-in scene has a menu label and a caption', () => {
    for (const name of SCENE_NAMES) {
      expect(SCENE_LABELS[name], name).toBeTruthy();
      expect(SCENE_CAPTIONS[name], name).toBeTruthy();
    }
  });
});
