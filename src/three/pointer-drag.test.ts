import { PerspectiveCamera, Vector3, type Raycaster } from 'three';
import { describe, expect, it } from 'vitest';
import { PointerDrag, type DragHit } from './pointer-drag.js';

/**
 * An element of 400 × 400 CSS px at the page's origin, and what the page's own listeners (orbit controls) saw:
 * `listen()` adds them, after the drag's (Node's EventTarget has no capture phase: registration order stands for
 * it, as capturing listeners run first on a browser's element)
 */
function element() {
  const target = new EventTarget() as EventTarget & Record<string, unknown>;
  const captured = new Set<number>();
  Object.assign(target, {
    getBoundingClientRect: () => ({ left: 0, top: 0, width: 400, height: 400 }),
    setPointerCapture: (id: number) => { captured.add(id); },
    releasePointerCapture: (id: number) => { captured.delete(id); },
  });
  const passedOn: string[] = [];
  const listen = () => { for (const type of ['pointerdown', 'pointermove', 'pointerup']) target.addEventListener(type, () => passedOn.push(type)); };
  return { el: target as unknown as HTMLElement, passedOn, captured, listen };
}

function pointer(el: HTMLElement, type: string, clientX: number, clientY: number, pointerId = 1, button = 0): Event {
  const e = Object.assign(new Event(type, { cancelable: true }), { clientX, clientY, pointerId, button });
  el.dispatchEvent(e);
  return e;
}

/** a camera at z = 2 looking down −z: the element's centre is the ray through the origin */
function camera(): PerspectiveCamera {
  const c = new PerspectiveCamera(60, 1, 0.1, 10);
  c.position.set(0, 0, 2);
  c.updateMatrixWorld();
  return c;
}

interface Hit extends DragHit { readonly id: number }

/** a particle at (0.05, 0, 0) that every ray near the centre hits at the origin; the calls made on it */
function target() {
  const calls: string[] = [];
  const at: Vector3[] = [];
  return {
    calls, at,
    pick: (r: Raycaster): Hit | null => (Math.abs(r.ray.direction.x) < 0.2 && Math.abs(r.ray.direction.y) < 0.2
      ? { id: 7, point: new Vector3(0, 0, 0), position: new Vector3(0.05, 0, 0) } : null),
    grab: (h: Hit, p: Vector3) => { calls.push(`grab ${h.id}`); at.push(p.clone()); },
    drag: (h: Hit, p: Vector3) => { calls.push(`drag ${h.id}`); at.push(p.clone()); },
    release: (h: Hit) => { calls.push(`release ${h.id}`); },
  };
}

describe('PointerDrag: the pointer handling of the addon\'s PointerGrab and of the app', () => {
  it('grabs the particle where it is, drags it with the offset of the press kept, and releases it on pointerup', () => {
    const { el, passedOn, captured, listen } = element(), t = target(), grabs: boolean[] = [];
    const drag = new PointerDrag(el, camera, t, { onGrab: (g) => grabs.push(g) });
    listen();
    const down = pointer(el, 'pointerdown', 200, 200);
    expect(down.defaultPrevented).toBe(true);
    expect(drag.grabbing).toBe(true);
    expect(captured.has(1)).toBe(true);
    // the particle, not the point pressed: no jump
    expect(t.at[0].toArray()).toEqual([0.05, 0, 0]);
    // 40 px up at 2 m under a 60° view: the pointer's plane point rises by tan(30°)·2·40/200 m
    pointer(el, 'pointermove', 200, 160);
    const rise = Math.tan(Math.PI / 6) * 2 * (40 / 200);
    expect(t.at[1].x).toBeCloseTo(0.05, 9);
    expect(t.at[1].y).toBeCloseTo(rise, 6);
    expect(t.at[1].z).toBeCloseTo(0, 9);
    pointer(el, 'pointerup', 200, 160);
    expect(t.calls).toEqual(['grab 7', 'drag 7', 'release 7']);
    expect(grabs).toEqual([true, false]);
    expect(captured.has(1)).toBe(false);
    // none of the grab's events reached the page's other listeners
    expect(passedOn).toEqual([]);
  });

  it('a press that misses is left to the page; a second finger while grabbing is not; a lost capture lets go', () => {
    const { el, passedOn, listen } = element(), t = target();
    const drag = new PointerDrag(el, camera, t);
    listen();
    pointer(el, 'pointerdown', 20, 20);
    expect(drag.grabbing).toBe(false);
    expect(passedOn).toEqual(['pointerdown']);
    pointer(el, 'pointerup', 20, 20);
    passedOn.length = 0;
    pointer(el, 'pointerdown', 200, 200, 1);
    const second = pointer(el, 'pointerdown', 30, 30, 2);
    expect(second.defaultPrevented).toBe(true);
    pointer(el, 'pointermove', 40, 40, 2);
    pointer(el, 'pointerup', 40, 40, 2);
    expect(drag.grabbing).toBe(true);
    expect(t.calls).toEqual(['grab 7']);
    el.dispatchEvent(Object.assign(new Event('lostpointercapture'), { pointerId: 1 }));
    expect(drag.grabbing).toBe(false);
    expect(t.calls).toEqual(['grab 7', 'release 7']);
    expect(passedOn).toEqual([]);
  });

  it('a press hook takes a press first (the pin tool), and cancel and dispose let go of a grab', () => {
    const { el } = element(), t = target();
    let take = true;
    const drag = new PointerDrag(el, camera, t, { press: () => take });
    expect(pointer(el, 'pointerdown', 200, 200).defaultPrevented).toBe(true);
    expect(drag.grabbing).toBe(false);
    take = false;
    pointer(el, 'pointerdown', 200, 200);
    expect(drag.grabbing).toBe(true);
    drag.cancel();
    expect(t.calls).toEqual(['grab 7', 'release 7']);
    pointer(el, 'pointerdown', 200, 200, 3);
    drag.dispose();
    expect(t.calls).toEqual(['grab 7', 'release 7', 'grab 7', 'release 7']);
    // no longer listening
    pointer(el, 'pointerdown', 200, 200, 4);
    expect(drag.grabbing).toBe(false);
    // a second finger that lands on the cloth while the first is down elsewhere grabs nothing: it is the page's
    const { el: el2, passedOn, listen } = element();
    const drag2 = new PointerDrag(el2, camera, t);
    listen();
    el2.dispatchEvent(Object.assign(new Event('pointerdown', { cancelable: true }), { clientX: 200, clientY: 200, pointerId: 9, button: 0, isPrimary: false }));
    expect(drag2.grabbing).toBe(false);
    expect(passedOn).toEqual(['pointerdown']);
    // a secondary button grabs nothing
    const again = new PointerDrag(el, camera, t);
    pointer(el, 'pointerdown', 200, 200, 5, 2);
    expect(again.grabbing).toBe(false);
  });
});
