import { describe, expect, it } from 'vitest';
import { parseSavedLayout } from './layout.js';

describe('parseSavedLayout: what a visit remembers of the HUD and panel', () => {
  it('reads the two choices', () => {
    expect(parseSavedLayout('{"hidden":true,"panelOpen":false}')).toEqual({ hidden: true, panelOpen: false });
    expect(parseSavedLayout('{"panelOpen":true}')).toEqual({ panelOpen: true });
    expect(parseSavedLayout('{"explain":false}')).toEqual({ explain: false });
  });

  it('nothing stored, unreadable or of the wrong type counts as not saved (the screen-size defaults apply)', () => {
    expect(parseSavedLayout(null)).toEqual({});
    expect(parseSavedLayout('{not json')).toEqual({});
    expect(parseSavedLayout('[1,2]')).toEqual({});
    expect(parseSavedLayout('"hidden"')).toEqual({});
    expect(parseSavedLayout('{"hidden":"yes","panelOpen":1}')).toEqual({});
  });
});
