// The page of `sphaera view`: a mesh and the levels of its sphere-tree, drawn with
// three.js (inlined in the page, no network). The data is the JSON element
// `#sphaera-data`, written by the CLI: typed arrays as base64 (little-endian).
import * as THREE from "three";

// Errors reported on the console (three.js reports WebGL failures there) are counted on
// the body, where the browser test reads them.
let consoleErrors = 0;
const reportError = console.error.bind(console);
console.error = (...args) => {
  consoleErrors += 1;
  document.body.dataset.consoleErrors = String(consoleErrors);
  reportError(...args);
};
window.addEventListener("error", () => {
  consoleErrors += 1;
  document.body.dataset.consoleErrors = String(consoleErrors);
});

const data = JSON.parse(document.getElementById("sphaera-data").textContent);

function floats(base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}

function integers(base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  return new Uint32Array(bytes.buffer);
}

// The scene: the mesh, centred on the origin by the CLI, and a light rig.
const canvas = document.getElementById("view");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f5f7);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(1, 2, 3);
scene.add(sun);

const geometry = new THREE.BufferGeometry();
geometry.setAttribute("position", new THREE.BufferAttribute(floats(data.positions), 3));
geometry.setIndex(new THREE.BufferAttribute(integers(data.triangles), 1));
geometry.computeVertexNormals();
const mesh = new THREE.Mesh(
  geometry,
  new THREE.MeshStandardMaterial({ color: 0xb8c4d6, roughness: 0.7, side: THREE.DoubleSide }),
);
scene.add(mesh);

// With `--simplify`: the simplified mesh, shown instead of the input when asked for.
let simplified = null;
if (data.simplified) {
  const shape = new THREE.BufferGeometry();
  shape.setAttribute("position", new THREE.BufferAttribute(floats(data.simplified.positions), 3));
  shape.setIndex(new THREE.BufferAttribute(integers(data.simplified.triangles), 1));
  shape.computeVertexNormals();
  simplified = new THREE.Mesh(
    shape,
    new THREE.MeshStandardMaterial({ color: 0xe0a458, roughness: 0.7, flatShading: true, side: THREE.DoubleSide }),
  );
  simplified.visible = false;
  scene.add(simplified);
}

// The spheres of the level shown: one instanced mesh sized for the largest level, and
// the level's worst sphere on its own, in red.
const levels = data.levels.map((level) => ({ ...level, spheres: floats(level.spheres) }));
const most = Math.max(1, ...levels.map((level) => level.count));
const unitSphere = new THREE.SphereGeometry(1, 32, 16);
const spheres = new THREE.InstancedMesh(
  unitSphere,
  new THREE.MeshStandardMaterial({ color: 0x3b7dd8, transparent: true, opacity: 0.28, depthWrite: false }),
  most,
);
spheres.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
scene.add(spheres);
const worst = new THREE.Mesh(
  unitSphere,
  new THREE.MeshStandardMaterial({ color: 0xd8363b, transparent: true, opacity: 0.45, depthWrite: false }),
);
scene.add(worst);

const matrix = new THREE.Matrix4();
function showLevel(index) {
  const level = levels[index];
  for (let k = 0; k < level.count; k += 1) {
    const [x, y, z, r] = level.spheres.subarray(4 * k, 4 * k + 4);
    matrix.makeScale(r, r, r).setPosition(x, y, z);
    spheres.setMatrixAt(k, matrix);
  }
  spheres.count = level.count;
  spheres.instanceMatrix.needsUpdate = true;
  const w = level.spheres.subarray(4 * level.worst, 4 * level.worst + 4);
  worst.position.set(w[0], w[1], w[2]);
  worst.scale.setScalar(w[3]);
  document.getElementById("level-label").textContent = `${index}: ${level.count} spheres`;
  for (const row of document.querySelectorAll("#levels tbody tr")) {
    row.classList.toggle("current", Number(row.dataset.level) === index);
  }
  // What the browser test reads back.
  document.body.dataset.level = String(index);
  document.body.dataset.drawnSpheres = String(spheres.visible ? level.count : 0);
  render();
}

// The side panel: the mesh's facts and every level's certified error.
document.getElementById("title").textContent = data.name;
document.getElementById("facts").textContent =
  `${data.triangles_count.toLocaleString("en")} triangles, ${levels.length} levels, diagonal ${data.diagonal.toPrecision(4)}`;
const percent = (value) => (value === null ? "—" : `${((100 * value) / data.diagonal).toFixed(3)} %`);
const body = document.querySelector("#levels tbody");
levels.forEach((level, index) => {
  const row = document.createElement("tr");
  row.dataset.level = String(index);
  const error = level.error_upper === null ? "—" : `${percent(level.error_lower)} – ${percent(level.error_upper)}`;
  for (const text of [String(index), String(level.count), error]) {
    const cell = document.createElement("td");
    cell.textContent = text;
    row.appendChild(cell);
  }
  row.addEventListener("click", () => { slider.value = String(index); showLevel(index); });
  body.appendChild(row);
});

const slider = document.getElementById("level");
slider.max = String(levels.length - 1);
slider.value = String(levels.length - 1);
slider.addEventListener("input", () => showLevel(Number(slider.value)));
document.getElementById("show-mesh").addEventListener("change", (event) => {
  mesh.visible = event.target.checked;
  render();
});
if (simplified) {
  const label = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox";
  box.id = "show-simplified";
  label.appendChild(box);
  label.append(
    ` simplified: ${data.simplified.triangles_count.toLocaleString("en")} triangles, certified bound ${percent(data.simplified.error_bound)}`,
  );
  document.getElementById("show-spheres").parentElement.after(label);
  box.addEventListener("change", () => {
    simplified.visible = box.checked;
    mesh.visible = !box.checked && document.getElementById("show-mesh").checked;
    render();
  });
}
document.getElementById("show-spheres").addEventListener("change", (event) => {
  spheres.visible = event.target.checked;
  worst.visible = event.target.checked;
  showLevel(Number(slider.value));
});

// The camera turns around the origin: drag to turn, wheel to zoom.
const camera = new THREE.PerspectiveCamera(40, 1, data.radius / 100, data.radius * 100);
let azimuth = 0.6;
let elevation = 0.35;
let distance = 3.2 * data.radius;
function place() {
  camera.position.set(
    distance * Math.cos(elevation) * Math.sin(azimuth),
    distance * Math.sin(elevation),
    distance * Math.cos(elevation) * Math.cos(azimuth),
  );
  camera.lookAt(0, 0, 0);
}
let dragging = null;
canvas.addEventListener("pointerdown", (event) => { dragging = { x: event.clientX, y: event.clientY }; });
window.addEventListener("pointerup", () => { dragging = null; });
window.addEventListener("pointermove", (event) => {
  if (!dragging) return;
  azimuth -= 0.01 * (event.clientX - dragging.x);
  elevation = Math.max(-1.5, Math.min(1.5, elevation + 0.01 * (event.clientY - dragging.y)));
  dragging = { x: event.clientX, y: event.clientY };
  render();
});
canvas.addEventListener("wheel", (event) => {
  event.preventDefault();
  distance *= Math.exp(0.001 * event.deltaY);
  render();
}, { passive: false });

function render() {
  const width = window.innerWidth;
  const height = window.innerHeight;
  renderer.setSize(width, height, false);
  camera.aspect = width / Math.max(1, height);
  camera.updateProjectionMatrix();
  place();
  renderer.render(scene, camera);
}
window.addEventListener("resize", render);
// `#level=K` in the address picks the level shown first (the browser test uses it).
const asked = /level=(\d+)/.exec(window.location.hash);
const first = asked ? Math.min(Number(asked[1]), levels.length - 1) : levels.length - 1;
slider.value = String(first);
showLevel(first);
document.body.dataset.ready = "true";
