import { Texture } from 'three/webgpu';
import { describe, expect, it } from 'vitest';
import { Simulation, clothEntries, clothName } from '../core/index.js';
import { DrapeCloth } from '../three/cloth.js';
import { ClothView } from './cloth-view.js';
import type { FabricLook } from './textures.js';

const look = (kind: FabricLook['kind']): FabricLook => ({ kind, map: new Texture(), roughness: 0.8, sheen: 0, sheenColor: '#ffffff', clearcoat: 0 });

describe('ClothView: the app draws its cloths as the addon draws a world\'s', () => {
  it('holds one drape/three DrapeCloth per cloth, each in its look; the colour views colour them all', () => {
    const sim = new Simulation({
      cloths: [
        { name: 'square', cloth: { resolution: 4, position: [0, 1, 0] }, material: { fabric: 'silk' } },
        { cloth: { shape: 'disc', resolution: 6, position: [0, 2, 0] }, material: { fabric: 'leather' } },
      ],
    }, { kernel: 'ts' });
    const entries = clothEntries(sim.scene);
    const view = new ClothView(sim.model, entries.map((entry, c) => ({ entry, name: clothName(entry, c), look: look(c ? 'leather' : 'silk') })));
    expect(view.cloths.map((c) => c instanceof DrapeCloth)).toEqual([true, true]);
    expect(view.cloths.map((c) => c.name)).toEqual(['square', 'cloth 1']);
    expect(view.cloths.every((c) => view.group.children.includes(c))).toBe(true);
    expect(view.drawnCloths).toEqual(sim.model.clothParts!.map((p, c) => ({ look: c ? 'leather' : 'silk', triangles: p.triangles.length / 3 })));
    // stepped, the cloths show the state's positions
    sim.advance(5);
    view.update(sim.state, -1);
    const x = sim.state.positions, second = view.cloths[1];
    expect(Array.from(second.positions)).toEqual(Array.from(x.subarray(3 * second.start, 3 * (second.start + second.particleCount))));
    const position = second.geometry.getAttribute('position');
    expect(position.getY(second.start)).toBe(x[3 * second.start + 1]);
    // the strain view: every cloth drawn with the vertex-coloured material, over the colours the view writes
    view.setView('strain');
    view.update(sim.state, -1);
    const materials = new Set(view.cloths.map((c) => c.material));
    expect(materials.size).toBe(1);
    expect(view.cloths.every((c) => c.geometry.getAttribute('color') !== undefined)).toBe(true);
    view.setView('wireframe');
    expect(view.cloths.every((c) => !c.visible)).toBe(true);
    view.setView('shaded');
    expect(view.cloths.map((c) => c.visible)).toEqual([true, true]);
    expect(new Set(view.cloths.map((c) => c.material)).size).toBe(2);
    view.dispose();
    sim.dispose();
  });
});
