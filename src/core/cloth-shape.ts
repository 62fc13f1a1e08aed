/**
 * From a scene's `cloth` to a model: the shape it names (the seed's rectangle grid, a disc, a tube, or a mesh
 * file), scaled and placed, checked and turned into particles, springs and colours. Mesh files are read by the
 * host (a path means nothing to the core, which runs in browsers too): the CLI and `drape/node` read them next
 * to the scene file; the app from an imported file.
 */
import { buildGridModel, buildMeshModel, mergeModels, type ClothModel } from './model.js';
import { discMesh, placeMesh, tubeFaces, tubeMesh, wovenDiscCells, wovenDiscMesh } from './mesh/generators.js';
import { parseGltf, type ExternalReader } from './mesh/gltf.js';
import { parseObj } from './mesh/obj.js';
import { extent, prepareMesh, type TriangleMesh } from './mesh/triangle-mesh.js';
import { SceneError, clothEntries, type ClothSpec, type Scene } from './scene.js';
import { plainText, shownValue } from './text.js';

/** The cloth shapes a scene can name (`cloth.shape`). */
export const CLOTH_SHAPES = ['rectangle', 'disc', 'tube', 'mesh'] as const;
export type ClothShape = (typeof CLOTH_SHAPES)[number];

/** The mesh a scene's `cloth.mesh` path names, as read and parsed by the host (throws SceneError naming the file). */
export type MeshResolver = (path: string) => TriangleMesh;

/** File types a cloth mesh may come in, by extension. */
export const MESH_EXTENSIONS = ['.obj', '.gltf', '.glb'] as const;

/**
 * Parses a mesh file's bytes by its name's extension (.obj, .gltf, .glb); `readExternal` reads a .gltf's separate
 * buffers. Throws SceneError naming the file. The mesh is checked when a model is built from it.
 */
export function parseMeshFile(bytes: Uint8Array, name: string, readExternal?: ExternalReader): TriangleMesh {
  if (typeof name !== 'string') throw new TypeError(`parseMeshFile: the file's name must be a string (its extension says the format), got ${shownValue(name)}`);
  const shown = plainText(name, 200);
  // the file's bytes: a Uint8Array (a Node Buffer is one); an ArrayBuffer or anything else is refused by name
  if (!(bytes instanceof Uint8Array)) throw new TypeError(`parseMeshFile: ${shown}: the file's contents must be a Uint8Array, got ${shownValue(bytes)}`);
  return meshFormat(name) === '.obj' ? parseObj(new TextDecoder().decode(bytes), shown) : parseGltf(bytes, shown, readExternal);
}

/** The extension of a mesh file's name (one of MESH_EXTENSIONS), or a SceneError naming the file. */
export function meshFormat(name: string): (typeof MESH_EXTENSIONS)[number] {
  const ext = name.slice(name.lastIndexOf('.')).toLowerCase();
  const known = MESH_EXTENSIONS.find((e) => e === ext);
  if (!known) throw new SceneError(`${plainText(name, 200)}: not a mesh file Drape reads (${MESH_EXTENSIONS.join(', ')})`);
  return known;
}

/**
 * The model of a scene's cloths: one cloth's, or several merged into one (mergeModels; cloth c's particles from
 * model.clothStarts[c]). A 'mesh' needs `meshes` to turn cloth.mesh into a mesh; without it (a link, a scene passed
 * without its files) the error says so.
 */
export function modelFor(scene: Scene, meshes?: MeshResolver): ClothModel {
  const entries = clothEntries(scene);
  return mergeModels(entries.map((e, k) => clothModel(e.cloth, e.material.scaleWithResolution, meshes, scene.cloths ? `cloths[${k}].` : '')));
}

/**
 * What a cloth's spec asks that its shape does not do (`at` prefixes the fields: '' or 'cloths[1].'), one line each
 * for a run's clamps: a field of another shape (cloth.lattice is a disc's, cloth.imperfection a rectangle's), or a
 * resolution below the shape's fewest faces (a disc of rings has 2 across, a woven one 4; a tube 3 around, 1 along).
 */
export function shapeNotes(c: ClothSpec, at = ''): string[] {
  const notes: string[] = [];
  if (c.lattice === 'weave' && c.shape !== 'disc') notes.push(`${at}cloth.lattice 'weave': a disc's lattice, and this cloth is a '${c.shape}': not used`);
  if (c.imperfection > 0 && c.shape !== 'rectangle') notes.push(`${at}cloth.imperfection ${c.imperfection}: a rectangle's bulge, and this cloth is a '${c.shape}': not used`);
  if (c.shape === 'disc') {
    const fewest = c.lattice === 'weave' ? wovenDiscCells(1) : 2;
    if (c.resolution < fewest) notes.push(`${at}cloth.resolution ${c.resolution}: a ${c.lattice === 'weave' ? 'woven disc' : 'disc of rings'} has at least ${fewest} faces across, so it has ${fewest}`);
  }
  if (c.shape === 'tube') {
    const { around, along, raised } = tubeFaces(c);
    if (raised) notes.push(`${at}cloth.resolution ${c.resolution}: a tube has at least 3 faces around and 1 along, so it has ${around} around and ${along} along`);
  }
  return notes;
}

/** The model of one cloth (`at` prefixes its fields in errors: '' or 'cloths[1].'). */
function clothModel(c: ClothSpec, swr: boolean, meshes: MeshResolver | undefined, at: string): ClothModel {
  switch (c.shape) {
    case 'rectangle':
      return buildGridModel({ ...c, scaleWithResolution: swr });
    case 'disc':
      return c.lattice === 'weave'
        ? buildMeshModel(prepareMesh(wovenDiscMesh(c), `${at}cloth.shape disc`), swr, { cellSize: c.width / wovenDiscCells(c.resolution) })
        : buildMeshModel(prepareMesh(discMesh(c), `${at}cloth.shape disc`), swr);
    case 'tube':
      return buildMeshModel(prepareMesh(tubeMesh(c), `${at}cloth.shape tube`), swr);
    case 'mesh': {
      const path = c.mesh!;
      if (!meshes) {
        throw new SceneError(`${at}cloth.mesh: '${plainText(path, 200)}' is a file, and nothing here reads files; load the scene with its files (drape run, loadSceneFile from drape/node, or the app's mesh import)`);
      }
      // a file that cannot be read, is no mesh or no cloth: named by its field, as a mesh collider's is (colliders/mesh.ts)
      let mesh: ReturnType<typeof prepareMesh>;
      try {
        mesh = prepareMesh(meshes(path), plainText(path, 200));
      } catch (e) {
        throw new SceneError(`${at}cloth.mesh: ${plainText(e instanceof Error ? e.message : String(e), 500)}`);
      }
      const scaled = new Float32Array(mesh.positions.length);
      for (let j = 0; j < scaled.length; j++) scaled[j] = mesh.positions[j] * c.scale;
      // its size at this scale, measured before anything is built on it (a model's size is floored at 1 mm)
      const { size } = extent(scaled);
      const unit = `${at}cloth.scale is metres per unit of the file (0.01 for centimetres)`;
      // as large as a generated cloth may be (cloth.width's most, 100 m), or a unit mistake too
      if (!(size <= 100)) {
        throw new SceneError(`${at}cloth.scale: ${plainText(path, 200)} is ${Number.isFinite(size) ? `${size.toPrecision(3)} m` : 'beyond float32\'s range'} across at scale ${c.scale}, more than 100 m (the most cloth.width allows); ${unit}`);
      }
      // a cloth smaller than its own contact thickness is a unit mistake, not a garment
      if (size < 2 * c.thickness) {
        throw new SceneError(`${at}cloth.scale: ${plainText(path, 200)} is ${size.toPrecision(3)} m across at scale ${c.scale}, less than twice ${at}cloth.thickness (${c.thickness} m); ${unit}`);
      }
      return buildMeshModel({ ...mesh, positions: placeMesh(scaled, c) }, swr);
    }
  }
}
