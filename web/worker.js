// The render worker: its own engine, given the same files, scene and
// toggles as the page's, for the long jobs (a render, a compare, a ray
// log) so that the page never freezes. Messages are handled in order.
let call = null;
let queue = Promise.resolve();

async function handle(message) {
  if (message.type === "init") {
    call = await engine(message.module, {
      progress: (done, total) => postMessage({ type: "progress", done, total }),
      panicked: (text) => postMessage({ type: "panicked", message: text }),
    });
    return;
  }
  const started = performance.now();
  try {
    const reply = call(message.op, message.args, message.bytes);
    const transfer = reply instanceof Uint8Array ? [reply.buffer] : [];
    postMessage({ type: "reply", id: message.id, reply, ms: performance.now() - started }, transfer);
  } catch (error) {
    postMessage({
      type: "reply", id: message.id, error: String(error.message || error),
      trapped: !(error instanceof EngineError),
    });
  }
}

onmessage = (event) => { queue = queue.then(() => handle(event.data)); };
