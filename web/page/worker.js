// The WebAssembly engine's Web Worker: it carries the page's messages to
// lumiere's viewer session (compiled to WebAssembly in ./pkg/) and its replies
// back, so the rendering never blocks the page.

import init, { Engine } from './pkg/lumiere_web.js';
import { idOf } from './protocol.js';

let engine = null;
let failure = null;
let ticking = false;

// Messages that come in while the WebAssembly module is compiling wait in this
// chain, in order; the handler is set first so none is lost.
let queue = init().then(
  () => {
    engine = new Engine();
  },
  (error) => {
    failure = `the WebAssembly engine could not start: ${error?.message ?? error}`;
  },
);

self.onmessage = (event) => {
  queue = queue.then(() => handle(event.data));
};

/** One message from the page: its replies go back, then any solve goes on. */
function handle(data) {
  if (!engine) {
    postError(idOf(data), failure ?? 'the WebAssembly engine is not running');
    return;
  }
  try {
    const replies = typeof data === 'string'
      ? engine.handle_text(data)
      : engine.handle_binary(new Uint8Array(data));
    post(replies);
  } catch (error) {
    // A panic leaves the WebAssembly instance unusable: say so once for every
    // message from now on.
    failure = `the WebAssembly engine stopped: ${error?.message ?? error}`;
    engine = null;
    postError(idOf(data), failure);
    return;
  }
  keepTicking();
}

/**
 * While the session has work left (a radiosity solve brightening), one tick
 * at a time from a setTimeout(0) loop: a message from the page gets in
 * between two ticks, so a move is never stuck behind a solve.
 */
function keepTicking() {
  if (ticking || !engine || !engine.busy()) return;
  ticking = true;
  setTimeout(() => {
    ticking = false;
    if (!engine || !engine.busy()) return;
    try {
      post(engine.tick());
    } catch (error) {
      failure = `the WebAssembly engine stopped: ${error?.message ?? error}`;
      engine = null;
      postError(null, failure);
      return;
    }
    keepTicking();
  }, 0);
}

/** Replies to the page: strings as they are, bytes by moving their buffer. */
function post(replies) {
  for (const reply of replies) {
    if (typeof reply === 'string') {
      self.postMessage(reply);
    } else {
      const whole = reply.byteOffset === 0 && reply.byteLength === reply.buffer.byteLength;
      const buffer = whole ? reply.buffer : reply.slice().buffer;
      self.postMessage(buffer, [buffer]);
    }
  }
}

function postError(id, message) {
  self.postMessage(JSON.stringify({ type: 'error', id, message }));
}
