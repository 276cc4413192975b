// armlab's web worker: the page has no threads, so the workspace's heavy computations (its
// statistics and the figure's map) run here, in a second instance of the same module, while the
// page keeps drawing. One request at a time: JSON in, partial maps and then the answer out, as JSON
// (src/offload.rs).
import init, { worker_compute } from "./armlab.js";

const ready = init({ module_or_path: "./armlab_bg.wasm" });

self.onmessage = async (event) => {
  await ready;
  // Partial maps (the figure as it forms) go to the page as they come, the answer last.
  self.postMessage(worker_compute(event.data, (partial) => self.postMessage(partial)));
};
