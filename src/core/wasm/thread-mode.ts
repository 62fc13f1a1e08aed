/**
 * Whether a kernel's helper threads take part in a frame, decided from measured frame times. On an idle machine
 * they make a frame faster; on a busy one a helper is often descheduled, and thread 0, which then does the
 * helper's share itself and may wait for a chunk the helper holds, can end up slower than alone. So the kernel
 * times its frames in the mode it is in, now and then runs one frame in the other mode (a probe), and keeps the
 * faster. Both modes compute the same cloth bit for bit: only the speed depends on the choice.
 */

/** Frames before the first probe (the code tiers up, the cloth starts moving) [-]. */
export const PROBE_AFTER = 8;
/** Frames between probes of the other mode [-]. */
export const PROBE_EVERY = 30;
/** The other mode must be this much faster per substep to be chosen [-]. */
export const SWITCH_MARGIN = 0.1;
/** Weight of a new frame in the running estimate of the current mode [-]. */
const SMOOTHING = 0.25;

export class ThreadModeChooser {
  /** whether the coming frame runs with the helpers */
  parallel = true;
  /** frames run alone since the start (for reports) */
  framesAlone = 0;
  /** frames run in all */
  frames = 0;
  /** ms per substep: [alone, parallel]; NaN until measured */
  private readonly estimate = [NaN, NaN];
  private sinceProbe = 0;
  private probing = false;

  /** Whether the next frame runs with the helpers (call once per frame, then record()). */
  next(): boolean {
    const current = this.estimate[this.parallel ? 1 : 0], other = this.estimate[this.parallel ? 0 : 1];
    // warm-up frames are not measured; then the current mode is, and the other is probed once it has a number
    this.probing = this.frames >= PROBE_AFTER && !Number.isNaN(current) && (Number.isNaN(other) || this.sinceProbe >= PROBE_EVERY);
    return this.probing ? !this.parallel : this.parallel;
  }

  /** The time of the frame next() was asked for, per substep [ms]. */
  record(msPerSubstep: number): void {
    const ran = this.probing ? !this.parallel : this.parallel;
    const measured = this.frames >= PROBE_AFTER && msPerSubstep >= 0 && Number.isFinite(msPerSubstep);
    this.frames++;
    if (!ran) this.framesAlone++;
    if (!measured) return;
    if (this.probing) {
      this.estimate[ran ? 1 : 0] = msPerSubstep;
      this.sinceProbe = 0;
      if (msPerSubstep < this.estimate[this.parallel ? 1 : 0] * (1 - SWITCH_MARGIN)) this.parallel = ran;
      return;
    }
    const k = this.parallel ? 1 : 0;
    this.estimate[k] = Number.isNaN(this.estimate[k]) ? msPerSubstep : this.estimate[k] + SMOOTHING * (msPerSubstep - this.estimate[k]);
    this.sinceProbe++;
  }
}
