//! The 3D tissue view (three.js, WebGL): the boundary surface of the tetrahedral mesh, displaced
//! and coloured by displacement magnitude, a movable section plane that cuts the tissue open (the
//! cut shows the surface's inside faces, the needle, its contact points and the targets behind
//! it), the needle, its contact points (stuck / slipping / tip), the target spheres, and an orbit
//! camera. Pure drawing: it knows the session's data only as `Surface3` and `Scene3`, which
//! `frame3.ts` builds from the protocol's messages.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

/** The tissue's boundary, fetched once per session: reference positions (m, world) of the
 * surface's nodes and triangles over them (indices into `positionsM / 3`). */
export interface Surface3 {
  positionsM: Float32Array;
  triangles: Uint32Array;
}

export type PointState = "stuck" | "slipping" | "tip" | "other";

/** What one frame shows. */
export interface Scene3 {
  /** Displacements (m) of the surface's nodes, `3·n`, or null (keep the last ones). */
  displacementM: Float32Array | null;
  /** The needle from base to tip (m, world). */
  needleM: [number, number, number][];
  /** Contact points (deformed positions, m) and their states. */
  points: { posM: [number, number, number]; state: PointState }[];
  /** Target spheres: displaced centre (m), radius (m), hit. */
  targets: { centreM: [number, number, number]; radiusM: number; hit: boolean }[];
}

const POINT_COLOUR: Record<PointState, number> = { stuck: 0x2166ac, slipping: 0xf18f01, tip: 0xe7298a, other: 0x999999 };

/** Displacement magnitude → colour: white (0) through yellow to red (at `scale` and above). */
function heat(t: number, out: THREE.Color): void {
  const s = Math.min(Math.max(t, 0), 1);
  if (s < 0.5) out.setRGB(1, 1, 1 - 2 * s * 0.9);
  else out.setRGB(1, 1 - (s - 0.5) * 1.6, 0.1);
}

export class TissueView3 {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  /** The section plane: points with `normal · x + constant < 0` are cut away (three.js's rule):
   * here the half y < y₀, the half towards the default camera. */
  readonly section = new THREE.Plane(new THREE.Vector3(0, 1, 0), 0);
  private sectionOn = false;
  private tissue: THREE.Mesh | null = null;
  private surface: Surface3 | null = null;
  private centre = new THREE.Vector3();
  private sizeM = 0.1;
  /** The displacement magnitude at the top of the colour scale (m): the shown frame's largest. */
  displacementScaleM = 1e-3;
  private needle: THREE.Line;
  private points: THREE.Points;
  private targetMeshes: THREE.Mesh[] = [];
  private unitSphere = new THREE.SphereGeometry(1, 24, 16);
  private colour = new THREE.Color();

  constructor(readonly canvas: HTMLCanvasElement) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.localClippingEnabled = true;
    this.renderer.setClearColor(0xffffff);
    this.camera = new THREE.PerspectiveCamera(40, canvas.width / canvas.height, 1e-4, 10);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = false;
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const sun = new THREE.DirectionalLight(0xffffff, 0.9);
    sun.position.set(1, 2, 3);
    this.scene.add(sun);
    const headlight = new THREE.DirectionalLight(0xffffff, 0.4);
    this.camera.add(headlight);
    this.scene.add(this.camera);
    this.needle = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x222222, linewidth: 2 }));
    this.needle.frustumCulled = false;
    this.points = new THREE.Points(
      new THREE.BufferGeometry(),
      new THREE.PointsMaterial({ size: 7, sizeAttenuation: false, vertexColors: true, depthTest: false }),
    );
    this.points.frustumCulled = false;
    this.points.renderOrder = 2;
    this.scene.add(this.needle, this.points);
  }

  /** Shows a new session's surface and frames the camera on it. */
  setSurface(s: Surface3): void {
    if (this.tissue) {
      this.scene.remove(this.tissue);
      this.tissue.geometry.dispose();
    }
    this.surface = s;
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(new Float32Array(s.positionsM), 3));
    g.setAttribute("color", new THREE.BufferAttribute(new Float32Array(s.positionsM.length).fill(1), 3));
    g.setIndex(new THREE.BufferAttribute(s.triangles, 1));
    g.computeVertexNormals();
    g.computeBoundingBox();
    const mat = new THREE.MeshLambertMaterial({
      vertexColors: true,
      side: THREE.DoubleSide,
      transparent: true,
      opacity: 0.85,
      clippingPlanes: [],
    });
    this.tissue = new THREE.Mesh(g, mat);
    this.scene.add(this.tissue);
    const box = g.boundingBox ?? new THREE.Box3();
    box.getCenter(this.centre);
    this.sizeM = box.getSize(new THREE.Vector3()).length() || 0.1;
    this.camera.near = this.sizeM * 1e-3;
    this.camera.far = this.sizeM * 50;
    this.camera.position.copy(this.centre).add(new THREE.Vector3(0.9, -1.4, 0.8).multiplyScalar(this.sizeM));
    this.camera.up.set(0, 0, 1);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(this.centre);
    this.controls.update();
    this.setSection(this.sectionOn, 0.5);
  }

  /** Turns the section plane on or off and places it: `at` ∈ [0, 1] across the tissue along y. */
  setSection(on: boolean, at: number): void {
    this.sectionOn = on;
    const box = this.tissue?.geometry.boundingBox;
    if (box) this.section.constant = -(box.min.y + at * (box.max.y - box.min.y));
    if (this.tissue) (this.tissue.material as THREE.Material).clippingPlanes = on ? [this.section] : [];
  }

  /** Updates the picture to a frame. */
  show(f: Scene3): void {
    const s = this.surface;
    if (s && this.tissue && f.displacementM && f.displacementM.length === s.positionsM.length) {
      const pos = this.tissue.geometry.getAttribute("position") as THREE.BufferAttribute;
      const col = this.tissue.geometry.getAttribute("color") as THREE.BufferAttribute;
      let maxMag = 0;
      const u = f.displacementM;
      for (let i = 0; i < u.length; i += 3) {
        const m = Math.hypot(u[i], u[i + 1], u[i + 2]);
        if (m > maxMag) maxMag = m;
      }
      // The frame's own largest displacement tops the scale (a square root spreads the colours
      // over the far field, where displacements fall off as 1/r).
      this.displacementScaleM = maxMag > 0 ? maxMag : 1;
      for (let i = 0, k = 0; i < u.length; i += 3, k++) {
        pos.setXYZ(k, s.positionsM[i] + u[i], s.positionsM[i + 1] + u[i + 1], s.positionsM[i + 2] + u[i + 2]);
        heat(Math.sqrt(Math.hypot(u[i], u[i + 1], u[i + 2]) / this.displacementScaleM), this.colour);
        col.setXYZ(k, this.colour.r, this.colour.g, this.colour.b);
      }
      pos.needsUpdate = true;
      col.needsUpdate = true;
      this.tissue.geometry.computeVertexNormals();
    }
    this.needle.geometry.setFromPoints(f.needleM.map(([x, y, z]) => new THREE.Vector3(x, y, z)));
    const pg = this.points.geometry;
    const pos3 = new Float32Array(f.points.length * 3), col3 = new Float32Array(f.points.length * 3);
    f.points.forEach((p, i) => {
      pos3.set(p.posM, 3 * i);
      this.colour.setHex(POINT_COLOUR[p.state]);
      col3.set([this.colour.r, this.colour.g, this.colour.b], 3 * i);
    });
    pg.setAttribute("position", new THREE.BufferAttribute(pos3, 3));
    pg.setAttribute("color", new THREE.BufferAttribute(col3, 3));
    // Target spheres: one mesh per target, made once and moved.
    while (this.targetMeshes.length < f.targets.length) {
      const m = new THREE.Mesh(this.unitSphere, new THREE.MeshLambertMaterial({ transparent: true, opacity: 0.75 }));
      this.targetMeshes.push(m);
      this.scene.add(m);
    }
    this.targetMeshes.forEach((m, i) => {
      const t = f.targets[i];
      m.visible = t !== undefined;
      if (!t) return;
      m.position.set(...t.centreM);
      m.scale.setScalar(t.radiusM);
      (m.material as THREE.MeshLambertMaterial).color.setHex(t.hit ? 0x1b9e77 : 0x7570b3);
    });
  }

  render(): void {
    this.renderer.render(this.scene, this.camera);
  }
}
