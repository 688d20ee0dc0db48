// The robot page of `sphaera view ROBOT.urdf`: every link's meshes and spheres, posed by
// the robot's forward kinematics as the joint sliders move (three.js, inlined, no
// network), links coloured by their certified protrusion, the self-collision pairs
// listed. The data is the JSON element `#sphaera-data`, written by the CLI: typed arrays
// as base64 (little-endian), lengths in page units (the robot's units divided by `scale`).
// (Shared with the mesh page, in `stage.js` before this script: THREE, `data`, the
// decoders `floats`, `integers`, the canvas, `renderer`, `scene` and `orbit`.)

// URDF robots stand on z: the robot turned so that z is up on the screen.
const robot = new THREE.Group();
robot.rotation.x = -Math.PI / 2;
scene.add(robot);

const unitSphere = new THREE.SphereGeometry(1, 20, 14);
const links = data.links.map((link) => {
  const group = new THREE.Group();
  group.matrixAutoUpdate = false;
  robot.add(group);
  const colour = new THREE.Color(link.colour);
  let mesh = null;
  if (link.mesh) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(floats(link.mesh.positions), 3));
    geometry.setIndex(new THREE.BufferAttribute(integers(link.mesh.triangles), 1));
    geometry.computeVertexNormals();
    mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: colour, roughness: 0.7, side: THREE.DoubleSide }));
    group.add(mesh);
  }
  const spheres = floats(link.spheres);
  const count = spheres.length / 4;
  let balls = null;
  if (count > 0) {
    balls = new THREE.InstancedMesh(unitSphere, new THREE.MeshStandardMaterial({
      color: colour, roughness: 0.5, transparent: true, opacity: 0.35, depthWrite: false,
    }), count);
    const m = new THREE.Matrix4();
    for (let k = 0; k < count; k += 1) {
      const r = spheres[4 * k + 3];
      m.makeScale(r, r, r).setPosition(spheres[4 * k], spheres[4 * k + 1], spheres[4 * k + 2]);
      balls.setMatrixAt(k, m);
    }
    balls.instanceMatrix.needsUpdate = true;
    group.add(balls);
  }
  return { ...link, group, mesh, balls, count, first: count > 0 ? new THREE.Vector3(spheres[0], spheres[1], spheres[2]) : null };
});
document.body.dataset.drawnSpheres = String(links.reduce((n, l) => n + l.count, 0));
document.body.dataset.joints = String(data.joints.length);

// Forward kinematics, as the CLI's: pose[child] = pose[parent] · origin · motion(value).
const origins = data.steps.map((step) => new THREE.Matrix4().fromArray(step.origin));
const axes = data.steps.map((step) => new THREE.Vector3(...step.axis));
const values = data.joints.map((joint) => joint.value);
const poses = Array.from({ length: data.link_count }, () => new THREE.Matrix4());

function pose() {
  poses.forEach((p) => p.identity());
  const motion = new THREE.Matrix4();
  data.steps.forEach((step, s) => {
    const source = step.source;
    const value = source ? source.multiplier * values[source.joint] + source.offset : 0;
    if (step.kind === "rotate") motion.makeRotationAxis(axes[s], value);
    else if (step.kind === "slide") motion.makeTranslation(axes[s].clone().multiplyScalar(value / data.scale));
    else motion.identity();
    poses[step.child].copy(poses[step.parent]).multiply(origins[s]).multiply(motion);
  });
  links.forEach((link) => {
    link.group.matrix.copy(poses[link.index]);
    link.group.matrixWorldNeedsUpdate = true;
  });
  // Where each link's first sphere is, in the robot's units: the browser test compares
  // it with the CLI's kinematics.
  document.body.dataset.probe = links
    .filter((link) => link.first)
    .map((link) => {
      const p = link.first.clone().applyMatrix4(poses[link.index]).multiplyScalar(data.scale);
      return `${link.name}:${p.x.toFixed(6)},${p.y.toFixed(6)},${p.z.toFixed(6)}`;
    })
    .join(";");
  document.body.dataset.values = values.map((v) => v.toFixed(6)).join(",");
}

// The panel.
document.getElementById("title").textContent = data.name;
document.getElementById("facts").textContent =
  `${data.links.length} links with spheres, ${data.joints.length} joints, ` +
  `${document.body.dataset.drawnSpheres} spheres, coverage of every link certified`;
const jointsPanel = document.getElementById("joints");
const sliders = data.joints.map((joint, j) => {
  const label = document.createElement("label");
  const name = document.createElement("span");
  name.textContent = joint.name;
  const shown = document.createElement("span");
  shown.className = "joint-value";
  const slider = document.createElement("input");
  slider.type = "range";
  slider.min = String(joint.lower);
  slider.max = String(joint.upper);
  slider.step = String(Math.max((joint.upper - joint.lower) / 1000, 1e-9));
  slider.value = String(joint.value);
  const update = () => { shown.textContent = values[j].toFixed(3); };
  slider.addEventListener("input", () => {
    values[j] = Number(slider.value);
    update();
    pose();
    render();
  });
  update();
  label.append(name, shown, slider);
  jointsPanel.append(label);
  return { slider, update };
});
const linkRows = document.querySelector("#links tbody");
links.forEach((link) => {
  const row = document.createElement("tr");
  const name = document.createElement("td");
  const swatch = document.createElement("span");
  swatch.className = "swatch";
  swatch.style.background = link.colour;
  name.append(swatch, document.createTextNode(link.name));
  const count = document.createElement("td");
  count.textContent = String(link.count);
  const worst = document.createElement("td");
  worst.textContent = `${(1000 * link.worst_protrusion).toFixed(1)} mm`;
  row.append(name, count, worst);
  linkRows.append(row);
});
const c = data.self_collision;
document.getElementById("collision-summary").textContent =
  `${c.pairs.length} pairs: ${c.counts.Adjacent} adjacent, ${c.counts.Default} in contact at the default configuration, ` +
  `${c.counts.Always} always and ${c.counts.Never} never in contact over ${c.samples} random configurations left out; ` +
  `${c.checked} for the planner to check.`;
const pairRows = document.querySelector("#pairs tbody");
c.pairs.filter((pair) => pair.reason).forEach((pair) => {
  const row = document.createElement("tr");
  for (const text of [pair.first, pair.second, pair.reason]) {
    const cell = document.createElement("td");
    cell.textContent = text;
    row.append(cell);
  }
  pairRows.append(row);
});
document.body.dataset.disabledPairs = String(pairRows.children.length);
const toggle = (id, part) => document.getElementById(id).addEventListener("change", (event) => {
  links.forEach((link) => { if (link[part]) link[part].visible = event.target.checked; });
  render();
});
toggle("show-meshes", "mesh");
toggle("show-spheres", "balls");

// The camera turns around the robot's middle: drag to turn, wheel to zoom.
const target = new THREE.Vector3(data.target[0], data.target[2], -data.target[1]);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 100);
const frame = orbit(camera, target, { azimuth: 0.8, elevation: 0.3, distance: 3.4 }, () => render());

function render() {
  frame();
  renderer.render(scene, camera);
}
// The address may set the joints (the browser test uses it): `#q=v1,v2,…` in the order
// of the sliders, each clamped to its range.
const asked = new URLSearchParams(window.location.hash.slice(1)).get("q");
if (asked) {
  asked.split(",").forEach((text, j) => {
    const value = Number(text);
    if (j < values.length && Number.isFinite(value)) {
      const joint = data.joints[j];
      values[j] = Math.max(joint.lower, Math.min(joint.upper, value));
      sliders[j].slider.value = String(values[j]);
      sliders[j].update();
    }
  });
}
pose();
render();
document.body.dataset.loadMs = String(Math.round(performance.now()));
document.body.dataset.ready = "true";
