// A small .glb reader for the Node tests: the JSON chunk, the BIN chunk and float accessors
// (dense or sparse, glTF 2.0 sections 3.6.2 and 3.6.2.3), independent of three.js's loader.
import { readFileSync } from 'node:fs';

/**
 * @param {string} path
 * @returns {{json: any, bin: Buffer}}
 */
export function readGlb(path) {
  const bytes = readFileSync(path);
  if (bytes.readUInt32LE(0) !== 0x46546c67) throw new Error(`${path}: not a .glb`);
  const jsonLength = bytes.readUInt32LE(12);
  const json = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
  const binStart = 20 + jsonLength;
  const binLength = bytes.readUInt32LE(binStart);
  return { json, bin: bytes.subarray(binStart + 8, binStart + 8 + binLength) };
}

const kComponents = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

/**
 * @param {{json: any, bin: Buffer}} glb
 * @param {number} viewIndex
 * @param {number} componentType
 * @param {number} count
 * @param {number} offset extra byte offset
 * @returns {Float64Array}
 */
function readView(glb, viewIndex, componentType, count, offset = 0) {
  const view = glb.json.bufferViews[viewIndex];
  const start = (view.byteOffset || 0) + offset;
  const out = new Float64Array(count);
  const size = { 5121: 1, 5123: 2, 5125: 4, 5126: 4 }[componentType];
  const stride = view.byteStride || size;
  for (let i = 0; i < count; ++i) {
    const at = start + i * stride;
    out[i] = componentType === 5126 ? glb.bin.readFloatLE(at)
      : componentType === 5121 ? glb.bin.readUInt8(at)
        : componentType === 5123 ? glb.bin.readUInt16LE(at) : glb.bin.readUInt32LE(at);
  }
  return out;
}

/**
 * The values of a float accessor (sparse accessors expanded over their zeros or base view).
 * @param {{json: any, bin: Buffer}} glb
 * @param {number} index
 * @returns {Float64Array}
 */
export function readAccessor(glb, index) {
  const acc = glb.json.accessors[index];
  const width = kComponents[/** @type {keyof typeof kComponents} */ (acc.type)];
  const n = acc.count * width;
  const out = acc.bufferView === undefined ? new Float64Array(n)
    : readView(glb, acc.bufferView, acc.componentType, n, acc.byteOffset || 0);
  if (acc.sparse) {
    const s = acc.sparse;
    const indices = readView(glb, s.indices.bufferView, s.indices.componentType, s.count, s.indices.byteOffset || 0);
    const values = readView(glb, s.values.bufferView, acc.componentType, s.count * width, s.values.byteOffset || 0);
    for (let i = 0; i < s.count; ++i) {
      for (let c = 0; c < width; ++c) out[indices[i] * width + c] = values[i * width + c];
    }
  }
  return out;
}
