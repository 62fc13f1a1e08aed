/**
 * A busy machine on demand, for `drape bench`: child processes that each keep one core busy, every one bounded in
 * time (it stops by itself after `maxMs` even if nobody stops it) and stopped when the work is done.
 */
import { spawn } from 'node:child_process';

/** Runs `work` (given the spinners' process ids) while `count` other processes spin, each for at most `maxMs` [ms]. */
export async function whileBusy<T>(count: number, maxMs: number, work: (pids: number[]) => Promise<T>): Promise<T> {
  const bound = Math.max(1, Math.floor(maxMs));
  let failed: Error | undefined;
  const spinners = Array.from({ length: count }, () => {
    const child = spawn(process.execPath, ['-e', `const end = Date.now() + ${bound}; while (Date.now() < end) {}`], { stdio: 'ignore' });
    child.on('error', (e) => { failed ??= e; });
    return child;
  });
  try {
    // until each has started spinning (Node starts in ~50 ms)
    await new Promise((r) => setTimeout(r, 300));
    if (failed) throw new Error(`could not start the processes that keep the machine busy (${failed.message})`);
    return await work(spinners.map((s) => s.pid!));
  } finally {
    for (const s of spinners) s.kill();
  }
}
