// The page's controls and read-outs: transport (play, pause, step, scrub, speed, loop), overlay
// switches, the live panel (time, energy, momentum, awake bodies) and names on hover.
import * as THREE from 'three';
import { OVERLAYS } from './overlays.js';

const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4];

// Button icons as SVG (no icon font: the page must look the same on every machine).
const ICON = {
  back: '<path d="M3 2h2v12H3zM14 2v12L6 8z"/>',
  forward: '<path d="M11 2h2v12h-2zM2 2v12l8-6z"/>',
  play: '<path d="M4 2v12l10-6z"/>',
  pause: '<path d="M3 2h4v12H3zM9 2h4v12H9z"/>',
};
const icon = (name) => `<svg viewBox="0 0 16 16" width="14" height="14" fill="currentColor">${ICON[name]}</svg>`;

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function fmt(x, unit) {
  if (!Number.isFinite(x)) return '–';
  const a = Math.abs(x);
  const text = a !== 0 && (a < 1e-3 || a >= 1e5) ? x.toExponential(3) : x.toFixed(a < 1 ? 4 : 3);
  return `${text} ${unit}`;
}

const length = (v) => Math.hypot(v[0], v[1], v[2]);

export class Ui {
  /** `player` has: doc, frame, playing, speed, loop, setFrame(f), play(), pause(), step(d). */
  constructor(root, player, world, overlays) {
    this.player = player;
    this.doc = player.doc;
    const doc = this.doc;
    this.dynamicCount = doc.bodies.filter((b) => b.kind === 'dynamic').length;

    this.stats = el('pre', { class: 'stats' });
    const title = el('div', { class: 'title' }, document.title.replace(/^Tumble — /, ''));
    root.append(el('div', { class: 'panel info' }, el('div', { class: 'brand' }, 'Tumble'), title, this.stats));

    const toggles = el('div', { class: 'panel toggles' }, el('div', { class: 'head' }, 'Show'));
    for (const o of OVERLAYS) {
      const box = el('input', { type: 'checkbox', 'data-overlay': o.key });
      box.checked = o.on;
      box.addEventListener('change', () => {
        overlays.setVisible(o.key, box.checked);
        player.redraw();
      });
      const swatch = o.color ? el('span', { class: 'swatch', style: `background:${o.color}` }) : '';
      toggles.append(el('label', {}, box, swatch, ` ${o.label}`));
    }
    if (!doc.simulated) toggles.append(el('div', { class: 'note' }, 'replayed from a recording: no contacts or sleep'));
    root.append(toggles);

    this.playButton = el('button', { title: 'play / pause (space)', onclick: () => player.toggle() });
    this.playButton.innerHTML = icon('play');
    const back = el('button', { title: 'step back (←)', onclick: () => player.step(-1) });
    back.innerHTML = icon('back');
    const forward = el('button', { title: 'step forward (→)', onclick: () => player.step(1) });
    forward.innerHTML = icon('forward');
    this.slider = el('input', { type: 'range', min: 0, max: doc.t.length - 1, step: 1, value: 0, 'aria-label': 'time' });
    this.slider.addEventListener('input', () => {
      player.pause();
      player.setFrame(Number(this.slider.value));
    });
    this.timeLabel = el('span', { class: 'time' });
    const speed = el('select', { title: 'playback speed' });
    for (const s of SPEEDS) speed.append(el('option', { value: s }, `${s}×`));
    speed.value = '1';
    speed.addEventListener('change', () => (player.speed = Number(speed.value)));
    const loop = el('input', { type: 'checkbox' });
    loop.checked = player.loop;
    loop.addEventListener('change', () => (player.loop = loop.checked));
    root.append(
      el('div', { class: 'panel transport' },
        back, this.playButton, forward,
        this.slider, this.timeLabel, speed,
        el('label', { title: 'start again at the end' }, loop, ' loop')),
      el('div', { class: 'help' }, 'drag: orbit · right-drag: pan · wheel: zoom · space: play/pause · ←/→: step'),
    );

    window.addEventListener('keydown', (e) => {
      if (e.target instanceof HTMLInputElement && e.target.type !== 'checkbox' && e.target.type !== 'range') return;
      if (e.code === 'Space') { player.toggle(); e.preventDefault(); }
      if (e.code === 'ArrowRight') { player.step(1); e.preventDefault(); }
      if (e.code === 'ArrowLeft') { player.step(-1); e.preventDefault(); }
    });

    this.tooltip = el('div', { class: 'tooltip' });
    root.append(this.tooltip);
    this.hover(world);
  }

  /** Names on hover: the body under the pointer. */
  hover(world) {
    const ray = new THREE.Raycaster();
    const pointer = new THREE.Vector2();
    const meshes = world.bodies.map((b) => b.mesh);
    world.renderer.domElement.addEventListener('pointermove', (e) => {
      const r = world.renderer.domElement.getBoundingClientRect();
      pointer.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
      ray.setFromCamera(pointer, world.camera);
      const hit = ray.intersectObjects(meshes, false)[0];
      if (!hit) { this.tooltip.style.display = 'none'; return; }
      const { name, kind, mass } = hit.object.userData;
      this.tooltip.textContent = kind === 'dynamic' ? `${name} · ${mass.toPrecision(4)} kg` : `${name} (${kind})`;
      Object.assign(this.tooltip.style, { display: 'block', left: `${e.clientX + 14}px`, top: `${e.clientY + 10}px` });
    });
    world.renderer.domElement.addEventListener('pointerleave', () => (this.tooltip.style.display = 'none'));
  }

  update(f) {
    const doc = this.doc;
    const t = doc.t[f];
    this.slider.value = String(f);
    const state = this.player.playing ? 'pause' : 'play';
    if (this.playButton.dataset.state !== state) {
      this.playButton.dataset.state = state;
      this.playButton.innerHTML = icon(state);
    }
    this.timeLabel.textContent = `${t.toFixed(3)} s / ${doc.t[doc.t.length - 1].toFixed(2)} s`;
    const kinetic = doc.kinetic[f];
    const potential = doc.potential[f];
    const lines = [
      `time      ${fmt(t, 's')}   frame ${f + 1}/${doc.t.length}`,
      `energy    ${fmt(kinetic + potential, 'J')}`,
      `  kinetic ${fmt(kinetic, 'J')}`,
      `  potent. ${fmt(potential, 'J')}`,
      `momentum  |p| ${fmt(length(doc.momentum[f]), 'kg m/s')}`,
      `          |L| ${fmt(length(doc.angularMomentum[f]), 'kg m²/s')}`,
      doc.simulated ? `awake     ${doc.awakeCount[f]} of ${this.dynamicCount} dynamic bodies` : 'awake     (not recorded)',
      doc.simulated ? `contacts  ${(doc.contacts[f] || []).length / 6} points` : '',
    ];
    this.stats.textContent = lines.filter(Boolean).join('\n');
  }
}
