// Hand-made glTF files for babylon_semantics.mjs: a triangle with N morph targets whose
// KHR_interactivity graph writes the values under test into the node's morph weights, so the page
// reads them back as influences.

/**
 * A glTF (JSON, embedded buffer) of one triangle with nTargets morph targets.
 * @param {number} nTargets
 * @param {object[]} [nodes] glTF nodes; node 0 holds the mesh (the default: [{mesh: 0}])
 * @param {number[]} [sceneNodes]
 */
export function triangle(nTargets, nodes = [{ mesh: 0 }], sceneNodes = [0]) {
  const floats = [0, 0, 0, 1, 0, 0, 0, 1, 0];
  for (let t = 0; t < nTargets; ++t) floats.push(0, 0, 1, 0, 0, 0, 0, 0, 0);
  const buffer = Buffer.from(new Float32Array(floats).buffer);
  const bufferViews = [];
  const accessors = [];
  for (let i = 0; i <= nTargets; ++i) {
    bufferViews.push({ buffer: 0, byteOffset: 36 * i, byteLength: 36 });
    const p = floats.slice(9 * i, 9 * i + 9);
    const range = (f) => [0, 1, 2].map((c) => f(p[c], p[c + 3], p[c + 6]));
    accessors.push({ bufferView: i, componentType: 5126, count: 3, type: 'VEC3', min: range(Math.min), max: range(Math.max) });
  }
  return {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: sceneNodes }],
    nodes,
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, targets: [...Array(nTargets).keys()].map((t) => ({ POSITION: t + 1 })) }],
      weights: new Array(nTargets).fill(0) }],
    buffers: [{ byteLength: buffer.length, uri: `data:application/octet-stream;base64,${buffer.toString('base64')}` }],
    bufferViews,
    accessors,
  };
}

/** Builds one KHR_interactivity graph: node 0 is event/onTick, node 1 the flow/sequence it starts. */
export class Graph {
  constructor() {
    /** @type {{signature: string}[]} */
    this.types = [];
    /** @type {{op: string}[]} */
    this.declarations = [];
    /** @type {object[]} */
    this.nodes = [];
    /** @type {object[] | undefined} the graph's variables (omitted when undefined) */
    this.variables = undefined;
    this.node('event/onTick', {}, undefined, { out: { node: 1, socket: 'in' } });
    this.node('flow/sequence');
  }
  /** @param {string} signature @returns {number} its index in types */
  type(signature) {
    let i = this.types.findIndex((t) => t.signature === signature);
    if (i < 0) i = this.types.push({ signature }) - 1;
    return i;
  }
  /**
   * Appends a node; returns its index.
   * @param {string} op
   * @param {object} [values] input value sockets: {node, socket} or a literal from lit()
   * @param {object} [configuration]
   * @param {object} [flows]
   */
  node(op, values = {}, configuration = undefined, flows = undefined) {
    let declaration = this.declarations.findIndex((d) => d.op === op);
    if (declaration < 0) declaration = this.declarations.push({ op }) - 1;
    const n = { declaration };
    if (Object.keys(values).length) n.values = values;
    if (configuration) n.configuration = configuration;
    if (flows) n.flows = flows;
    return this.nodes.push(n) - 1;
  }
  /** A literal input value. @param {string} signature @param {number|boolean|Array<number|boolean>} value */
  lit(signature, value) { return { value: Array.isArray(value) ? value : [value], type: this.type(signature) }; }
  /** An output socket of a node as an input value. */
  out(node, socket = 'value') { return { node, socket }; }
  /** A pointer/get node's index. */
  get(pointer, signature) {
    return this.node('pointer/get', {}, { pointer: { value: [pointer] }, type: { value: [this.type(signature)] } });
  }
  /**
   * Appends to the sequence one pointer/set per source: weight first + k of `target` (a pointer
   * prefix) := sources[k].
   * @param {object[]} sources
   * @param {string} [target]
   * @param {number} [first]
   */
  setWeights(sources, target = '/nodes/0/weights', first = 0) {
    const flows = this.nodes[1].flows || {};
    const start = Object.keys(flows).length;
    sources.forEach((source, k) => {
      const set = this.node('pointer/set', { value: source }, { pointer: { value: [`${target}/${first + k}`] }, type: { value: [this.type('float')] } });
      flows[String(start + k).padStart(4, '0')] = { node: set, socket: 'in' };
    });
    this.nodes[1].flows = flows;
  }
  /** Appends a flow node to the sequence. @param {number} node */
  then(node) {
    const flows = this.nodes[1].flows || {};
    flows[String(Object.keys(flows).length).padStart(4, '0')] = { node, socket: 'in' };
    this.nodes[1].flows = flows;
  }
  /** The glTF with this graph as its KHR_interactivity extension. */
  into(gltf) {
    const graph = { types: this.types, declarations: this.declarations, nodes: this.nodes };
    if (this.variables !== undefined) graph.variables = this.variables;
    return { ...gltf, extensionsUsed: ['KHR_interactivity'], extensions: { KHR_interactivity: { graphs: [graph], graph: 0 } } };
  }
}
