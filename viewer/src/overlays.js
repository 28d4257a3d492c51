// Overlays drawn over the bodies, each switched on and off on its own: contact points and
// normals, joint anchors and axes, body frames, centres of mass, and the angular velocity ω and
// angular momentum L of every dynamic body as arrows from its centre of mass.
import * as THREE from 'three';
import { poseOf, vectorOf, maxLength } from './data.js';
import { Arrow } from './arrow.js';

export const OVERLAYS = [
  { key: 'contacts', label: 'contacts (points, normals)', on: true },
  { key: 'joints', label: 'joints (anchors, axes)', on: true },
  { key: 'frames', label: 'body frames', on: false },
  { key: 'com', label: 'centres of mass', on: false },
  { key: 'omega', label: 'angular velocity ω', on: true, color: '#e8590c' },
  { key: 'L', label: 'angular momentum L', on: true, color: '#5f3dc4' },
];

const OMEGA_COLOR = 0xe8590c;
const L_COLOR = 0x5f3dc4;

function noDepth(material) {
  material.depthTest = false;
  material.transparent = true;
  return material;
}

export class Overlays {
  constructor(world) {
    this.world = world;
    this.doc = world.doc;
    this.groups = {};
    for (const { key } of OVERLAYS) {
      this.groups[key] = new THREE.Group();
      this.groups[key].renderOrder = 10;
      world.scene.add(this.groups[key]);
    }
    const s = world.scale;
    this.makeContacts(s);
    this.makeJoints(s);
    this.makeFramesAndCom();
    this.makeArrows(s);
    for (const o of OVERLAYS) this.setVisible(o.key, o.on);
  }

  setVisible(key, on) {
    this.groups[key].visible = on;
  }

  makeContacts(s) {
    const max = Math.max(1, ...this.doc.contacts.map((c) => c.length / 6));
    this.maxContacts = max;
    const dot = new THREE.SphereGeometry(0.015 * s, 10, 6);
    this.contactDots = new THREE.InstancedMesh(dot, noDepth(new THREE.MeshBasicMaterial({ color: 0xe03131 })), max);
    this.contactDots.count = 0;
    this.contactDots.frustumCulled = false;
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', new THREE.BufferAttribute(new Float32Array(max * 6), 3));
    this.contactLines = new THREE.LineSegments(lines, noDepth(new THREE.LineBasicMaterial({ color: 0xe03131 })));
    this.contactLines.frustumCulled = false;
    this.normalLength = 0.18 * s;
    this.groups.contacts.add(this.contactDots, this.contactLines);
  }

  makeJoints(s) {
    this.jointParts = this.doc.joints.map(() => {
      const anchor = new THREE.SphereGeometry(0.025 * s, 12, 8);
      const a = new THREE.Mesh(anchor, noDepth(new THREE.MeshBasicMaterial({ color: 0x1971c2 })));
      const b = new THREE.Mesh(anchor, noDepth(new THREE.MeshBasicMaterial({ color: 0x0c8599 })));
      const axis = new Arrow(0x1971c2, 0.008 * s);
      const link = new THREE.Line(
        new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
        noDepth(new THREE.LineBasicMaterial({ color: 0x1971c2 })),
      );
      link.frustumCulled = false;
      this.groups.joints.add(a, b, axis, link);
      return { a, b, axis, link };
    });
  }

  makeFramesAndCom() {
    this.world.bodies.forEach((body, i) => {
      const axes = new THREE.AxesHelper(body.radius * 1.25);
      axes.material = noDepth(axes.material);
      const frame = new THREE.Group();
      frame.add(axes);
      body.group.add(frame);
      body.frameHelper = frame;
      const com = new THREE.Mesh(
        new THREE.SphereGeometry(body.radius * 0.06, 16, 10),
        noDepth(new THREE.MeshBasicMaterial({ color: 0x111111 })),
      );
      com.position.fromArray(this.doc.bodies[i].com);
      body.group.add(com);
      body.comMarker = com;
    });
  }

  makeArrows(s) {
    const dynamic = this.doc.bodies.map((b, i) => (b.kind === 'dynamic' ? i : -1)).filter((i) => i >= 0);
    const maxOmega = maxLength(this.doc.omega);
    const maxL = maxLength(this.doc.L);
    // The longest arrow over the run is 0.9 of the scene radius; lengths are to scale within a kind.
    this.omegaScale = maxOmega > 0 ? (0.9 * s) / maxOmega : 0;
    this.LScale = maxL > 0 ? (0.9 * s) / maxL : 0;
    this.arrows = dynamic.map((i) => {
      // L wider and translucent, ω thinner inside it: both show when they line up.
      const L = new Arrow(L_COLOR, 0.022 * s, 0.55);
      const omega = new Arrow(OMEGA_COLOR, 0.011 * s);
      this.groups.omega.add(omega);
      this.groups.L.add(L);
      return { i, omega, L };
    });
  }

  update(f) {
    const doc = this.doc;
    // Frames and centres of mass live in the body groups; their switches are these groups'.
    this.world.bodies.forEach((body) => {
      body.frameHelper.visible = this.groups.frames.visible;
      body.comMarker.visible = this.groups.com.visible;
    });

    const c = doc.contacts[f] || [];
    const n = Math.min(c.length / 6, this.maxContacts);
    const m = new THREE.Matrix4();
    const positions = this.contactLines.geometry.attributes.position.array;
    for (let k = 0; k < n; k++) {
      const [px, py, pz, nx, ny, nz] = c.slice(6 * k, 6 * k + 6);
      this.contactDots.setMatrixAt(k, m.makeTranslation(px, py, pz));
      positions.set([px, py, pz, px + nx * this.normalLength, py + ny * this.normalLength, pz + nz * this.normalLength], 6 * k);
    }
    this.contactDots.count = n;
    this.contactDots.instanceMatrix.needsUpdate = true;
    this.contactLines.geometry.setDrawRange(0, 2 * n);
    this.contactLines.geometry.attributes.position.needsUpdate = true;

    const q = new THREE.Quaternion();
    const bodyPoint = (i, local) => {
      const pose = poseOf(doc, f, i);
      return new THREE.Vector3().fromArray(local).applyQuaternion(q.fromArray(pose.quaternion)).add(new THREE.Vector3().fromArray(pose.position));
    };
    doc.joints.forEach((joint, j) => {
      const parts = this.jointParts[j];
      const anchorA = bodyPoint(joint.a, joint.frameA.slice(0, 3));
      const anchorB = bodyPoint(joint.b, joint.frameB.slice(0, 3));
      parts.a.position.copy(anchorA);
      parts.b.position.copy(anchorB);
      const frameRotation = new THREE.Quaternion().fromArray(joint.frameA.slice(3, 7));
      const bodyRotation = new THREE.Quaternion().fromArray(poseOf(doc, f, joint.a).quaternion);
      const axis = new THREE.Vector3(0, 0, 1).applyQuaternion(bodyRotation.multiply(frameRotation));
      parts.axis.set(anchorA, axis, 0.35 * this.world.scale);
      parts.link.geometry.setFromPoints([anchorA, anchorB]);
    });

    for (const { i, omega, L } of this.arrows) {
      const com = bodyPoint(i, doc.bodies[i].com);
      omega.set(com, new THREE.Vector3().fromArray(vectorOf(doc.omega, f, i)), this.omegaScale);
      L.set(com, new THREE.Vector3().fromArray(vectorOf(doc.L, f, i)), this.LScale);
    }
  }

}
