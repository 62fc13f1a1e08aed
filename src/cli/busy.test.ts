import { describe, expect, it } from 'vitest';
import { whileBusy } from './busy.js';

const alive = (pid: number) => {
  try {
    process.kill(pid, 0);
    return true;
  } catch {
    return false;
  }
};

describe('whileBusy', () => {
  it('keeps one spinning process per core during the work, and none after it', async () => {
    let seen: number[] = [];
    const value = await whileBusy(2, 60_000, async (pids) => {
      seen = pids;
      expect(pids).toHaveLength(2);
      for (const pid of pids) expect(alive(pid), `spinner ${pid} runs`).toBe(true);
      return 42;
    });
    expect(value).toBe(42);
    // killed when the work ends (the kill is delivered at once; the process is gone once it is reaped)
    await expect.poll(() => seen.filter(alive), { timeout: 10_000 }).toEqual([]);
  });

  it('stops the spinners when the work fails, too', async () => {
    let seen: number[] = [];
    await expect(whileBusy(1, 60_000, async (pids) => { seen = pids; throw new Error('boom'); })).rejects.toThrow('boom');
    await expect.poll(() => seen.filter(alive), { timeout: 10_000 }).toEqual([]);
  });
});
