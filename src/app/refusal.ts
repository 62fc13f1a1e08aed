/** How the app words a scene the core refuses. */
import { SceneError } from '../core/index.js';

/** The core's one-line refusal of a scene (SceneError); anything else is a bug, thrown on. */
export function refusal(e: unknown): string {
  if (e instanceof SceneError) return e.message.replace(/^--set /, '');
  throw e;
}
