/**
 * The hidden file input behind an import button: opens the browser's file picker, refuses a file over the size cap
 * with a message (its name shown as plain text), and hands any other file on. One per kind of file.
 */
import { plainText } from '../core/index.js';
import type { Overlay } from '../ui/overlay.js';
import { importSizeProblem } from './limits.js';

export interface FilePickerSpec {
  /** the input's accept list, e.g. '.obj,.gltf,.glb' */
  accept: string;
  /** data-testid of the input (the browser tests set files on it) */
  testid: string;
  /** what the file is, in messages ('scene file', 'mesh file') */
  what: string;
  /** how a refusal starts, e.g. 'Import refused' */
  refused: string;
  /** gets a file within the size cap, and its bytes */
  onFile: (file: File, bytes: ArrayBuffer) => void | Promise<void>;
}

/** A hidden file input in `root` with the size check; `open()` shows the picker. */
export class FilePicker {
  private readonly input: HTMLInputElement;

  constructor(private readonly overlay: Overlay, root: HTMLElement, private readonly spec: FilePickerSpec) {
    this.input = document.createElement('input');
    this.input.type = 'file';
    this.input.accept = spec.accept;
    this.input.hidden = true;
    this.input.dataset.testid = spec.testid;
    this.input.addEventListener('change', () => void this.read());
    root.append(this.input);
  }

  /** Opens the file picker. */
  open(): void {
    this.input.value = '';
    this.input.click();
  }

  private async read(): Promise<void> {
    const file = this.input.files?.[0];
    if (!file) return;
    const tooBig = importSizeProblem(file.size, this.spec.what);
    // the file's name is shown in messages: as text, with no control or direction-changing characters
    if (tooBig) { this.overlay.message(`${this.spec.refused} — ${plainText(file.name, 80)}: ${tooBig}`); return; }
    let bytes: ArrayBuffer;
    try {
      // read here, so that a file that cannot be read (moved or deleted since it was picked, a cloud file not
      // downloaded) is a message, not an unhandled rejection
      bytes = await file.arrayBuffer();
    } catch (e) {
      this.overlay.message(`${this.spec.refused} — ${plainText(file.name, 80)}: the file could not be read (${plainText(e instanceof Error ? e.message : String(e), 120)})`);
      return;
    }
    await this.spec.onFile(file, bytes);
  }
}
