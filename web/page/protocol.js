// The viewer's messages as bytes (docs/viewer-protocol.md).
//
// A message is text (one JSON object) or binary: a little-endian u32 header
// length, the header (one JSON object, UTF-8), then a payload whose layout the
// header's `type` gives. Both engines speak this; the page never knows which.

const encoder = new TextEncoder();
const decoder = new TextDecoder();

/** A text message: one JSON object. */
export function encodeText(message) {
  return JSON.stringify(message);
}

/** A binary message of `header` (an object) and `payload` (bytes). */
export function encodeBinary(header, payload = new Uint8Array(0)) {
  const head = encoder.encode(JSON.stringify(header));
  const bytes = new Uint8Array(4 + head.length + payload.length);
  new DataView(bytes.buffer).setUint32(0, head.length, true);
  bytes.set(head, 4);
  bytes.set(payload, 4 + head.length);
  return bytes;
}

/**
 * An `open-files` message: the header lists the files' names and sizes, the
 * payload is their bytes one after another, in the same order.
 */
export function encodeOpenFiles(id, files, main, sets = []) {
  const header = {
    type: 'open-files',
    id,
    main,
    files: files.map((f) => ({ name: f.name, size: f.bytes.length })),
    sets,
  };
  const size = files.reduce((sum, f) => sum + f.bytes.length, 0);
  const payload = new Uint8Array(size);
  let at = 0;
  for (const f of files) {
    payload.set(f.bytes, at);
    at += f.bytes.length;
  }
  return encodeBinary(header, payload);
}

/**
 * A message as the page uses it: a text message becomes its object, a binary
 * one `{header, payload}` with the payload a view into the same bytes (no copy:
 * a frame can be megabytes).
 */
export function decode(data) {
  if (typeof data === 'string') return JSON.parse(data);
  const bytes = data instanceof Uint8Array ? data : new Uint8Array(data);
  if (bytes.length < 4) throw new Error(`a binary message of ${bytes.length} bytes has no header length`);
  const length = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength).getUint32(0, true);
  if (4 + length > bytes.length) throw new Error(`a header of ${length} bytes in a message of ${bytes.length}`);
  const header = JSON.parse(decoder.decode(bytes.subarray(4, 4 + length)));
  return { header, payload: bytes.subarray(4 + length) };
}

/** The `type` and `id` of a decoded message, text or binary alike. */
export function typeAndId(message) {
  const fields = message.header ?? message;
  return { type: fields.type, id: fields.id ?? null };
}

/** The `id` a raw message (string or bytes) carries, or null if it cannot be read. */
export function idOf(data) {
  try {
    return typeAndId(decode(data)).id;
  } catch {
    return null;
  }
}
