// The page of `sphaera view`: a mesh and the levels of its sphere-tree, drawn with
// three.js (inlined in the page, no network), and what else the CLI was asked for: other
// surfaces (simplification rungs, HAL approximations), the distance to another mesh as
// vertex colours, silhouette labels in grey levels. The data is the JSON element
// `#sphaera-data`, written by the CLI: typed arrays as base64 (little-endian).
// (Shared with the robot page, in `stage.js` before this script: THREE, `data`, the
// decoders `floats`, `integers`, `bytes`, the canvas, `renderer`, `scene` and `orbit`.)

function shape(arrays) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(floats(arrays.positions), 3));
  geometry.setIndex(new THREE.BufferAttribute(integers(arrays.triangles), 1));
  geometry.computeVertexNormals();
  return geometry;
}

const plainColour = new THREE.Color(0xb8c4d6);
const geometry = shape(data.mesh);
const vertexCount = geometry.getAttribute("position").count;
// Vertex colours, white until a colouring is chosen (the material multiplies them).
geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * vertexCount).fill(1), 3));
const meshMaterial = new THREE.MeshStandardMaterial({
  color: plainColour, roughness: 0.7, side: THREE.DoubleSide,
});
const mesh = new THREE.Mesh(geometry, meshMaterial);
scene.add(mesh);

// Other surfaces (`--simplify`, `--hal`), one shown at a time in place of the input.
const layers = data.layers.map((layer) => {
  const object = new THREE.Mesh(
    shape(layer),
    new THREE.MeshStandardMaterial({
      color: layer.kind === "simplified" ? 0xe0a458 : 0x7bb87a,
      roughness: 0.7, flatShading: true, side: THREE.DoubleSide,
    }),
  );
  object.visible = false;
  scene.add(object);
  return { ...layer, object };
});

// With `--hausdorff`: the other mesh as wires, and where the distance is largest.
let other = null;
let farthest = null;
if (data.distance) {
  other = new THREE.Mesh(
    shape(data.distance.other),
    new THREE.MeshBasicMaterial({ color: 0x444444, wireframe: true, transparent: true, opacity: 0.35 }),
  );
  other.visible = false;
  scene.add(other);
  farthest = new THREE.Group();
  const [fx, fy, fz] = data.distance.farthest;
  const [cx, cy, cz] = data.distance.closest;
  const marker = new THREE.Mesh(
    new THREE.SphereGeometry(0.018 * data.radius, 16, 8),
    new THREE.MeshBasicMaterial({ color: 0xff00aa, depthTest: false }),
  );
  marker.position.set(fx, fy, fz);
  marker.renderOrder = 2;
  const line = new THREE.Line(
    new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(fx, fy, fz), new THREE.Vector3(cx, cy, cz)]),
    new THREE.LineBasicMaterial({ color: 0xff00aa, depthTest: false }),
  );
  line.renderOrder = 2;
  farthest.add(marker, line);
  farthest.visible = false;
  scene.add(farthest);
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
  `${data.mesh.triangles_count.toLocaleString("en")} triangles, ${levels.length} levels, diagonal ${data.diagonal.toPrecision(4)}`;
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

// The surface shown: 0 the input, k the k-th of `data.layers`, each with its bound.
const surfaceMenu = document.getElementById("surface");
const surfaces = [
  { label: `input: ${data.mesh.triangles_count.toLocaleString("en")} triangles`, object: mesh,
    triangles_count: data.mesh.triangles_count, bound: null },
  ...layers.map((layer) => ({
    ...layer,
    label: `${layer.label}: ${layer.triangles_count.toLocaleString("en")} triangles`,
  })),
];
surfaces.forEach((surface, index) => {
  const option = document.createElement("option");
  option.value = String(index);
  option.textContent = surface.label;
  surfaceMenu.appendChild(option);
});
document.getElementById("surface-choice").hidden = layers.length === 0;
const boundName = { simplified: "certified error bound", hal_level: "widest lens", hal_tolerance: "widest lens" };
function showSurface(index) {
  const shown = document.getElementById("show-mesh").checked;
  surfaces.forEach((surface, k) => { surface.object.visible = shown && k === index; });
  const surface = surfaces[index];
  document.getElementById("surface-bound").textContent =
    index === 0 ? "" : `${boundName[surface.kind]} ${surface.bound === null ? "unbounded" : `${percent(surface.bound)} of the diagonal`}`;
  surfaceMenu.value = String(index);
  document.body.dataset.surface = String(index);
  document.body.dataset.drawnTriangles = String(shown ? surface.triangles_count : 0);
  render();
}
surfaceMenu.addEventListener("change", () => showSurface(Number(surfaceMenu.value)));
document.getElementById("show-mesh").addEventListener("change", () => showSurface(Number(surfaceMenu.value)));

// Colours of the input's vertices: plain, the distance to the other mesh, or the
// silhouette labels of the camera nearest the viewing direction.
const colourMenu = document.getElementById("colour");
const colourings = [["plain", "plain"]];
if (data.distance) colourings.push(["distance", `distance to ${data.distance.other_name}`]);
if (data.labels) colourings.push(["labels", "silhouette labels"]);
for (const [value, text] of colourings) {
  const option = document.createElement("option");
  option.value = value;
  option.textContent = text;
  colourMenu.appendChild(option);
}
document.getElementById("colour-choice").hidden = colourings.length === 1;
const colourAttribute = geometry.getAttribute("color");
const distanceColours = data.distance ? bytes(data.distance.colors) : null;
const labelDirections = data.labels ? floats(data.labels.directions) : null;
const labelGrey = data.labels ? bytes(data.labels.grey) : null;
let colouring = "plain";
let labelView = -1;

function setColours(source, stride) {
  const target = colourAttribute.array;
  for (let v = 0; v < vertexCount; v += 1) {
    for (let c = 0; c < 3; c += 1) {
      target[3 * v + c] = source[stride === 3 ? 3 * v + c : v] / 255;
    }
  }
  colourAttribute.needsUpdate = true;
}

// The view whose labels colour the mesh: the one nearest the direction toward the camera.
function nearestLabelView() {
  const d = camera.position.clone().normalize();
  let best = 0;
  let bestDot = -Infinity;
  for (let k = 0; k < data.labels.count; k += 1) {
    const dot = d.x * labelDirections[3 * k] + d.y * labelDirections[3 * k + 1] + d.z * labelDirections[3 * k + 2];
    if (dot > bestDot) { bestDot = dot; best = k; }
  }
  return best;
}

function updateLabels() {
  if (colouring !== "labels") return;
  const k = nearestLabelView();
  if (k === labelView) return;
  labelView = k;
  setColours(labelGrey.subarray(k * vertexCount, (k + 1) * vertexCount), 1);
  document.body.dataset.labelView = String(k);
}

function showColouring(value) {
  colouring = value;
  colourMenu.value = value;
  labelView = -1;
  const legend = document.getElementById("legend");
  legend.hidden = value === "plain";
  meshMaterial.vertexColors = value !== "plain";
  meshMaterial.color = value === "plain" ? plainColour : new THREE.Color(0xffffff);
  meshMaterial.needsUpdate = true;
  if (farthest) farthest.visible = value === "distance";
  if (value === "distance") {
    setColours(distanceColours, 3);
    document.getElementById("legend-bar").style.background =
      `linear-gradient(to right, ${data.distance.legend.join(", ")})`;
    document.getElementById("legend-low").textContent = "0";
    document.getElementById("legend-high").textContent = percent(data.distance.mesh_to_other_upper);
    document.getElementById("legend-note").textContent =
      `Each vertex's certified distance to ${data.distance.other_name}, in % of the diagonal. ` +
      `Hausdorff distance (certified): ${percent(data.distance.lower)} – ${percent(data.distance.upper)}, ` +
      `reached at the magenta mark (${data.distance.dominating === "mesh_to_other" ? "on this mesh" : "on the other mesh"}), ` +
      "its closest point at the line's other end.";
  } else if (value === "labels") {
    document.getElementById("legend-bar").style.background = "linear-gradient(to right, #000, #fff)";
    document.getElementById("legend-low").textContent = "0 (outline)";
    document.getElementById("legend-high").textContent = `${data.labels.scale.toFixed(1)} cells`;
    document.getElementById("legend-note").textContent =
      `Distance from the outline on the ${data.labels.resolution}² grid of the nearest of ${data.labels.count} cameras ` +
      `(every ${data.labels.step_degrees}°); turn the view to see the labels change.`;
  }
  if (value !== "plain" && Number(surfaceMenu.value) !== 0) showSurface(0);
  document.body.dataset.colour = value;
  if (value !== "labels") delete document.body.dataset.labelView;
  render();
}
colourMenu.addEventListener("change", () => showColouring(colourMenu.value));
if (other) {
  document.getElementById("other-choice").hidden = false;
  document.getElementById("other-name").textContent = `${data.distance.other_name} (wires)`;
  document.getElementById("show-other").addEventListener("change", (event) => {
    other.visible = event.target.checked;
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
const frame = orbit(camera, new THREE.Vector3(0, 0, 0), { azimuth: 0.6, elevation: 0.35, distance: 3.2 * data.radius }, () => render());

function render() {
  frame();
  if (data.labels) updateLabels();
  renderer.render(scene, camera);
}
// The address picks what is shown first (the browser test uses it): `#level=K`,
// `surface=S` (an index of the surface menu), `colour=plain|distance|labels`,
// `spheres=off`, joined by `&`.
const asked = new URLSearchParams(window.location.hash.slice(1));
const clamp = (text, last, otherwise) => {
  const value = Number.parseInt(text ?? "", 10);
  return Number.isInteger(value) ? Math.max(0, Math.min(value, last)) : otherwise;
};
const first = clamp(asked.get("level"), levels.length - 1, levels.length - 1);
slider.value = String(first);
showLevel(first);
showSurface(clamp(asked.get("surface"), surfaces.length - 1, 0));
if (asked.get("spheres") === "off") {
  const box = document.getElementById("show-spheres");
  box.checked = false;
  box.dispatchEvent(new Event("change"));
}
const colourAsked = asked.get("colour");
showColouring(colourings.some(([value]) => value === colourAsked) ? colourAsked : "plain");
document.body.dataset.loadMs = String(Math.round(performance.now()));
document.body.dataset.ready = "true";
