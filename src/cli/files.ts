/**
 * The files the CLI reads and writes, checked before any work: inputs (scene files, and the meshes a scene names
 * later) must be regular files of at most MAX_INPUT_BYTES — a device, FIFO or socket (/dev/zero, a named pipe, a
 * symlink to either) is refused at once, never read; an export's destination is checked before simulating, so a
 * bad path costs nothing.
 */
import { accessSync, closeSync, constants, fstatSync, openSync, readSync, statSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { MAX_INPUT_BYTES } from '../core/index.js';
import { UsageError } from './errors.js';

const mib = (bytes: number) => `${(bytes / 2 ** 20).toFixed(bytes < 2 ** 20 ? 2 : 0)} MiB`;

function cannot(path: string, e: unknown, doing: string): UsageError {
  const code = (e as NodeJS.ErrnoException).code;
  const why = code === 'ENOENT' ? 'no such file' : code === 'EACCES' || code === 'EPERM' ? 'permission denied'
    : code === 'ENOTDIR' ? 'a folder on the path is a file' : code === 'ELOOP' ? 'too many symbolic links'
      : code === 'ENXIO' ? 'not a regular file (a socket or device)' : `${doing} failed (${code ?? (e as Error).message})`;
  return new UsageError(`${path}: ${why}`);
}

/** The text of an input file (UTF-8), or a UsageError naming it: not a regular file, larger than the cap, unreadable. */
export function readInputFile(path: string, what = 'scene file'): string {
  return Buffer.from(readInputBytes(path, what)).toString('utf8');
}

/** The bytes of an input file, or a UsageError naming it: not a regular file, larger than the cap, unreadable. */
export function readInputBytes(path: string, what = 'scene file'): Uint8Array {
  let fd: number;
  try {
    // non-blocking, so that opening a FIFO with no writer returns at once (it is then refused as not a file)
    fd = openSync(path, constants.O_RDONLY | (constants.O_NONBLOCK ?? 0) | (constants.O_NOCTTY ?? 0));
  } catch (e) {
    throw cannot(path, e, 'opening');
  }
  try {
    const st = fstatSync(fd);
    if (st.isDirectory()) throw new UsageError(`${path}: is a folder, not a ${what}`);
    if (!st.isFile()) throw new UsageError(`${path}: not a regular file (a device, pipe or socket); a ${what} must be a file`);
    if (st.size > MAX_INPUT_BYTES) throw new UsageError(`${path}: ${mib(st.size)}, more than the ${mib(MAX_INPUT_BYTES)} a ${what} may have`);
    // one byte more than the file's size: a file that grows while it is read fills it, and is refused
    const buf = Buffer.alloc(st.size + 1);
    let n = 0;
    for (let got = 1; got > 0 && n < buf.length; n += got) got = readSync(fd, buf, n, buf.length - n, null);
    if (n > st.size) throw new UsageError(`${path}: the file changed while it was read`);
    return buf.subarray(0, n);
  } catch (e) {
    if (e instanceof UsageError) throw e;
    throw cannot(path, e, 'reading');
  } finally {
    closeSync(fd);
  }
}

/**
 * Checks that `path` can be written as a new or replaced regular file: its folder exists and is writable, and the
 * path is not a folder, device or other special file. Throws UsageError naming the problem.
 */
export function checkOutputPath(path: string, flag: string): void {
  let st;
  try {
    st = statSync(path);
  } catch (e) {
    const code = (e as NodeJS.ErrnoException).code;
    if (code === 'ENOTDIR') throw new UsageError(`${flag} ${path}: a folder on the path is a file`);
    if (code !== 'ENOENT') throw new UsageError(`${flag} ${path}: cannot check it (${code ?? (e as Error).message})`);
  }
  if (st) {
    if (st.isDirectory()) throw new UsageError(`${flag} ${path}: is a folder; give a file name`);
    if (!st.isFile()) throw new UsageError(`${flag} ${path}: not a regular file`);
    try {
      accessSync(path, constants.W_OK);
    } catch {
      throw new UsageError(`${flag} ${path}: the file is not writable`);
    }
    return;
  }
  const folder = dirname(resolve(path));
  let dir;
  try {
    dir = statSync(folder);
  } catch {
    throw new UsageError(`${flag} ${path}: the folder ${folder} does not exist`);
  }
  if (!dir.isDirectory()) throw new UsageError(`${flag} ${path}: ${folder} is not a folder`);
  try {
    accessSync(folder, constants.W_OK);
  } catch {
    throw new UsageError(`${flag} ${path}: the folder ${folder} is not writable`);
  }
}
