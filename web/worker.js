// armlab's web worker: the page has no threads, so the workspace's heavy computations (its
// statistics and the figure's map) run here, in a second instance of the same module, while the
// page keeps drawing. One request at a time: JSON in, JSON out (src/app/offload.rs).
import init, { worker_compute } from "./armlab.js";

const ready = init({ module_or_path: "./armlab_bg.wasm" });

self.onmessage = async (event) => {
  await ready;
  self.postMessage(worker_compute(event.data));
};
