// The viewing-sphere widget (Rademacher 99, Figure 4): the unit sphere of view directions with the
// key views (blue), the dummy base points of the uncovered regions (grey), the hull's triangles as
// great-circle arcs, the triangle the current view lies in (filled, orange) and the view itself
// (red). Drawn from the main camera's side, so the current view faces the viewer.
import * as THREE from 'three';

const ARC_STEPS = 16;

/**
 * Points along the great-circle arc from unit a to unit b, at radius r.
 * @param {THREE.Vector3} a @param {THREE.Vector3} b @param {number} r
 * @returns {THREE.Vector3[]}
 */
function arc(a, b, r) {
  const out = [];
  for (let s = 0; s <= ARC_STEPS; ++s) out.push(a.clone().lerp(b, s / ARC_STEPS).normalize().multiplyScalar(r));
  return out;
}

/**
 * A spherical triangle as a subdivided mesh's positions (flat array, 3 floats a vertex).
 * @param {THREE.Vector3[]} c corners @param {number} r @param {number} n subdivisions a side
 */
function sphericalTriangle(c, r, n) {
  const at = (i, j) => {
    const k = n - i - j;
    return new THREE.Vector3()
      .addScaledVector(c[0], k / n).addScaledVector(c[1], i / n).addScaledVector(c[2], j / n).normalize().multiplyScalar(r);
  };
  const positions = [];
  for (let i = 0; i < n; ++i)
    for (let j = 0; j < n - i; ++j) {
      for (const p of [at(i, j), at(i + 1, j), at(i, j + 1)]) positions.push(p.x, p.y, p.z);
      if (i + j < n - 1) for (const p of [at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]) positions.push(p.x, p.y, p.z);
    }
  return positions;
}

export class SphereWidget {
  /** @param {import('../vdg-three.js').VdgExtras} extras */
  constructor(extras) {
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.1, 10);
    const sphere = extras.sphere;
    /** @type {THREE.Vector3[]} */
    this.points = sphere.points.map((p) => new THREE.Vector3().fromArray(p).normalize());
    this.triangles = sphere.triangles;
    this.scene.add(new THREE.Mesh(new THREE.SphereGeometry(0.995, 48, 24),
      new THREE.MeshBasicMaterial({ color: 0xeef0f4, transparent: true, opacity: 0.85 })));
    const lines = [];
    for (const [a, b, c] of sphere.triangles)
      for (const [u, v] of [[a, b], [b, c], [c, a]]) {
        const pts = arc(this.points[u], this.points[v], 1.002);
        for (let s = 0; s < pts.length - 1; ++s) lines.push(pts[s], pts[s + 1]);
      }
    this.scene.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(lines),
      new THREE.LineBasicMaterial({ color: 0x556070 })));
    const dot = new THREE.SphereGeometry(1, 12, 8);
    this.points.forEach((p, i) => {
      const key = i < sphere.views;
      const mesh = new THREE.Mesh(dot, new THREE.MeshBasicMaterial({ color: key ? 0x2050c0 : 0x9a9a9a }));
      mesh.scale.setScalar(key ? 0.045 : 0.03);
      mesh.position.copy(p).multiplyScalar(1.01);
      this.scene.add(mesh);
    });
    this.active = new THREE.Mesh(new THREE.BufferGeometry(),
      new THREE.MeshBasicMaterial({ color: 0xff9020, transparent: true, opacity: 0.6, side: THREE.DoubleSide }));
    this.scene.add(this.active);
    this.view = new THREE.Mesh(dot, new THREE.MeshBasicMaterial({ color: 0xd02020 }));
    this.view.scale.setScalar(0.05);
    this.scene.add(this.view);
    this.activeTriangle = -2;
  }

  /**
   * Follows the main camera and the current weights.
   * @param {THREE.Vector3} view unit model-space view direction
   * @param {THREE.Camera} mainCamera
   * @param {{triangle: number}|null} sphereWeights the runtime's lastSphereWeights
   */
  update(view, mainCamera, sphereWeights) {
    this.view.position.copy(view).multiplyScalar(1.01);
    this.camera.position.copy(view).multiplyScalar(4.8);
    this.camera.up.copy(mainCamera.up);
    this.camera.lookAt(0, 0, 0);
    const triangle = sphereWeights ? sphereWeights.triangle : -1;
    if (triangle === this.activeTriangle) return;
    this.activeTriangle = triangle;
    const positions = triangle >= 0 ? sphericalTriangle(this.triangles[triangle].map((i) => this.points[i]), 1.004, 12) : [];
    this.active.geometry.dispose();
    this.active.geometry = new THREE.BufferGeometry();
    this.active.geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  }
}
