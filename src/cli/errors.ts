/** An error the user caused (bad flag, unknown scene, unavailable backend): printed as one line, exit code 2. */
export class UsageError extends Error {}

/** The CLI's exit codes (documented in the README). */
export const EXIT = {
  /** done */
  ok: 0,
  /** a bug: an error nobody anticipated (one line, no stack trace) */
  internal: 1,
  /** bad input (flags, scene, files): nothing was run */
  usage: 2,
  /** the simulation became unstable (positions not finite): nothing exported */
  unstable: 3,
  /** the run finished and its results are printed, but the export could not be written (also: stdout could not be, bin/drape.js) */
  exportFailed: 4,
} as const;
