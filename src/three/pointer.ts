/**
 * Grabbing a world's cloths with the pointer (mouse, pen, touch): a press on a cloth grabs the particle under it,
 * dragging pulls it across the plane through the grab point facing the camera, and letting go releases it (it
 * keeps its velocity). A press that misses the cloths is left to the page's other listeners (orbit controls); one
 * that hits is not passed on (its listener runs in the capture phase, before them).
 */
import { Plane, Raycaster, Vector2, Vector3, type Camera } from 'three';
import type { DrapeWorld } from './world.js';

export interface PointerGrabOptions {
  /** called when a grab starts (true) and ends (false): e.g. to turn orbit controls off meanwhile. Default: none */
  onGrab?: (grabbing: boolean) => void;
}

export class PointerGrab {
  private readonly raycaster = new Raycaster();
  private readonly ndc = new Vector2();
  private readonly plane = new Plane();
  private readonly target = new Vector3();
  private readonly normal = new Vector3();
  private pointer = -1;

  /** Listens on `element` (the renderer's canvas) for the pointer, picking through `camera`; `dispose()` stops. */
  constructor(private readonly world: DrapeWorld, private readonly camera: Camera, private readonly element: HTMLElement, private readonly options: PointerGrabOptions = {}) {
    if (!element || typeof element.addEventListener !== 'function') throw new TypeError('PointerGrab: element must be an HTMLElement (the renderer\'s canvas)');
    element.addEventListener('pointerdown', this.down, { capture: true });
    element.addEventListener('pointermove', this.move);
    element.addEventListener('pointerup', this.up);
    element.addEventListener('pointercancel', this.up);
  }

  private rayFrom(e: PointerEvent): void {
    const r = this.element.getBoundingClientRect();
    this.ndc.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(this.ndc, this.camera);
  }

  private readonly down = (e: PointerEvent): void => {
    if (this.pointer >= 0 || e.button !== 0) return;
    this.rayFrom(e);
    const hit = this.world.pick(this.raycaster);
    if (!hit) return;
    e.stopImmediatePropagation();
    e.preventDefault();
    this.pointer = e.pointerId;
    this.element.setPointerCapture?.(e.pointerId);
    this.camera.getWorldDirection(this.normal);
    this.plane.setFromNormalAndCoplanarPoint(this.normal, hit.point);
    this.world.grab(hit);
    this.options.onGrab?.(true);
  };

  private readonly move = (e: PointerEvent): void => {
    if (e.pointerId !== this.pointer) return;
    this.rayFrom(e);
    if (this.raycaster.ray.intersectPlane(this.plane, this.target)) this.world.drag(this.target);
  };

  private readonly up = (e: PointerEvent): void => {
    if (e.pointerId !== this.pointer) return;
    this.pointer = -1;
    this.world.release();
    this.options.onGrab?.(false);
  };

  /** Stops listening (and lets go of a grab in progress). */
  dispose(): void {
    this.element.removeEventListener('pointerdown', this.down, { capture: true });
    this.element.removeEventListener('pointermove', this.move);
    this.element.removeEventListener('pointerup', this.up);
    this.element.removeEventListener('pointercancel', this.up);
    if (this.pointer >= 0) { this.pointer = -1; this.world.release(); }
  }
}
