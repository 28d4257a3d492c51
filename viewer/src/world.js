// The 3D scene: renderer, Z-up camera with orbit/pan/zoom, lights with shadows, the floor, and one
// mesh per body placed at its pose of a frame.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { poseOf } from './data.js';

THREE.Object3D.DEFAULT_UP.set(0, 0, 1);

const DYNAMIC_COLORS = [0xd9622b, 0x2f74c0, 0x3a9a4a, 0xc9a227, 0x8a52b3, 0x2aa198, 0xc0392b, 0x7f8c8d];
const STATIC_COLOR = 0x9a9a96;
const BACKGROUND = 0xeef1f5;

export class World {
  constructor(container, doc) {
    this.doc = doc;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.shadowMap.enabled = true;
    this.renderer.shadowMap.type = THREE.PCFSoftShadowMap;
    this.renderer.setClearColor(BACKGROUND);
    container.appendChild(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(BACKGROUND);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;

    this.bodies = doc.bodies.map((body, i) => this.makeBody(body, i));
    // The camera frames everywhere the bodies go; the floor goes under it.
    this.bounds = this.sceneBounds(0, doc.t.length);
    this.floorZ = this.bounds.min.z;
    this.addLights();
    this.addFloor();
    this.frameCamera();
  }

  makeBody(body, index) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(body.positions, 3));
    geometry.setAttribute('normal', new THREE.Float32BufferAttribute(body.normals, 3));
    geometry.setIndex(body.indices);
    geometry.computeBoundingSphere();
    const dynamicIndex = this.doc.bodies.slice(0, index).filter((b) => b.kind !== 'static').length;
    const color = body.kind === 'static' ? STATIC_COLOR : DYNAMIC_COLORS[dynamicIndex % DYNAMIC_COLORS.length];
    const material = new THREE.MeshStandardMaterial({ color, roughness: 0.55, metalness: 0.05 });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.castShadow = true;
    mesh.receiveShadow = true;
    mesh.userData = { index, name: body.name, kind: body.kind, mass: body.mass };
    const group = new THREE.Group(); // the body frame; overlays attach to it too
    group.add(mesh);
    this.scene.add(group);
    const radius = geometry.boundingSphere ? geometry.boundingSphere.center.length() + geometry.boundingSphere.radius : 0;
    return { group, mesh, radius: Math.max(radius, 1e-3), color, awakeColor: new THREE.Color(color) };
  }

  /** A box around the bodies over frames [from, to), from a sample of at most 60 of them. */
  sceneBounds(from, to) {
    const box = new THREE.Box3();
    const frames = Math.min(to, this.doc.t.length);
    const step = Math.max(1, Math.floor((frames - from) / 60));
    const m = new THREE.Matrix4();
    const q = new THREE.Quaternion();
    const p = new THREE.Vector3();
    const one = new THREE.Vector3(1, 1, 1);
    const bodyBox = new THREE.Box3();
    for (let f = from; f < frames; f += step) {
      this.doc.bodies.forEach((body, i) => {
        const pose = poseOf(this.doc, f, i);
        m.compose(p.fromArray(pose.position), q.fromArray(pose.quaternion), one);
        const geometry = this.bodies[i].mesh.geometry;
        if (!geometry.boundingBox) geometry.computeBoundingBox();
        bodyBox.copy(geometry.boundingBox).applyMatrix4(m);
        box.union(bodyBox);
      });
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    return box;
  }

  addLights() {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8070, 1.1));
    const size = this.bounds.getSize(new THREE.Vector3()).length();
    const centre = this.bounds.getCenter(new THREE.Vector3());
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.copy(centre).add(new THREE.Vector3(0.45, -0.35, 1).normalize().multiplyScalar(size * 1.5 + 1));
    sun.target.position.copy(centre);
    sun.castShadow = true;
    sun.shadow.mapSize.set(2048, 2048);
    const half = size * 0.75 + 0.5;
    Object.assign(sun.shadow.camera, { left: -half, right: half, top: half, bottom: -half, near: 0.01, far: size * 4 + 4 });
    sun.shadow.bias = -0.0005;
    sun.shadow.normalBias = 0.01 * half;
    this.scene.add(sun, sun.target);
  }

  /** A floor under everything, catching shadows, with a metre grid (finer for small scenes). */
  addFloor() {
    const size = this.bounds.getSize(new THREE.Vector3());
    const centre = this.bounds.getCenter(new THREE.Vector3());
    const extent = Math.max(size.x, size.y, size.z, 1) * 4;
    const z = this.floorZ - 0.002 * Math.max(size.z, 0.1);
    const floor = new THREE.Mesh(
      new THREE.PlaneGeometry(extent, extent),
      new THREE.MeshStandardMaterial({ color: 0xdcd8cf, roughness: 0.95 }),
    );
    floor.position.set(centre.x, centre.y, z);
    floor.receiveShadow = true;
    floor.userData.floor = true;
    this.scene.add(floor);
    const cell = Math.pow(10, Math.floor(Math.log10(Math.max(size.x, size.y, size.z, 0.01)))) / 2;
    const divisions = Math.min(400, Math.round(extent / cell));
    const grid = new THREE.GridHelper(divisions * cell, divisions, 0xb5b0a5, 0xc9c5bb);
    grid.rotation.x = Math.PI / 2; // GridHelper lies in XZ; the floor is XY
    grid.position.set(centre.x, centre.y, z + 1e-4 * extent);
    this.scene.add(grid);
    this.floor = floor;
    this.grid = grid;
  }

  frameCamera() {
    const centre = this.bounds.getCenter(new THREE.Vector3());
    const radius = Math.max(this.bounds.getSize(new THREE.Vector3()).length() / 2, 0.05);
    // Fits the bounding sphere, less a little: the box is rarely full in every direction.
    const distance = (radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2))) * 0.8;
    this.camera.position.copy(centre).add(new THREE.Vector3(1.0, -1.6, 0.75).normalize().multiplyScalar(distance));
    this.camera.near = distance / 500;
    this.camera.far = distance * 50;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    this.scale = radius;
  }

  /** Places every body at frame `f`; sleeping bodies are drawn paler. */
  setFrame(f) {
    this.doc.bodies.forEach((body, i) => {
      const pose = poseOf(this.doc, f, i);
      const { group, mesh, awakeColor } = this.bodies[i];
      group.position.fromArray(pose.position);
      group.quaternion.fromArray(pose.quaternion);
      if (body.kind === 'dynamic' && this.doc.simulated) {
        const asleep = this.doc.awake[f][i] === 0;
        mesh.material.color.copy(awakeColor);
        if (asleep) mesh.material.color.lerp(new THREE.Color(0xffffff), 0.45);
      }
    });
  }

  resize(width, height) {
    this.renderer.setSize(width, height, false);
    this.renderer.domElement.style.width = `${width}px`;
    this.renderer.domElement.style.height = `${height}px`;
    this.camera.aspect = width / Math.max(height, 1);
    this.camera.updateProjectionMatrix();
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}
