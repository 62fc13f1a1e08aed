/**
 * Benchmark peer for self-contact: the method of Matthias Müller's Ten Minute Physics 15, "Self-collision of cloth"
 * (2022), written here from its description for `drape bench --self-contact` (its demo: a 30 × 200 particle strip,
 * 1 cm apart, falling into a pile, in real time in plain JavaScript). The cloth is particles only:
 *
 * - every particle is a ball of diameter `thickness` (the particle spacing): two particles nearer than it are pushed
 *   apart, half each, to `thickness` (to their rest distance where that is less, so neighbours in the mesh are
 *   left alone), then both their motions over the substep pulled toward their mean by `contactFriction` (friction
 *   between layers);
 * - the speed is capped at `0.2 · thickness / h` per substep, so a particle moves at most a fifth of the thickness
 *   in one substep and cannot jump through a layer;
 * - the neighbour lists come from a spatial hash built once per frame, listing every particle within the distance
 *   one particle can travel in the frame at the capped speed (`0.2 · thickness · substeps`, 2 cm in the demo; two
 *   particles can close more than that, so a pair can be missed: the demo's trade, kept here);
 * - stretch, shear and bending are XPBD distance constraints (grid edges, cell diagonals, and the far corners of
 *   each pair of triangles sharing an edge), solved Gauss–Seidel once per substep, with the floor at y = 0.
 *
 * The cloth is a grid triangle mesh (`GridCloth`), the same one Drape simulates in the comparison.
 */

/** A rectangular grid cloth: `nx × ny` particles `spacing` apart, its cells split into two triangles. */
export interface GridCloth {
  /** particle positions [m], xyz interleaved, row by row (x fastest) */
  positions: Float32Array;
  /** triangles, index triples */
  triangles: Uint32Array;
  nx: number;
  ny: number;
  /** distance between neighbouring particles [m] */
  spacing: number;
}

/**
 * The demo's strip as a grid: `nx × ny` particles `spacing` apart, hanging in the xy plane (x across, y up), its
 * lowest row at `bottom` [m], its rows waving in z by ±`wave` [m] with a wavelength of 8 rows (so that it folds as
 * it lands, instead of standing on its edge as a rod).
 */
export function hangingStrip(nx: number, ny: number, spacing: number, bottom: number, wave: number): GridCloth {
  const positions = new Float32Array(3 * nx * ny);
  // each row one spacing from the last along the wave
  const step = 2 * Math.PI / 8;
  let y = bottom;
  for (let j = 0; j < ny; j++) {
    const z = wave * Math.sin(step * j);
    if (j > 0) y += Math.sqrt(Math.max(spacing * spacing - (z - wave * Math.sin(step * (j - 1))) ** 2, 0));
    for (let i = 0; i < nx; i++) {
      const k = 3 * (j * nx + i);
      positions[k] = (i - (nx - 1) / 2) * spacing;
      positions[k + 1] = y;
      positions[k + 2] = z;
    }
  }
  const triangles = new Uint32Array(6 * (nx - 1) * (ny - 1));
  let t = 0;
  for (let j = 0; j + 1 < ny; j++) {
    for (let i = 0; i + 1 < nx; i++) {
      const a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      triangles.set([a, b, d, a, d, c], t);
      t += 6;
    }
  }
  return { positions, triangles, nx, ny, spacing };
}

/** The method's settings (every particle has inverse mass 1 [1/kg], as in the demo). */
export interface ParticleHashSettings {
  /** particle diameter and contact distance [m] (the demo: the spacing) */
  thickness: number;
  /** substeps per frame */
  substeps: number;
  /** whether particles collide with each other (the demo's switch; the speed cap holds either way) */
  contact: boolean;
  /** XPBD compliances [m/N] of the grid edges, the cell diagonals and the bending pairs */
  stretchCompliance: number;
  shearCompliance: number;
  bendCompliance: number;
  /**
   * share of the relative motion over the substep removed at each contact [-] (friction, inelastic contact): 0.2
   * here; at 0.5 and more the 30 × 200 pile never settles (RMS speed 1.4 m/s at 3 s, millions of crossing pairs)
   */
  contactFriction: number;
  gravity: [number, number, number];
}

export const PARTICLE_HASH_DEFAULTS: ParticleHashSettings = {
  thickness: 0.01,
  substeps: 10,
  contact: true,
  stretchCompliance: 0,
  shearCompliance: 1e-4,
  bendCompliance: 1,
  contactFriction: 0.2,
  gravity: [0, -9.81, 0],
};

/** The grid cloth stepped by the particle-hash method (see the file's comment). */
export class ParticleHashCloth {
  readonly positions: Float32Array;
  private readonly previous: Float32Array;
  private readonly velocities: Float32Array;
  private readonly rest: Float32Array;
  /** constraint pairs and their rest lengths [m] and compliances [m/N] */
  private readonly pairs: Uint32Array;
  private readonly restLengths: Float32Array;
  private readonly compliances: Float32Array;
  /** the spatial hash: cell starts (counting sort) and the particle ids sorted by cell */
  private readonly cellStart: Int32Array;
  private readonly cellEntries: Int32Array;
  private readonly tableSize: number;
  /** neighbour lists built once a frame: for particle i, neighbours[first[i] … first[i + 1]) */
  private readonly first: Int32Array;
  private neighbours: Int32Array;
  readonly n: number;

  constructor(cloth: GridCloth, readonly settings: ParticleHashSettings = PARTICLE_HASH_DEFAULTS) {
    const n = (this.n = cloth.nx * cloth.ny);
    this.positions = Float32Array.from(cloth.positions);
    this.previous = Float32Array.from(cloth.positions);
    this.velocities = new Float32Array(3 * n);
    this.rest = Float32Array.from(cloth.positions);
    const pairs: number[] = [], kinds: number[] = [];
    const { nx, ny } = cloth;
    for (let j = 0; j < ny; j++) {
      for (let i = 0; i < nx; i++) {
        const a = j * nx + i;
        if (i + 1 < nx) { pairs.push(a, a + 1); kinds.push(0); }
        if (j + 1 < ny) { pairs.push(a, a + nx); kinds.push(0); }
        if (i + 1 < nx && j + 1 < ny) { pairs.push(a, a + nx + 1, a + 1, a + nx); kinds.push(1, 1); }
      }
    }
    // bending: the two far corners of each pair of triangles sharing an edge
    const owner = new Map<number, number>();
    const tri = cloth.triangles;
    for (let t = 0; t < tri.length; t += 3) {
      for (let e = 0; e < 3; e++) {
        const a = tri[t + e], b = tri[t + (e + 1) % 3], far = tri[t + (e + 2) % 3];
        const key = Math.min(a, b) * n + Math.max(a, b);
        const other = owner.get(key);
        if (other === undefined) owner.set(key, far);
        else { pairs.push(other, far); kinds.push(2); }
      }
    }
    this.pairs = Uint32Array.from(pairs);
    this.restLengths = new Float32Array(kinds.length);
    this.compliances = new Float32Array(kinds.length);
    const c = [settings.stretchCompliance, settings.shearCompliance, settings.bendCompliance];
    for (let k = 0; k < kinds.length; k++) {
      const a = 3 * this.pairs[2 * k], b = 3 * this.pairs[2 * k + 1], x = this.rest;
      this.restLengths[k] = Math.hypot(x[a] - x[b], x[a + 1] - x[b + 1], x[a + 2] - x[b + 2]);
      this.compliances[k] = c[kinds[k]];
    }
    this.tableSize = 2 * n;
    this.cellStart = new Int32Array(this.tableSize + 1);
    this.cellEntries = new Int32Array(n);
    this.first = new Int32Array(n + 1);
    this.neighbours = new Int32Array(10 * n);
  }

  /** The hash cell of integer cell coordinates (Teschner et al. 2003's hash). */
  private cell(xi: number, yi: number, zi: number): number {
    return Math.abs((Math.imul(xi, 92837111) ^ Math.imul(yi, 689287499) ^ Math.imul(zi, 283923481))) % this.tableSize;
  }

  /** The spatial hash of the positions (cells of size `reach`) and each particle's neighbours within `reach` [m]. */
  private findNeighbours(reach: number): void {
    const x = this.positions, n = this.n, s = reach, start = this.cellStart, entries = this.cellEntries;
    start.fill(0);
    // counting sort: the counts, their running sums (start[h] the end of cell h), then each particle put at its
    // cell's end and the end moved down, so that start[h] … start[h + 1] holds cell h's particles
    for (let i = 0; i < n; i++) start[this.cell(Math.floor(x[3 * i] / s), Math.floor(x[3 * i + 1] / s), Math.floor(x[3 * i + 2] / s))]++;
    for (let k = 1; k <= this.tableSize; k++) start[k] += start[k - 1];
    for (let i = 0; i < n; i++) {
      const h = this.cell(Math.floor(x[3 * i] / s), Math.floor(x[3 * i + 1] / s), Math.floor(x[3 * i + 2] / s));
      entries[--start[h]] = i;
    }
    const r2 = reach * reach;
    let count = 0;
    for (let i = 0; i < n; i++) {
      this.first[i] = count;
      const px = x[3 * i], py = x[3 * i + 1], pz = x[3 * i + 2];
      const x0 = Math.floor((px - reach) / s), x1 = Math.floor((px + reach) / s);
      const y0 = Math.floor((py - reach) / s), y1 = Math.floor((py + reach) / s);
      const z0 = Math.floor((pz - reach) / s), z1 = Math.floor((pz + reach) / s);
      for (let xi = x0; xi <= x1; xi++) for (let yi = y0; yi <= y1; yi++) for (let zi = z0; zi <= z1; zi++) {
        const h = this.cell(xi, yi, zi);
        for (let e = start[h]; e < start[h + 1]; e++) {
          const j = entries[e];
          if (j <= i) continue;
          const dx = x[3 * j] - px, dy = x[3 * j + 1] - py, dz = x[3 * j + 2] - pz;
          if (dx * dx + dy * dy + dz * dz > r2) continue;
          if (count === this.neighbours.length) {
            const grown = new Int32Array(2 * count);
            grown.set(this.neighbours);
            this.neighbours = grown;
          }
          this.neighbours[count++] = j;
        }
      }
    }
    this.first[n] = count;
  }

  /** One frame of `dt` [s]: the neighbours, then the substeps. */
  step(dt: number): void {
    const { substeps, thickness, gravity, contactFriction } = this.settings;
    const h = dt / substeps, vMax = (0.2 * thickness) / h;
    if (this.settings.contact) this.findNeighbours(vMax * dt);
    else this.first.fill(0);
    const x = this.positions, xp = this.previous, v = this.velocities, rest = this.rest, n = this.n;
    const pairs = this.pairs, restLengths = this.restLengths, compliances = this.compliances;
    for (let sub = 0; sub < substeps; sub++) {
      for (let i = 0; i < n; i++) {
        const k = 3 * i;
        let vx = v[k] + gravity[0] * h, vy = v[k + 1] + gravity[1] * h, vz = v[k + 2] + gravity[2] * h;
        const speed = Math.sqrt(vx * vx + vy * vy + vz * vz);
        if (speed > vMax) { const f = vMax / speed; vx *= f; vy *= f; vz *= f; }
        xp[k] = x[k]; xp[k + 1] = x[k + 1]; xp[k + 2] = x[k + 2];
        x[k] += vx * h; x[k + 1] += vy * h; x[k + 2] += vz * h;
      }
      // XPBD distance constraints, every particle's inverse mass 1
      for (let c = 0; c < restLengths.length; c++) {
        const a = 3 * pairs[2 * c], b = 3 * pairs[2 * c + 1];
        const dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
        const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
        if (len === 0) continue;
        const alpha = compliances[c] / (h * h);
        const s = -(len - restLengths[c]) / (len * (2 + alpha));
        x[a] += s * dx; x[a + 1] += s * dy; x[a + 2] += s * dz;
        x[b] -= s * dx; x[b + 1] -= s * dy; x[b + 2] -= s * dz;
      }
      // contact between particles: apart to the thickness (or their rest distance), velocities toward their mean
      const t2 = thickness * thickness;
      for (let i = 0; i < n; i++) {
        const a = 3 * i;
        for (let e = this.first[i]; e < this.first[i + 1]; e++) {
          const b = 3 * this.neighbours[e];
          const dx = x[b] - x[a], dy = x[b + 1] - x[a + 1], dz = x[b + 2] - x[a + 2];
          const d2 = dx * dx + dy * dy + dz * dz;
          if (d2 > t2 || d2 === 0) continue;
          const r2 = (rest[b] - rest[a]) ** 2 + (rest[b + 1] - rest[a + 1]) ** 2 + (rest[b + 2] - rest[a + 2]) ** 2;
          if (d2 > r2) continue;
          const d = Math.sqrt(d2), min = Math.min(thickness, Math.sqrt(r2));
          const s = (0.5 * (min - d)) / d;
          x[a] -= s * dx; x[a + 1] -= s * dy; x[a + 2] -= s * dz;
          x[b] += s * dx; x[b + 1] += s * dy; x[b + 2] += s * dz;
          for (let c = 0; c < 3; c++) {
            const va = x[a + c] - xp[a + c], vb = x[b + c] - xp[b + c], mean = 0.5 * (va + vb);
            x[a + c] += contactFriction * (mean - va);
            x[b + c] += contactFriction * (mean - vb);
          }
        }
      }
      // the floor, with the particle's radius, last: a particle in it is put on it at rest (an inelastic floor with
      // friction: put back and given the speed of being put back, the bottom layer of a pile pumps the pile upward)
      for (let k = 0; k < 3 * n; k += 3) {
        if (x[k + 1] < 0.5 * thickness) { x[k] = xp[k]; x[k + 2] = xp[k + 2]; x[k + 1] = xp[k + 1] = 0.5 * thickness; }
      }
      for (let k = 0; k < 3 * n; k++) v[k] = (x[k] - xp[k]) / h;
    }
  }
}
