import { describe, expect, it } from 'vitest';
import { exportCloths, Simulation, validateScene } from '../index.js';
import { modelCloths } from './glb.js';
import { toMTL, toOBJ } from './obj-export.js';
import { parseObj } from './obj.js';

describe('the OBJ and MTL writers', () => {
  const scene = validateScene({
    name: 'two\nlooks',
    cloths: [
      { name: 'a b', cloth: { resolution: 3, position: [0, 1, 0] }, material: { fabric: 'leather' } },
      { name: 'c', cloth: { shape: 'disc', resolution: 5, position: [0, 1.4, 0] } },
      { name: 'd', cloth: { resolution: 2, position: [0, 1.8, 0] }, material: { fabric: 'leather' } },
    ],
  });
  const sim = new Simulation(scene, { kernel: 'ts' });
  sim.advance(10);
  const cloths = modelCloths(sim.model, sim.state.positions, exportCloths(scene));

  it('one vertex list in the scene\'s numbering, an object per cloth with its material, unit normals', () => {
    const text = toOBJ({ name: scene.name, cloths, mtllib: 'two.mtl' });
    // read back by the app's and the CLI's own reader: the same positions, every triangle
    const back = parseObj(text, 'two.obj');
    expect(Array.from(back.positions)).toEqual(Array.from(sim.state.positions));
    expect(back.triangles.length).toBe(sim.model.triangles.length);
    const lines = text.split('\n');
    expect(lines[0]).toBe(`# Drape cloth 'two\ufffdlooks': ${sim.model.particleCount} vertices, ${sim.model.triangles.length / 3} triangles, 3 cloths`);
    expect(lines[1]).toBe('mtllib two.mtl');
    expect(lines.filter((l) => l.startsWith('o ') || l.startsWith('usemtl '))).toEqual([
      'o a b', 'usemtl leather_fabric', 'o c', 'usemtl cotton_fabric', 'o d', 'usemtl leather_fabric',
    ]);
    const normals = lines.filter((l) => l.startsWith('vn ')).map((l) => l.slice(3).split(' ').map(Number));
    expect(normals).toHaveLength(sim.model.particleCount);
    for (const n of normals) expect(Math.hypot(n[0], n[1], n[2])).toBeCloseTo(1, 6);
    // cloth c's faces index its own vertices, after cloth a's
    const starts = sim.model.clothStarts;
    const faces = lines.slice(lines.indexOf('o c'), lines.indexOf('o d')).filter((l) => l.startsWith('f '));
    const used = faces.flatMap((f) => f.slice(2).split(' ').map((corner) => Number(corner.split('/')[0]) - 1));
    expect(Math.min(...used)).toBe(starts[1]);
    expect(Math.max(...used)).toBe(starts[2] - 1);
  });

  it('object names: one line, no #, and a name for an empty one', () => {
    const odd = validateScene({
      cloths: ['', '   ', 'a b#c'].map((name, k) => ({ name, cloth: { resolution: 1, position: [0, 1 + k, 0] } })),
    });
    const s = new Simulation(odd, { kernel: 'ts' });
    const text = toOBJ({ name: odd.name, cloths: modelCloths(s.model, s.state.positions, exportCloths(odd)) });
    expect(text.match(/^o .*$/gm)).toEqual(['o cloth 1', 'o cloth 2', 'o a b_c']);
    s.dispose();
  });

  it('refuses what is not a finite number: positions (OBJ), a colour or roughness (MTL)', () => {
    const sim = new Simulation(validateScene({ cloth: { resolution: 2 } }), { kernel: 'ts' });
    const x = sim.state.positions.slice();
    x[4] = Infinity;
    const cloths = modelCloths(sim.model, x, exportCloths(sim.scene));
    expect(() => toOBJ({ name: 'x', cloths })).toThrow(/^obj: cloth '.*' has positions that are not finite \(vertex 1\)$/);
    const [c] = modelCloths(sim.model, sim.state.positions, exportCloths(sim.scene));
    expect(() => toMTL({ name: 'x', cloths: [{ ...c, material: { ...c.material, roughness: NaN } }] })).toThrow(/^mtl: material '.*' has a colour or roughness that is not a finite number$/);
    expect(toOBJ({ name: 'x', cloths: [c] })).not.toMatch(/NaN|Infinity/);
    for (const input of [null, {}, { name: 'x' }]) {
      expect(() => toOBJ(input as never)).toThrow(/^obj: the input must be \{ name, cloths: \[\.\.\.\] \}/);
      expect(() => toMTL(input as never)).toThrow(/^mtl: the input must be/);
    }
    sim.dispose();
  });

  it('the MTL: one material per look, its colour and roughness', () => {
    const mtl = toMTL({ name: scene.name, cloths });
    expect(mtl.match(/^newmtl .*$/gm)).toEqual(['newmtl leather_fabric', 'newmtl cotton_fabric']);
    expect(mtl).toContain('newmtl leather_fabric\nKd 0.4196 0.2471 0.1333\nKa 0 0 0\nKs 0.04 0.04 0.04\nNs 144.4\nPr 0.62\nPm 0\nd 1\nillum 2\n');
    expect(mtl.split('\n')[0]).toBe("# Drape materials of 'two\ufffdlooks'");
  });
});
