// Tumble's viewer page: plays the run embedded in the page (see data.js) in 3D.
// The page needs nothing from the network: three.js is bundled into this script at build time.
import { readDocument, frameAt } from './data.js';
import { World } from './world.js';
import { Overlays } from './overlays.js';
import { Ui } from './ui.js';

class Player {
  constructor(doc, world, overlays) {
    this.doc = doc;
    this.world = world;
    this.overlays = overlays;
    this.frame = 0;
    this.time = doc.t[0];
    this.playing = false;
    this.speed = 1;
    this.loop = true;
    this.ui = null;
  }

  setFrame(f) {
    this.frame = Math.max(0, Math.min(this.doc.t.length - 1, f));
    this.time = this.doc.t[this.frame];
    this.redraw();
  }

  redraw() {
    const f = this.frame;
    this.world.setFrame(f);
    this.overlays.update(f);
    if (this.ui) this.ui.update(f);
    this.world.render();
  }

  play() {
    if (this.frame >= this.doc.t.length - 1) this.setFrame(0);
    this.playing = true;
    this.redraw();
  }

  pause() {
    this.playing = false;
  }

  toggle() {
    if (this.playing) this.pause();
    else this.play();
    this.redraw();
  }

  step(delta) {
    this.pause();
    this.setFrame(this.frame + delta);
  }

  /** Advances by `seconds` of wall time at the chosen speed. */
  advance(seconds) {
    if (!this.playing) return false;
    const t = this.doc.t;
    const end = t[t.length - 1];
    this.time += seconds * this.speed;
    if (this.time > end) {
      if (this.loop && end > t[0]) this.time = t[0] + ((this.time - t[0]) % (end - t[0]));
      else { this.time = end; this.playing = false; }
    }
    this.frame = frameAt(this.doc, this.time);
    return true;
  }
}

function start() {
  const doc = readDocument();
  const root = document.getElementById('app');
  const world = new World(root, doc);
  const overlays = new Overlays(world);
  const player = new Player(doc, world, overlays);
  player.ui = new Ui(root, player, world, overlays);

  const resize = () => {
    world.resize(window.innerWidth, window.innerHeight);
    player.redraw();
  };
  window.addEventListener('resize', resize);
  resize();

  // Draw only when something changed: playing, or the camera moved (software renderers and
  // laptops both thank us).
  let cameraMoved = false;
  world.controls.addEventListener('change', () => (cameraMoved = true));
  let last = performance.now();
  const tick = (now) => {
    const seconds = Math.min((now - last) / 1000, 0.1);
    last = now;
    if (player.advance(seconds)) player.redraw();
    else if (cameraMoved) world.render();
    cameraMoved = false;
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  player.play();

  // For tests and for poking at from the console.
  window.tumbleViewer = {
    frameCount: doc.t.length,
    bodyNames: doc.bodies.map((b) => b.name),
    setFrame: (f) => { player.pause(); player.setFrame(f); },
    frameAtTime: (t) => frameAt(doc, t),
    pause: () => player.pause(),
    get frame() { return player.frame; },
    get playing() { return player.playing; },
    setBodiesVisible: (on) => { world.bodies.forEach((b) => (b.mesh.visible = on)); player.redraw(); },
    setOverlay: (key, on) => { overlays.setVisible(key, on); player.redraw(); },
    /** Screen position (CSS pixels) of each body frame's origin at the current frame. */
    bodyScreenPoints: () => world.bodies.map((b) => {
      const p = b.group.position.clone().project(world.camera);
      return { x: (p.x + 1) / 2 * window.innerWidth, y: (1 - p.y) / 2 * window.innerHeight, visible: Math.abs(p.z) <= 1 };
    }),
    canvas: world.renderer.domElement,
  };
  document.body.dataset.ready = 'true';
}

try {
  start();
} catch (error) {
  const message = error instanceof Error ? error.message : String(error);
  document.body.insertAdjacentHTML('afterbegin', '<div class="fatal"></div>');
  document.querySelector('.fatal').textContent = `The viewer could not start: ${message}`;
  console.error(error);
}
