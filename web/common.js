"use strict";
// Shared by the page and its render worker: unpacking what the page
// embeds, and calling the engine. Every number and sentence the page shows
// comes back from these calls; the script only lays them out.

/** base64 of gzip (web/assemble.py's `packed`) -> bytes. */
async function unpack(base64) {
  const binary = atob(base64);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/** An error the engine answered with: its message is the command line's. */
class EngineError extends Error {}

/** Instantiates the engine; `hooks.progress(done, total)` hears a
 * render's rows, `hooks.panicked(message)` a panic before the trap. */
async function engine(module, hooks) {
  let memory = null;
  const decoder = new TextDecoder();
  const instance = await WebAssembly.instantiate(module, {
    env: {
      raystep_progress: (done, total) => hooks.progress(done, total),
      raystep_panicked: (start, length) =>
        hooks.panicked(decoder.decode(new Uint8Array(memory.buffer, start, length))),
    },
  });
  const e = instance.exports;
  memory = e.memory;
  const encoder = new TextEncoder();
  const put = (bytes) => {
    const start = e.raystep_alloc(bytes.length);
    new Uint8Array(e.memory.buffer, start, bytes.length).set(bytes);
    return start;
  };
  /** call(op, args, bytes) -> JSON, text or bytes; throws EngineError. */
  return function call(op, args, bytes) {
    const parts = [encoder.encode(op), encoder.encode(JSON.stringify(args || {})),
                   bytes || new Uint8Array(0)];
    const starts = parts.map(put);
    let kind;
    try {
      kind = e.raystep_call(starts[0], parts[0].length, starts[1], parts[1].length,
                            starts[2], parts[2].length);
    } finally {
      parts.forEach((p, i) => e.raystep_free(starts[i], p.length));
    }
    const reply = new Uint8Array(e.memory.buffer, e.raystep_reply(), e.raystep_reply_length()).slice();
    switch (kind) {
      case 0: return JSON.parse(decoder.decode(reply));
      case 1: return decoder.decode(reply);
      case 2: return reply;
      default: throw new EngineError(decoder.decode(reply));
    }
  };
}
