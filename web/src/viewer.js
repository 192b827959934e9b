// The viewer of volspline's interactive pages (docs/web-pages.md). esbuild bundles this file with
// the parts of three.js it imports into one minified script (cmake/web_viewer.cmake), which the
// library embeds in every page (src/web/interactive_page.cpp). The page carries its data as JSON
// in <script id="volspline-page" type="application/json">:
//
//   title, command                   strings
//   parts: [{name, number, srgb, glb}]   the result, one binary glTF (base64) per part
//   probes: [{name, label, part, values, glbs, initial}]   one glTF per level; the slider shows one
//   probe_points: {probes: [i, j, k], points: [[x, y, z], ...]}   V(u_i, v_j, w_k), i fastest
//   color_bar: {title, min, max, stops: [[r, g, b], ...]} or null
//   reduced: {triangles, shown, cell_size} where the result is shown with fewer triangles, or null
//   info: any JSON object, shown as nested lists
//
// When everything is loaded and drawn, document.body gets data-ready="1" and
// window.volsplinePage holds what the browser tests read (readyAt: milliseconds from the start of
// navigation until drawn; loadMilliseconds: the viewer's own share).
import {
  AmbientLight,
  Box3,
  Color,
  DirectionalLight,
  DoubleSide,
  Group,
  Mesh,
  MeshStandardMaterial,
  PerspectiveCamera,
  Plane,
  Scene,
  SphereGeometry,
  SRGBColorSpace,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const STYLE = `
html, body { margin: 0; height: 100%; font-family: sans-serif; font-size: 13px; }
body { display: flex; }
#vs-panel { width: 330px; min-width: 330px; overflow-y: auto; padding: 8px 12px; box-sizing: border-box;
  border-right: 1px solid #ccc; background: #fafafa; }
#vs-view { flex: 1; position: relative; min-width: 0; }
#vs-canvas { width: 100%; height: 100%; display: block; }
#vs-panel h1 { font-size: 15px; margin: 4px 0 8px; }
#vs-panel h2 { font-size: 13px; margin: 12px 0 4px; border-bottom: 1px solid #ddd; }
#vs-panel label { display: block; margin: 2px 0; }
.vs-swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid #555; vertical-align: middle; margin: 0 4px; }
.vs-slider { width: 100%; }
.vs-info dl { margin: 0 0 0 8px; }
.vs-info dt { font-weight: bold; margin-top: 2px; }
.vs-info dd { margin: 0 0 0 12px; word-break: break-all; }
#vs-colorbar { position: absolute; right: 16px; top: 16px; width: 28px; height: 240px; border: 1px solid #444; }
#vs-colorbar-labels { position: absolute; right: 52px; top: 10px; height: 252px; display: flex; flex-direction: column;
  justify-content: space-between; text-align: right; font-size: 12px; }
#vs-colorbar-title { position: absolute; right: 10px; top: 262px; font-size: 12px; }
pre.vs-command { white-space: pre-wrap; background: #eee; padding: 4px; font-size: 11px; }
`;

function element(tag, attributes = {}, parent = null) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v);
  }
  if (parent) parent.appendChild(e);
  return e;
}

function base64Bytes(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

function cssColor(srgb) {
  return `rgb(${srgb.map((c) => Math.round(255 * c)).join(',')})`;
}

// JSON shown as nested definition lists: objects by key, arrays of numbers on one line.
function infoList(value, parent) {
  if (value === null || typeof value !== 'object') {
    parent.appendChild(document.createTextNode(String(value)));
    return;
  }
  if (Array.isArray(value) && value.every((v) => v === null || typeof v !== 'object')) {
    parent.appendChild(document.createTextNode(value.join(', ')));
    return;
  }
  const dl = element('dl', {}, parent);
  for (const [k, v] of Object.entries(value)) {
    element('dt', { text: Array.isArray(value) ? `[${k}]` : k }, dl);
    infoList(v, element('dd', {}, dl));
  }
}

async function main() {
  const started = performance.now();
  const data = JSON.parse(document.getElementById('volspline-page').textContent);
  element('style', { text: STYLE }, document.head);
  document.title = data.title;

  const panel = element('div', { id: 'vs-panel' }, document.body);
  const view = element('div', { id: 'vs-view' }, document.body);
  const canvas = element('canvas', { id: 'vs-canvas' }, view);
  element('h1', { text: data.title }, panel);

  const renderer = new WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.outputColorSpace = SRGBColorSpace;
  renderer.localClippingEnabled = true;
  const scene = new Scene();
  scene.background = new Color(1, 1, 1);
  const camera = new PerspectiveCamera(35, 1, 0.01, 1000);
  scene.add(camera);
  scene.add(new AmbientLight(0xffffff, 1.2));
  const headlight = new DirectionalLight(0xffffff, 2.2);
  headlight.position.set(0.3, 0.5, 1);
  camera.add(headlight);
  const controls = new OrbitControls(camera, canvas);

  const clipPlane = new Plane(new Vector3(0, 0, -1), 0);
  const clipping = { on: false };
  const materials = [];
  const partMaterials = [];
  const wire = { on: false };
  // The result is drawn see-through while probes are inside it (Lasser Fig. 10 shows the
  // surfaces through the point inside the solid's outline).
  const seeThrough = { on: data.probes.some((p) => p.shown) };
  function translucent(m) {
    m.transparent = seeThrough.on;
    m.opacity = seeThrough.on ? 0.3 : 1;
    m.depthWrite = !seeThrough.on;
    m.needsUpdate = true;
  }
  function material(ofPart) {
    const m = new MeshStandardMaterial({ vertexColors: true, side: DoubleSide, roughness: 0.75, metalness: 0 });
    m.clippingPlanes = clipping.on ? [clipPlane] : [];
    m.wireframe = wire.on;
    materials.push(m);
    if (ofPart) {
      partMaterials.push(m);
      translucent(m);
    }
    return m;
  }

  const loader = new GLTFLoader();
  async function meshOf(glb, ofPart) {
    const gltf = await loader.parseAsync(base64Bytes(glb), '');
    const group = new Group();
    gltf.scene.traverse((o) => {
      if (o.isMesh) group.add(new Mesh(o.geometry, material(ofPart)));
    });
    return group;
  }

  let frame = 0;
  function draw() {
    const w = view.clientWidth, h = view.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(h, 1);
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
    ++frame;
  }
  function redraw() {
    requestAnimationFrame(draw);
  }
  controls.addEventListener('change', redraw);
  window.addEventListener('resize', redraw);

  // The result, one object per part, listed with its colour and a switch.
  const parts = [];
  const box = new Box3();
  element('h2', { text: 'Parts' }, panel);
  for (const part of data.parts) {
    const object = await meshOf(part.glb, true);
    scene.add(object);
    box.expandByObject(object);
    parts.push({ part, object });
    const label = element('label', {}, panel);
    const check = element('input', { type: 'checkbox', 'data-part': part.name }, label);
    check.checked = true;
    check.addEventListener('change', () => {
      object.visible = check.checked;
      redraw();
    });
    const swatch = element('span', { class: 'vs-swatch' }, label);
    swatch.style.background = cssColor(part.srgb);
    label.appendChild(document.createTextNode(`${part.name} (${part.number}): ${part.triangles} triangles`));
  }

  if (data.reduced) {
    element('p', {
      id: 'vs-reduced',
      text: `Shown with ${data.reduced.shown} of its ${data.reduced.triangles} triangles (vertices clustered in cubes of ` +
        `${Number(data.reduced.cell_size).toPrecision(3)}); the mesh file has them all.`,
    }, panel);
  }

  // Probes: one slider each, showing the precomputed mesh of the level it points at.
  const probes = [];
  const marker = new Mesh(new SphereGeometry(1, 16, 12), new MeshStandardMaterial({ color: 0xd01010 }));
  marker.visible = false;
  scene.add(marker);
  function placeMarker() {
    const pp = data.probe_points;
    if (!pp) return;
    const shown = pp.probes.map((name) => probes.find((p) => p.probe.name === name));
    marker.visible = shown.every((p) => p && p.check.checked);
    if (!marker.visible) return;
    const n = shown.map((p) => p.probe.values.length);
    const [i, j, k] = shown.map((p) => p.index);
    const point = pp.points[i + n[0] * (j + n[1] * k)];
    marker.position.set(point[0], point[1], point[2]);
  }
  if (data.probes.length > 0) element('h2', { text: 'Probes' }, panel);
  for (const probe of data.probes) {
    const levels = [];
    for (const glb of probe.glbs) {
      const object = await meshOf(glb, false);
      object.visible = false;
      scene.add(object);
      // Every level a slider can show is framed as the page opens, not only the parts.
      box.expandByObject(object);
      levels.push(object);
    }
    const label = element('label', {}, panel);
    const check = element('input', { type: 'checkbox', 'data-probe-toggle': probe.name }, label);
    check.checked = probe.shown;
    const swatch = element('span', { class: 'vs-swatch' }, label);
    swatch.style.background = cssColor(probe.srgb);
    const text = document.createTextNode('');
    label.appendChild(text);
    const slider = element('input', {
      type: 'range', class: 'vs-slider', min: 0, max: probe.values.length - 1, step: 1, 'data-probe': probe.name,
    }, panel);
    const entry = { probe, check, slider, levels, index: probe.initial };
    slider.value = String(entry.index);
    function update() {
      entry.index = Number(slider.value);
      levels.forEach((o, i) => (o.visible = check.checked && i === entry.index));
      text.textContent = `${probe.label} = ${probe.values[entry.index].toPrecision(4)}`;
      placeMarker();
      redraw();
    }
    slider.addEventListener('input', update);
    check.addEventListener('change', update);
    probes.push(entry);
    entry.update = update;
  }
  for (const p of probes) p.update();

  const size = box.getSize(new Vector3());
  const radius = Math.max(size.length() / 2, 1e-9);
  marker.scale.setScalar(radius / 40);

  // Display: wireframe and a clipping plane across the box along x, y or z.
  element('h2', { text: 'Display' }, panel);
  const wireLabel = element('label', {}, panel);
  const wireCheck = element('input', { type: 'checkbox', id: 'vs-wireframe' }, wireLabel);
  wireLabel.appendChild(document.createTextNode(' wireframe'));
  wireCheck.addEventListener('change', () => {
    wire.on = wireCheck.checked;
    for (const m of materials) {
      m.wireframe = wire.on;
      m.needsUpdate = true;
    }
    redraw();
  });
  const seeLabel = element('label', {}, panel);
  const seeCheck = element('input', { type: 'checkbox', id: 'vs-translucent' }, seeLabel);
  seeCheck.checked = seeThrough.on;
  seeLabel.appendChild(document.createTextNode(' parts see-through'));
  seeCheck.addEventListener('change', () => {
    seeThrough.on = seeCheck.checked;
    partMaterials.forEach(translucent);
    redraw();
  });
  const clipLabel = element('label', {}, panel);
  const clipCheck = element('input', { type: 'checkbox', id: 'vs-clip' }, clipLabel);
  clipLabel.appendChild(document.createTextNode(' clip along '));
  const clipAxis = element('select', { id: 'vs-clip-axis' }, clipLabel);
  for (const a of ['x', 'y', 'z']) element('option', { value: a, text: a }, clipAxis);
  clipAxis.value = 'z';
  const clipSlider = element('input', { type: 'range', class: 'vs-slider', id: 'vs-clip-offset', min: 0, max: 1000, value: 500 }, panel);
  function updateClip() {
    clipping.on = clipCheck.checked;
    const axis = { x: 0, y: 1, z: 2 }[clipAxis.value];
    const normal = new Vector3(0, 0, 0).setComponent(axis, -1);
    const t = Number(clipSlider.value) / 1000;
    const at = box.min.getComponent(axis) + t * (box.max.getComponent(axis) - box.min.getComponent(axis));
    clipPlane.set(normal, at);  // keeps the points with coordinate <= at
    for (const m of materials) {
      m.clippingPlanes = clipping.on ? [clipPlane] : [];
      m.needsUpdate = true;
    }
    redraw();
  }
  clipCheck.addEventListener('change', updateClip);
  clipAxis.addEventListener('change', updateClip);
  clipSlider.addEventListener('input', updateClip);

  if (data.color_bar) {
    const bar = data.color_bar;
    const strip = element('div', { id: 'vs-colorbar' }, view);
    const stops = bar.stops.map((c, i) => `${cssColor(c)} ${(100 * i) / (bar.stops.length - 1)}%`);
    strip.style.background = `linear-gradient(to top, ${stops.join(', ')})`;
    const labels = element('div', { id: 'vs-colorbar-labels' }, view);
    for (const v of [bar.max, (bar.min + bar.max) / 2, bar.min]) element('span', { text: Number(v).toPrecision(4) }, labels);
    element('div', { id: 'vs-colorbar-title', text: bar.title }, view);
  }

  element('h2', { text: 'Model' }, panel);
  infoList(data.info, element('div', { class: 'vs-info' }, panel));
  if (data.command) {
    element('h2', { text: 'Made by' }, panel);
    element('pre', { class: 'vs-command', text: data.command }, panel);
  }

  const center = box.getCenter(new Vector3());
  controls.target.copy(center);
  // The bounding sphere fits both ways: within the vertical angle and within the horizontal one
  // the canvas's shape gives (fitting the vertical angle alone cut the sides off a canvas taller
  // than wide: a narrow window, the browser test at 640 x 400).
  camera.aspect = view.clientWidth / Math.max(view.clientHeight, 1);
  const halfVertical = (camera.fov * Math.PI) / 360;
  const halfHorizontal = Math.atan(Math.tan(halfVertical) * camera.aspect);
  const distance = radius / Math.sin(Math.min(halfVertical, halfHorizontal));
  camera.position.copy(center).add(new Vector3(1.0, -1.6, 1.1).normalize().multiplyScalar(distance * 1.05));
  camera.up.set(0, 0, 1);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.update();
  draw();

  window.volsplinePage = {
    loadMilliseconds: performance.now() - started,
    readyAt: performance.now(),
    frames: () => frame,
    draw,
  };
  document.body.dataset.ready = '1';
}

main().catch((e) => {
  console.error(`volspline page: ${e && e.stack ? e.stack : e}`);
  document.body.dataset.ready = 'error';
});
