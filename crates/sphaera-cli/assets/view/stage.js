// What every `sphaera view` page shares, put before the page's own script: three.js
// (inlined in the page, no network), the console-error counter the browser test reads,
// the base64 decoders of the page's typed arrays (little-endian), the canvas, renderer,
// scene and lights, and a camera that turns around a point (drag to turn, wheel to zoom).
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

function bytes(base64) {
  return Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
}
const floats = (base64) => new Float32Array(bytes(base64).buffer);
const integers = (base64) => new Uint32Array(bytes(base64).buffer);

const canvas = document.getElementById("view");
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f5f7);
scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(1, 2, 3);
scene.add(sun);

// A camera turning around `target` at `distance`: `draw` is called whenever it moves; the
// page's render calls `frame()` to size the drawing and place the camera.
function orbit(camera, target, view, draw) {
  let { azimuth, elevation, distance } = view;
  let dragging = null;
  canvas.addEventListener("pointerdown", (event) => { dragging = { x: event.clientX, y: event.clientY }; });
  window.addEventListener("pointerup", () => { dragging = null; });
  window.addEventListener("pointermove", (event) => {
    if (!dragging) return;
    azimuth -= 0.01 * (event.clientX - dragging.x);
    elevation = Math.max(-1.5, Math.min(1.5, elevation + 0.01 * (event.clientY - dragging.y)));
    dragging = { x: event.clientX, y: event.clientY };
    draw();
  });
  canvas.addEventListener("wheel", (event) => {
    event.preventDefault();
    distance *= Math.exp(0.001 * event.deltaY);
    draw();
  }, { passive: false });
  window.addEventListener("resize", draw);
  return function frame() {
    const width = window.innerWidth;
    const height = window.innerHeight;
    renderer.setSize(width, height, false);
    camera.aspect = width / Math.max(1, height);
    camera.updateProjectionMatrix();
    camera.position.set(
      target.x + distance * Math.cos(elevation) * Math.sin(azimuth),
      target.y + distance * Math.sin(elevation),
      target.z + distance * Math.cos(elevation) * Math.cos(azimuth),
    );
    camera.lookAt(target);
  };
}
