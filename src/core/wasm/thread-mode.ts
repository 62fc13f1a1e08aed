/**
 * Whether a kernel's helper threads take part in a frame, decided from measured frame times. On an idle machine
 * they make a frame faster; on a busy one a helper is often descheduled, and thread 0, which then does the
 * helper's share itself and may wait for a chunk the helper holds, can end up slower than alone. So the kernel
 * times its frames in the mode it is in, now and then runs a few frames in the other mode (a probe), and keeps the
 * faster. Medians, not means: a machine's hiccups make single frames slow, not fast. Both modes compute the same
 * cloth bit for bit: only the speed depends on the choice.
 */

/** Frames before anything is measured (the code tiers up, the cloth starts moving) [-]. */
export const PROBE_AFTER = 8;
/** Frames in the current mode between probes [-]. */
export const PROBE_EVERY = 90;
/** Frames a probe runs in the other mode [-]. */
export const PROBE_FRAMES = 5;
/**
 * How much lower the other mode's median must be to be chosen [-]: the helpers must clearly pay to be taken on
 * (a busy machine makes timings noisy, and alone is the safe side), and are dropped as soon as they do not.
 */
export const MARGIN_TO_PARALLEL = 0.15;
export const MARGIN_TO_ALONE = 0.05;
/** Recent frames of the current mode whose median it is judged by [-]. */
const WINDOW = 9;

function median(values: Float64Array, count: number, scratch: Float64Array): number {
  for (let i = 0; i < count; i++) scratch[i] = values[i];
  const s = scratch.subarray(0, count).sort();
  return count % 2 ? s[(count - 1) / 2] : 0.5 * (s[count / 2 - 1] + s[count / 2]);
}

export class ThreadModeChooser {
  /** whether the current mode runs with the helpers */
  parallel = true;
  /** frames run alone since the start (for reports) */
  framesAlone = 0;
  /** frames run in all */
  frames = 0;
  /** the current mode's last WINDOW frames [ms per substep], a ring */
  private readonly recent = new Float64Array(WINDOW);
  private recentCount = 0;
  private recentAt = 0;
  private readonly probe = new Float64Array(PROBE_FRAMES);
  private probeCount = 0;
  private readonly scratch = new Float64Array(WINDOW);
  /** frames of the current mode since the last probe (the first is due as soon as the window is full) */
  private sinceProbe = PROBE_EVERY;
  private probing = false;

  /** mode held by hold(), or undefined while measurements decide */
  private held: boolean | undefined;

  /** Runs every frame with the helpers (true) or alone (false), measuring nothing; undefined lets the times decide. */
  hold(parallel: boolean | undefined): void {
    this.held = parallel;
    this.probing = false;
  }

  /** Whether the next frame runs with the helpers (call once per frame, then record()). */
  next(): boolean {
    if (this.held !== undefined) return this.held;
    // warm-up frames are not measured; a probe starts once the current mode has a full window and is due
    if (!this.probing && this.recentCount === WINDOW && this.sinceProbe >= PROBE_EVERY) {
      this.probing = true;
      this.probeCount = 0;
    }
    return this.probing ? !this.parallel : this.parallel;
  }

  /** The time of the frame next() was asked for, per substep [ms]. */
  record(msPerSubstep: number): void {
    if (this.held !== undefined) {
      this.frames++;
      if (!this.held) this.framesAlone++;
      return;
    }
    const ran = this.probing ? !this.parallel : this.parallel;
    const measured = this.frames >= PROBE_AFTER && msPerSubstep >= 0 && Number.isFinite(msPerSubstep);
    this.frames++;
    if (!ran) this.framesAlone++;
    if (!measured) return;
    if (this.probing) {
      this.probe[this.probeCount++] = msPerSubstep;
      if (this.probeCount < PROBE_FRAMES) return;
      this.probing = false;
      this.sinceProbe = 0;
      const other = median(this.probe, PROBE_FRAMES, this.scratch);
      if (other < median(this.recent, WINDOW, this.scratch) * (1 - (ran ? MARGIN_TO_PARALLEL : MARGIN_TO_ALONE))) {
        // switch; the probe's frames start the new mode's window
        this.parallel = ran;
        this.recentCount = 0;
        this.recentAt = 0;
        for (let i = 0; i < PROBE_FRAMES; i++) this.push(this.probe[i]);
      }
      return;
    }
    this.push(msPerSubstep);
    this.sinceProbe++;
  }

  private push(ms: number): void {
    this.recent[this.recentAt] = ms;
    this.recentAt = (this.recentAt + 1) % WINDOW;
    this.recentCount = Math.min(this.recentCount + 1, WINDOW);
  }
}
