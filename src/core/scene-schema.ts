/**
 * The one schema of a Drape scene (JSON Schema draft-07). Defaults, ranges and units live here and nowhere else:
 * the validator fills in defaults, the UI reads ranges from here for its sliders, and `scene.schema.json` at the
 * repository root is generated from this object (`npm run schema`; a test checks it is current).
 */

import { MAX_COLLIDERS } from './layout.generated.js';
import { FABRIC_NAMES } from './fabrics.js';

const vec3 = (description: string, min: number, max: number, dflt: readonly number[]) => ({
  description,
  type: 'array',
  items: { type: 'number', minimum: min, maximum: max },
  minItems: 3,
  maxItems: 3,
  default: dflt,
});

export const PIN_PRESETS = [
  'top-left', 'top-right', 'bottom-left', 'bottom-right', 'center',
  'top-edge', 'bottom-edge', 'left-edge', 'right-edge',
] as const;

/** Most keys of one collider's motion. */
export const MAX_KEYFRAMES = 10000;
/** Most cloths one scene may have (`cloths`). */
export const MAX_CLOTHS = 8;
/** the most substeps per frame a scene may ask for (solver.substeps) and self-contact may raise them to [-] */
export const MAX_SUBSTEPS = 200;

/** A pin list: presets, particle indices or regions (the scene's `pins`, a collider's `pins`). */
const pinList = (description: string) => ({
  type: 'array',
  default: [],
  maxItems: 1050625,
  description,
  items: {
    anyOf: [
      { enum: [...PIN_PRESETS] },
      { type: 'integer', minimum: 0 },
      {
        type: 'object',
        additionalProperties: false,
        required: ['min', 'max'],
        description: 'a region: every particle whose start position lies in the box from min to max (any shape, any resolution)',
        properties: {
          min: vec3('the box\'s lowest corner [m]', -1000, 1000, [0, 0, 0]),
          max: vec3('the box\'s highest corner [m]', -1000, 1000, [0, 0, 0]),
        },
      },
      {
        type: 'object',
        additionalProperties: false,
        required: ['center', 'radius'],
        description: 'a round region: every particle whose start position lies within radius of center (a clamp\'s disc, any shape, any resolution)',
        properties: {
          center: vec3('the ball\'s centre [m]', -1000, 1000, [0, 0, 0]),
          radius: { type: 'number', minimum: 0, maximum: 1000, description: 'the ball\'s radius [m]' },
        },
      },
    ],
  },
});

/** What every collider may have besides its shape: a motion and pins it carries. */
const colliderCommon = {
  motion: {
    type: 'object',
    additionalProperties: false,
    required: ['keyframes'],
    description: 'keyframed motion relative to the placement above: turned about pivot by rotation, then moved by translation; ' +
      'translation and Euler angles are interpolated linearly between keys (0° to 360° spins once at constant speed); the first and last key hold outside their times',
    properties: {
      keyframes: {
        type: 'array',
        minItems: 1,
        maxItems: MAX_KEYFRAMES,
        description: 'the keys, in order of time',
        items: {
          type: 'object',
          additionalProperties: false,
          required: ['time'],
          properties: {
            time: { type: 'number', minimum: 0, maximum: 1e6, description: 'time of the key [s]; not before the previous key\'s' },
            translation: vec3('translation from the placement [m]', -1000, 1000, [0, 0, 0]),
            rotation: vec3('rotation about the pivot, Euler XYZ as cloth.rotation [degrees]', -36000, 36000, [0, 0, 0]),
          },
        },
      },
      pivot: {
        description: 'the point the rotation turns about [m]; absent: the collider\'s centre (a sphere\'s, box\'s or cylinder\'s centre, the middle of a capsule\'s axis, a plane\'s point, (0, height, 0) for a floor)',
        type: 'array',
        items: { type: 'number', minimum: -1000, maximum: 1000 },
        minItems: 3,
        maxItems: 3,
      },
      loop: { type: 'boolean', default: false, description: 'repeat the keys, the last key\'s time being the period (it must be > 0)' },
    },
  },
  pins: pinList('particles pinned to this collider, carried with it as it moves (presets, indices or regions, as the scene\'s pins)'),
} as const;

/** `cloth`: the shape, size and start pose of a cloth (one of `cloths` has the same). */
const clothSchema = {
  type: 'object',
  additionalProperties: false,
  default: {},
  properties: {
    shape: { enum: ['rectangle', 'disc', 'tube', 'mesh'], default: 'rectangle', description: "'rectangle': the seed's grid; 'disc': a round sheet of concentric rings; 'tube': an open cylinder (a skirt, a sleeve); 'mesh': the triangle mesh in the file cloth.mesh (set when cloth.mesh is given)" },
    mesh: { type: 'string', minLength: 1, maxLength: 1000, description: 'OBJ or glTF (.obj, .gltf, .glb) file of the cloth, relative to the scene file; any manifold triangle mesh with boundary, several pieces allowed. The app imports it from a file; a link cannot carry it' },
    scale: { type: 'number', minimum: 1e-6, maximum: 1e6, default: 1, description: 'metres per unit of the mesh file: 0.01 for centimetres, 0.001 for millimetres, 0.0254 for inches (mesh only; the cloth must come out at least twice cloth.thickness and at most 100 m across) [m]' },
    resolution: { type: 'integer', minimum: 1, maximum: 1024, default: 32, description: 'density [-]: faces per side of a rectangle (1 is one quad of 4 particles, 64 is 4096 faces: 65² particles); faces across a disc\'s diameter; faces along the longer of a tube\'s circumference and length (a mesh file has its own)' },
    lattice: { enum: ['rings', 'weave'], default: 'rings', description: "how a disc is meshed: 'rings' (concentric rings of 6k vertices, a lattice of triangles alike in every direction; every edge is a structural spring, so the disc resists in-plane shear as stiffly as stretch) or 'weave' (the rectangle's square cells cut round, threads along x and z: structural springs along them, shear springs across the cells, so the disc shears as softly as its material.shearStiffness says, like a woven fabric; at least 4 cells across). Not for other shapes" },
    width: { type: 'number', minimum: 0.01, maximum: 100, default: 1, description: 'extent along x of a rectangle; diameter of a disc or tube [m]' },
    height: { type: 'number', minimum: 0.01, maximum: 100, default: 1, description: 'extent of a rectangle along its second axis (z when horizontal, y when hanging); length of a tube [m]' },
    orientation: { enum: ['horizontal', 'hanging'], default: 'horizontal', description: "start pose of a rectangle, disc or tube: 'horizontal' lies in the xz plane (row 0 at -z; a tube's axis along z); 'hanging' in the xy plane (row 0 at the top; a tube's axis vertical). A mesh keeps the file's pose" },
    position: vec3('centre of the cloth at the start (of its bounding box, for a mesh) [m]', -1000, 1000, [0, 1.2, 0]),
    rotation: vec3('extra rotation about the centre, Euler XYZ [degrees]', -360, 360, [0, 0, 0]),
    thickness: { type: 'number', minimum: 0, maximum: 0.1, default: 0.005, description: 'contact thickness: how far the cloth surface is kept from colliders [m]' },
    imperfection: { type: 'number', minimum: 0, maximum: 0.1, default: 0, description: "how far a rectangle's start (and rest) shape bulges out of its plane: sin(πu)·sin(πv) across it times this, zero on its edges (not for other shapes). A real cloth is never flat; an exactly flat one in a plane that holds gravity and every other force (a flag on a pole with no wind) can never buckle out of it, and stays up on its in-plane stiffness [m]" },
    perturbation: {
      type: 'object',
      additionalProperties: false,
      default: {},
      description: "a seeded smooth waviness of the start pose, not of the rest shape (any shape): a real specimen is never laid exactly flat, and the folds a flat disc forms otherwise follow its mesh. Seeds 1, 2, 3 are three specimens, as the Cusick test's (BS 5058) mean of three asks (perturbation.ts)",
      properties: {
        amplitude: { type: 'number', minimum: 0, maximum: 0.1, default: 0, description: 'root mean square of the waviness over the free particles, along each particle\'s normal (8 plane waves of wavelengths 1/4 to 1 of the cloth\'s size; pinned particles stay, and it grows from 0 at a pin over half the shortest wave); 0: none [m]' },
        seed: { type: 'integer', minimum: 0, maximum: 2147483647, default: 1, description: 'random seed: the same seed gives the same waviness [-]' },
      },
    },
  },
} as const;

/** `material`: a cloth's fabric (one of `cloths` has the same). */
const materialSchema = {
  type: 'object',
  additionalProperties: false,
  default: {},
  properties: {
    fabric: { enum: FABRIC_NAMES, description: 'a named fabric (docs/materials.md): it fills every material field this scene does not set itself (a schema default never counts as set); setting it with --set or in the app puts every field back to that fabric\'s' },
    arealDensity: { type: 'number', minimum: 0.005, maximum: 10, default: 0.12, description: 'mass per unit area of the fabric; the cloth\'s mass is this × its rest area (not with material.mass) [kg/m²]' },
    mass: { type: 'number', minimum: 1e-5, maximum: 100, description: 'mass of the whole cloth, instead of arealDensity (the older path; not with material.arealDensity; by default the cloth weighs arealDensity × its area) [kg]' },
    structuralStiffness: { type: 'number', minimum: 1, maximum: 1e6, default: 8600, description: 'tensile stiffness of the sheet (force per unit width per unit strain) = per-spring Hooke constant of structural springs on square cells [N/m]' },
    shearStiffness: { type: 'number', minimum: 0, maximum: 1e6, default: 56, description: 'in-plane shear stiffness: per-spring Hooke constant of the diagonal springs [N/m]' },
    bendingRigidity: { type: 'number', minimum: 0, maximum: 1, default: 7.85e-6, description: 'bending rigidity of the sheet per unit width, B (KES-FB2), which the hinges and the Laplacian bend with and the bend springs are derived from: k_b = 94 372 m⁻² × B at the reference spacing of 1/32 m (not with material.bendStiffness) [N·m]' },
    bendStiffness: { type: 'number', minimum: 0, maximum: 1e5, description: 'Hooke constant of the skip-one bend springs at the reference spacing of 1/32 m, instead of bendingRigidity (the older path: B = this / 94 372 m⁻²; not with material.bendingRigidity) [N/m]' },
    damping: { type: 'number', minimum: 0, maximum: 10, default: 0.1, description: 'damping along every spring on the relative velocity of its ends; with the bending stencils solved together (solver.bendingSolve \'global\'), each stencil is damped with the damping time of a bend spring, this / (94 372 m⁻² × material.bendingRigidity) [N·s/m]' },
    stretchFactor: { type: 'number', minimum: 1, maximum: 2, default: 1.05, description: 'longest a structural or shear spring may get, as a multiple of its rest length (mass-spring stretch limiting) [-]' },
    friction: { type: 'number', minimum: 0, maximum: 2, default: 0.3, description: 'kinetic Coulomb friction coefficient against colliders [-]' },
    staticFriction: { type: 'number', minimum: 0, maximum: 2, default: 0.4, description: 'static Coulomb friction coefficient against colliders (at least the kinetic one is used) [-]' },
    scaleWithResolution: { type: 'boolean', default: true, description: 'true: parameters mean the same fabric at every resolution; false: the seed\'s per-spring constants (finer meshes bend more easily)' },
  },
} as const;

/** `pins`: a cloth's pinned particles (one of `cloths` has the same). */
const clothPins = pinList(`pinned particles: presets (${PIN_PRESETS.join(', ')}; all but center need a rectangle) particle indices (a rectangle's row-major, row 0 first; a mesh file's vertex order after welding) or regions ({ min, max }: the particles that start in that box; { center, radius }: those that start within radius of center)`);

/**
 * A JSON Schema document, as the code reads it: the scene schema's own literal type would only repeat the
 * schema (100 kB of declarations) in the package's types.
 */
export type SceneSchema = { readonly [key: string]: unknown };

export const sceneSchema: SceneSchema = {
  $schema: 'http://json-schema.org/draft-07/schema#',
  $id: 'https://drape.dev/scene.schema.json',
  title: 'Drape scene',
  description: 'A cloth, its material, the solver, forces, colliders and pins. Every field is optional; missing ones take the defaults shown.',
  type: 'object',
  additionalProperties: false,
  properties: {
    $schema: { type: 'string', description: 'URL or path of this schema, for editors' },
    name: { type: 'string', maxLength: 100, description: 'Scene name shown in the UI and CLI', default: 'custom' },
    description: { type: 'string', maxLength: 1000, description: 'One line on what the scene shows' },
    cloth: clothSchema,
    material: materialSchema,
    cloths: {
      type: 'array',
      minItems: 1,
      maxItems: MAX_CLOTHS,
      description: 'several cloths in one scene, instead of cloth, material and pins (give one or the other): each its own shape, start pose, fabric and pins, colliding with the colliders and, with solver.selfContact, with each other. Particles are numbered through the cloths in order (reports, exports, colliders[k].pins); a cloth\'s own pins count from its first particle. Between two cloths the contact distance is the mean of their thicknesses and friction the geometric mean of their coefficients',
      items: {
        type: 'object',
        additionalProperties: false,
        properties: {
          name: { type: 'string', maxLength: 100, description: 'what reports call this cloth (by default its place in the list: cloth 0, cloth 1, …)' },
          cloth: clothSchema,
          material: materialSchema,
          pins: clothPins,
        },
      },
    },
    solver: {
      type: 'object',
      additionalProperties: false,
      default: {},
      properties: {
        type: { enum: ['xpbd', 'mass-spring'], default: 'xpbd', description: "'xpbd' (Macklin et al. 2016, small steps 2019) or 'mass-spring' (the seed: Verlet, Hooke springs, stretch limiting)" },
        substeps: { type: 'integer', minimum: 1, maximum: MAX_SUBSTEPS, default: 20, description: 'substeps per 1/60 s frame; with solver.selfContact, raised where solver.selfContactSpeed needs more [-]' },
        iterations: { type: 'integer', minimum: 1, maximum: 20, default: 1, description: 'constraint passes per substep (XPBD: Gauss–Seidel sweeps; mass-spring: stretch-limiting passes) [-]' },
        bending: { enum: ['springs', 'hinges', 'laplacian'], default: 'springs', description: "the xpbd solver's bending model: 'springs' (the seed's skip-one bend springs), 'hinges' (the isometric bending model of Bergou et al. 2006 on the triangles' hinges: energy ½·B·κ² per area, B = material.bendingRigidity; stiffer across a fold that no edge follows) or 'laplacian' (the cotangent Laplacian at the interior vertices, Wardetzky et al. 2007: the same energy, the same in every direction on the grid); the mass-spring solver always bends with springs" },
        stretch: { enum: ['gauss-seidel', 'two-level', 'global'], default: 'two-level', description: "how the xpbd solver solves its springs each substep: 'gauss-seidel' (XPBD, one spring at a time, solver.iterations sweeps; a fine or soft cloth hangs longer than its stiffness says), 'two-level' (the default: the same sweeps, each substep starting from a coarse correction: the springs of each cell of a grid over the cloth, cells about 8 particles across, of one kind and in one of 4 directions, share one multiplier, solved together; a hanging sheet then stretches as its stiffness says from 16 to 128 faces a side, at about 1.6 times the sweep's frame) or 'global' (all together: solver.iterations local/global passes of Projective Dynamics, Bouaziz et al. 2014, on a system factored once; converges where a sweep lets a fine or soft cloth overstretch, so the tethers and the stretch limit are not applied; the GPU solves with the CPU's factor; a cloth of more than 66 049 particles is solved 'gauss-seidel', with a note)" },
        bendingSolve: { enum: ['gauss-seidel', 'global'], default: 'gauss-seidel', description: "how the xpbd solver solves a stencil bending model (solver.bending 'hinges' or 'laplacian'; the skip-one springs are solved with the stretch) each substep: 'gauss-seidel' (XPBD, one stencil at a time, solver.iterations sweeps) or 'global' (all together: the stencils' energy is quadratic, so its backward-Euler step is one linear system, factored once per mesh, substep and pins and solved exactly each substep; a light or stiff cloth then bends as its material.bendingRigidity says, where a sweep lets it bend too easily; the GPU solves with the CPU's factor; a cloth of more than 66 049 particles is solved 'gauss-seidel', with a note)" },
        selfContact: { type: 'boolean', default: false, description: "the cloth kept from passing through itself: each particle against the triangles near it and each edge against the edges near it, with side memory and the cloth's friction, every substep before collider contact (both solvers, every backend; docs/physics.md \"Self-contact\")" },
        selfContactSpeed: { type: 'number', minimum: 0, maximum: 100, default: 6, description: "with solver.selfContact, the speed of cloth against cloth that self-contact is made to catch: the substeps are raised (with a note) until cloth this fast moves at most the self-contact distance in one substep, on a fine mesh or a thin cloth; a grabbed particle is carried no faster (a faster drag would pull it through the cloth); 0 keeps solver.substeps as it is and the grab as fast as it is dragged (docs/physics.md \"Substeps for self-contact\", \"A fast grab\") [m/s]" },
        depenetrationSpeed: { type: 'number', minimum: 0.01, maximum: 100, default: 0.25, description: 'fastest the cloth is pushed out of a collider it did not move into (a cloth that starts inside one, or that a collider is moved into); contact the cloth moves into is undone at once [m/s]' },
      },
    },
    gravity: vec3('gravitational acceleration [m/s²]', -50, 50, [0, -9.81, 0]),
    wind: {
      type: 'object',
      additionalProperties: false,
      default: {},
      properties: {
        enabled: { type: 'boolean', default: false, description: 'the air on or off: on, the air pushes the cloth where it blows and drags on the cloth where it moves through it (at strength 0, still air: the drag alone); off, no air forces at all (free fall in a vacuum)' },
        strength: { type: 'number', minimum: 0, maximum: 30, default: 5, description: 'wind speed [m/s] (0: still air)' },
        direction: vec3('direction the wind blows towards (normalised; a zero vector: still air) [-]', -100, 100, [1, 0, 0]),
        airDensity: { type: 'number', minimum: 0, maximum: 10, default: 1.225, description: 'air density ρ in F = ½ρ·|v|(v·n)·area·n [kg/m³]' },
        gusts: {
          type: 'object',
          additionalProperties: false,
          default: {},
          properties: {
            enabled: { type: 'boolean', default: false, description: 'smoothly varying strength and direction' },
            amplitude: { type: 'number', minimum: 0, maximum: 1, default: 0.5, description: 'relative strength swing (and direction swing, as a fraction of 45°) [-]' },
            frequency: { type: 'number', minimum: 0.01, maximum: 10, default: 0.5, description: 'typical gust frequency [Hz]' },
            seed: { type: 'integer', minimum: 0, maximum: 2147483647, default: 1, description: 'random seed: the same seed gives the same gusts' },
          },
        },
      },
    },
    colliders: {
      type: 'array',
      maxItems: MAX_COLLIDERS,
      description: 'colliders the cloth meets: sphere, floor, plane (any angle), box, capsule, cylinder, mesh (a file); each may move (motion keys, or a pose the library sets each frame) and carry pins',
      default: [
        { type: 'sphere', center: [0, 0.5, 0], radius: 0.3 },
        { type: 'floor', height: 0 },
      ],
      items: {
        type: 'object',
        required: ['type'],
        discriminator: { propertyName: 'type' },
        oneOf: [
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            properties: {
              type: { const: 'sphere' },
              ...colliderCommon,
              center: vec3('centre [m]', -1000, 1000, [0, 0.5, 0]),
              radius: { type: 'number', minimum: 0.001, maximum: 100, default: 0.3, description: 'radius [m]' },
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            properties: {
              type: { const: 'floor' },
              ...colliderCommon,
              height: { type: 'number', minimum: -1000, maximum: 1000, default: 0, description: 'height of the floor plane y = height [m]' },
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            description: 'a half-space at any angle (a ramp, a wall): everything below the plane through point with the given normal',
            properties: {
              type: { const: 'plane' },
              ...colliderCommon,
              point: vec3('a point of the plane [m]', -1000, 1000, [0, 0, 0]),
              normal: vec3('outward normal of the plane (any length but zero; the solid side is behind it) [-]', -1, 1, [0, 1, 0]),
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            description: 'a solid box, turned like the cloth (Euler XYZ)',
            properties: {
              type: { const: 'box' },
              ...colliderCommon,
              center: vec3('centre [m]', -1000, 1000, [0, 0.35, 0]),
              halfExtents: vec3('half the size along the box\'s own x, y, z axes [m]', 0.001, 100, [0.4, 0.35, 0.4]),
              rotation: vec3('rotation about the centre, Euler XYZ as cloth.rotation [degrees]', -360, 360, [0, 0, 0]),
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            description: 'a capsule: the points within radius of the segment from a to b (a limb, a rail)',
            properties: {
              type: { const: 'capsule' },
              ...colliderCommon,
              a: vec3('one end of the axis segment [m]', -1000, 1000, [-0.4, 0.5, 0]),
              b: vec3('the other end of the axis segment (equal to a: a sphere) [m]', -1000, 1000, [0.4, 0.5, 0]),
              radius: { type: 'number', minimum: 0.001, maximum: 100, default: 0.1, description: 'radius [m]' },
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type'],
            description: 'a closed cylinder, caps included (a pedestal, a post)',
            properties: {
              type: { const: 'cylinder' },
              ...colliderCommon,
              center: vec3('centre (half way up the axis) [m]', -1000, 1000, [0, 0.25, 0]),
              axis: vec3('direction of the axis (any length but zero) [-]', -1, 1, [0, 1, 0]),
              radius: { type: 'number', minimum: 0.001, maximum: 100, default: 0.2, description: 'radius [m]' },
              height: { type: 'number', minimum: 0.001, maximum: 200, default: 0.5, description: 'length along the axis, cap to cap [m]' },
            },
          },
          {
            type: 'object',
            additionalProperties: false,
            required: ['type', 'mesh'],
            description: 'a triangle mesh from a file (a figure, a chair, a bowl, a terrain), kept in the file\'s own coordinates (a figure standing on y = 0 stays there): closed pieces are solids, open ones two-sided shells the cloth stays off on either side. Runs on the CPU and on the GPU',
            properties: {
              type: { const: 'mesh' },
              ...colliderCommon,
              mesh: { type: 'string', minLength: 1, maxLength: 1000, description: 'OBJ or glTF (.obj, .gltf, .glb) file of the collider, relative to the scene file; at most 1,000,000 triangles' },
              scale: { type: 'number', minimum: 1e-6, maximum: 1e6, default: 1, description: 'metres per unit of the mesh file: 0.01 for centimetres, 0.001 for millimetres, 0.0254 for inches [m]' },
              position: vec3('where the file\'s origin goes [m]', -1000, 1000, [0, 0, 0]),
              rotation: vec3('rotation about the file\'s origin, Euler XYZ as cloth.rotation [degrees]', -360, 360, [0, 0, 0]),
            },
          },
        ],
      },
    },
    duration: { type: 'number', minimum: 0.01, maximum: 3600, default: 3, description: 'how long `drape run` simulates when it is not given --frames (rounded to whole 1/60 s frames) [s]' },
    test: {
      description: 'the standard fabric test this scene is; the report (--json, the app\'s HUD) then gives its measurement as test.*',
      type: 'object',
      required: ['type'],
      discriminator: { propertyName: 'type' },
      oneOf: [
        {
          type: 'object',
          additionalProperties: false,
          description: 'ASTM D1388 / Peirce cantilever: a strip clamped (pinned) flat, overhanging an edge; reports test.overhang [m], test.chordAngle [degrees] and test.bendingLength [m], the bending length that angle gives (heavy elastica; null while the tip has not dropped below the edge)',
          properties: {
            type: { const: 'cantilever' },
            edge: vec3('a point of the platform\'s edge; the overhang and the chord are measured from the clamp\'s last pinned row at or behind it (the edge itself where a row lies on it) [m]', -1000, 1000, [0, 0, 0]),
            direction: vec3('the direction the strip overhangs in (its horizontal part is used) [-]', -1, 1, [0, 0, 1]),
          },
        },
        {
          type: 'object',
          additionalProperties: false,
          description: 'BS 5058 / ISO 9073-9 Cusick drape: a disc on a pedestal; reports test.projectedArea [m²], test.drapeCoefficient [-] and test.folds [-]',
          properties: {
            type: { const: 'cusick' },
            center: vec3('a point of the pedestal\'s (vertical) axis [m]', -1000, 1000, [0, 0, 0]),
            pedestalRadius: { type: 'number', minimum: 0.001, maximum: 10, default: 0.09, description: 'radius of the pedestal\'s top [m]' },
          },
        },
      ],
    },
    resolutionSweep: {
      type: 'array',
      maxItems: 16,
      items: { type: 'integer', minimum: 1, maximum: 1024 },
      description: 'optional: run the scene once per resolution listed (faces per side), e.g. the seed\'s 1 → 4096 faces demo',
    },
    pins: clothPins,
  },
} as const;
