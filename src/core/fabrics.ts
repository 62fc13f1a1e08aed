/**
 * The named fabrics (`material.fabric`): each fills every material field a scene does not set itself. Values in SI
 * units; where each comes from (a measurement, a class-typical literature value or an estimate) is in
 * docs/materials.md, section by section.
 */

import { REFERENCE_SPACING } from './model.js';

/**
 * The skip-one bend spring's stiffness at the reference spacing per unit bending rigidity [m⁻²]: k_b = 9·B /
 * (l_ref⁴·κ_c²) with l_ref = 1/32 m and κ_c = 10 m⁻¹ (docs/materials.md, "Bend spring"). material.bendStiffness
 * (the older path) is k_b: B = k_b / this; the bend springs get k_b = this × B.
 */
export const BEND_SPRING_PER_RIGIDITY = 9 / (REFERENCE_SPACING ** 4 * 100);

/** What a fabric sets: the measured quantities and the tuning values of a material. */
export interface FabricValues {
  /** mass per unit area [kg/m²] */
  arealDensity: number;
  /** tensile stiffness: force per unit width per unit strain, at low load [N/m] */
  structuralStiffness: number;
  /** in-plane shear stiffness: force per unit length per radian of shear [N/m] */
  shearStiffness: number;
  /** bending rigidity per unit width, B [N·m] (KES-FB2 B) */
  bendingRigidity: number;
  /** damping along every spring / distance constraint (a tuning value) [N·s/m] */
  damping: number;
  /** longest a structural or shear spring may get, × its rest length [-] */
  stretchFactor: number;
  /** kinetic Coulomb friction against solids [-] */
  friction: number;
  /** static Coulomb friction against solids [-] */
  staticFriction: number;
}

/** The fabrics by name, in the order the schema lists them. */
export const FABRICS = {
  /** plain-weave cotton shirting (docs/materials.md §3.1) */
  cotton: { arealDensity: 0.12, structuralStiffness: 8600, shearStiffness: 56, bendingRigidity: 7.85e-6, damping: 0.1, stretchFactor: 1.05, friction: 0.3, staticFriction: 0.4 },
  /** silk crêpe de chine, 14 momme (§3.2) */
  silk: { arealDensity: 0.061, structuralStiffness: 3700, shearStiffness: 17, bendingRigidity: 1.96e-6, damping: 0.05, stretchFactor: 1.1, friction: 0.2, staticFriction: 0.25 },
  /** garment leather, about 1 mm (§3.3) */
  leather: { arealDensity: 0.65, structuralStiffness: 5000, shearStiffness: 1700, bendingRigidity: 1.0e-3, damping: 0.5, stretchFactor: 1.15, friction: 0.4, staticFriction: 0.5 },
  /** natural latex sheet, 0.4 mm (§3.4) */
  rubber: { arealDensity: 0.38, structuralStiffness: 600, shearStiffness: 200, bendingRigidity: 8.0e-6, damping: 0.2, stretchFactor: 1.8, friction: 0.8, staticFriction: 1.0 },
  /** cotton denim, a heavy twill: Kawabata values measured on six denims (§3.5) */
  denim: { arealDensity: 0.4, structuralStiffness: 6800, shearStiffness: 138, bendingRigidity: 1.81e-5, damping: 0.3, stretchFactor: 1.06, friction: 0.35, staticFriction: 0.45 },
  /** a wool-blend twill (75 % wool, 15 % polyester, 10 % elastane), 179 g/m², whose drape coefficient was measured too (§3.7) */
  wool: { arealDensity: 0.1787, structuralStiffness: 445, shearStiffness: 50, bendingRigidity: 2.07e-6, damping: 0.15, stretchFactor: 1.1, friction: 0.35, staticFriction: 0.45 },
} as const satisfies Record<string, FabricValues>;

export type FabricName = keyof typeof FABRICS;
export const FABRIC_NAMES = Object.keys(FABRICS) as FabricName[];

/** The material fields a fabric fills, and the old path each may be given by instead (an alias). */
export const FABRIC_FIELDS = Object.keys(FABRICS.cotton) as (keyof FabricValues)[];
