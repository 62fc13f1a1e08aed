/**
 * `drape/node`: scene and mesh files in Node, under the CLI's file rules (regular files of at most
 * MAX_INPUT_BYTES, errors naming the file). A scene's cloth.mesh is read relative to the scene file's folder, a
 * .gltf's separate buffers relative to the .gltf.
 */
import { dirname, isAbsolute, relative, resolve } from 'node:path';
import { meshFormat, parseMeshFile, parseScene, shownValue, type MeshResolver, type Scene, type TriangleMesh } from '../core/index.js';
import { readInputBytes, readInputFile } from './files.js';
import { UsageError } from './errors.js';

/**
 * A MeshResolver for Simulation's `meshes` option: reads (once; later calls reuse the parsed mesh) the mesh file
 * a path names, relative to `baseDir` (default: the working folder).
 */
export function meshReader(baseDir = process.cwd()): MeshResolver {
  if (typeof baseDir !== 'string') throw new TypeError(`meshReader: the folder mesh files are read from must be a path (a string), got ${shownValue(baseDir)}`);
  const cache = new Map<string, TriangleMesh>();
  return (path: string) => {
    if (typeof path !== 'string') throw new TypeError(`meshReader: a mesh file's path must be a string, got ${shownValue(path)}`);
    const file = resolve(baseDir, path);
    let mesh = cache.get(file);
    if (!mesh) {
      meshFormat(path); // a file of another kind is refused by its name, before it is opened
      const folder = dirname(file);
      mesh = parseMeshFile(readInputBytes(file, 'mesh file'), path, (uri) => {
        const target = resolve(folder, uri), inside = relative(folder, target);
        if (isAbsolute(uri) || /^[a-z][a-z0-9+.-]*:/i.test(uri) || inside.startsWith('..') || isAbsolute(inside)) {
          throw new UsageError(`${path}: buffer '${uri.slice(0, 100)}' must be a file in the .gltf's folder or below it (a relative path)`);
        }
        return readInputBytes(target, 'glTF buffer');
      });
      cache.set(file, mesh);
    }
    return mesh;
  };
}

/** Reads a scene file and returns the validated scene with a resolver for the mesh files it names. */
export function loadSceneFile(path: string): { scene: Scene; meshes: MeshResolver } {
  return { scene: parseScene(readInputFile(path), path), meshes: meshReader(dirname(resolve(path))) };
}
