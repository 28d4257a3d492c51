// A solid arrow (shaft and head) for vectors: visible at any zoom, unlike one-pixel lines. Drawn
// over everything (no depth test) so an arrow inside a body still shows.
import * as THREE from 'three';

const UP = new THREE.Vector3(0, 1, 0); // three's cylinders and cones lie along Y

export class Arrow extends THREE.Group {
  /** `thickness`: shaft radius in metres; `opacity` below 1 lets a thinner arrow inside show. */
  constructor(color, thickness, opacity = 1) {
    super();
    const material = new THREE.MeshBasicMaterial({ color, transparent: true, opacity, depthTest: false });
    this.shaft = new THREE.Mesh(new THREE.CylinderGeometry(1, 1, 1, 12), material);
    this.head = new THREE.Mesh(new THREE.ConeGeometry(1, 1, 16), material);
    this.add(this.shaft, this.head);
    this.thickness = thickness;
    this.renderOrder = 20;
    this.shaft.renderOrder = 20;
    this.head.renderOrder = 20;
  }

  /** Points the arrow from `origin` along `vector` scaled by `scale` (metres per unit). */
  set(origin, vector, scale) {
    const length = vector.length() * scale;
    this.visible = length > 1e-9;
    if (!this.visible) return;
    this.position.copy(origin);
    this.quaternion.setFromUnitVectors(UP, vector.clone().normalize());
    const r = this.thickness;
    const head = Math.min(length * 0.4, 5 * r);
    this.shaft.scale.set(r, length - head, r);
    this.shaft.position.set(0, (length - head) / 2, 0);
    this.head.scale.set(2.4 * r, head, 2.4 * r);
    this.head.position.set(0, length - head / 2, 0);
  }
}
