// The two engines the page can talk to, with one interface:
//
//   engine.send(message)    an object goes as text JSON; `{header, payload}`
//                           or bytes (Uint8Array, ArrayBuffer) go as binary
//   engine.onreply(reply)   each reply, decoded: an object for text,
//                           `{header, payload}` for binary
//   engine.onfail(message)  the engine is gone (a worker that did not start,
//                           a server that stopped); nothing more will come
//   engine.name             'worker' or 'socket'
//   engine.native           whether `quit` means something (the server ends)
//
// Both carry the same messages to the same lumiere::viewer::Session.

import { decode, encodeBinary, encodeText } from './protocol.js';

/** What `send` puts on the wire: a string, or bytes. */
function wire(message) {
  if (message instanceof ArrayBuffer) return new Uint8Array(message);
  if (ArrayBuffer.isView(message)) return new Uint8Array(message.buffer, message.byteOffset, message.byteLength);
  if (message.header && message.payload) return encodeBinary(message.header, message.payload);
  return encodeText(message);
}

class BaseEngine {
  constructor(name, native) {
    this.name = name;
    this.native = native;
    this.failed = null;
    this.onreply = () => {};
    this.onfail = () => {};
  }

  /** A reply as it came (string or bytes), decoded for the page. */
  receive(data) {
    let reply;
    try {
      reply = decode(data);
    } catch (error) {
      reply = { type: 'error', id: null, message: `a reply that cannot be read: ${error.message}` };
    }
    this.onreply(reply);
  }

  fail(message) {
    if (this.failed) return;
    this.failed = message;
    this.onfail(message);
  }
}

/** lumiere compiled to WebAssembly, in a Web Worker (worker.js). */
export class WorkerEngine extends BaseEngine {
  constructor(url = './worker.js') {
    super('worker', false);
    this.worker = new Worker(new URL(url, import.meta.url), { type: 'module' });
    this.worker.onmessage = (event) => this.receive(event.data);
    // A module that does not load (no ./pkg/ built) only shows up here.
    this.worker.onerror = (event) => {
      event.preventDefault();
      this.fail(`the WebAssembly engine could not start: ${event.message || 'its module did not load'}`);
    };
  }

  send(message) {
    const data = wire(message);
    if (typeof data === 'string') {
      this.worker.postMessage(data);
    } else {
      // Moved, not copied: a copy of the bytes, so the caller's stay usable.
      const buffer = data.slice().buffer;
      this.worker.postMessage(buffer, [buffer]);
    }
  }
}

/** The native library behind `lumiere view`, over a WebSocket on this host. */
export class SocketEngine extends BaseEngine {
  constructor(url = (location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/socket') {
    super('socket', true);
    this.waiting = []; // messages sent before the socket opened
    this.socket = new WebSocket(url);
    this.socket.binaryType = 'arraybuffer';
    this.socket.onopen = () => {
      for (const data of this.waiting) this.socket.send(data);
      this.waiting = [];
    };
    this.socket.onmessage = (event) => this.receive(event.data);
    this.socket.onclose = () => this.fail('the lumiere server has stopped');
  }

  send(message) {
    const data = wire(message);
    if (this.socket.readyState === WebSocket.CONNECTING) this.waiting.push(data);
    else if (this.socket.readyState === WebSocket.OPEN) this.socket.send(data);
    else this.fail('the lumiere server has stopped');
  }
}

/** The engine the URL asks for: `engine=socket` for the server, else the worker. */
export function engineFor(params) {
  return params.get('engine') === 'socket' ? new SocketEngine() : new WorkerEngine();
}
