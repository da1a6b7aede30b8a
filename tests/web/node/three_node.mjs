// three.js's GLTFLoader in Node for the tests: Node has no image decoding (GLTFLoader reaches for
// `self.URL` and the DOM to decode a texture), and the tests check geometry, morph targets and
// weights, not pixels. A loader plugin therefore resolves every texture to null, which GLTFLoader
// treats as "no texture" (the material keeps its colour factor). The browser test
// (tests/web/browser) checks that the textures load.

/**
 * A GLTFLoader (the class passed in, from web/node_modules) that skips textures.
 * @template {new () => any} L
 * @param {L} GLTFLoader
 * @returns {InstanceType<L>}
 */
export function nodeGltfLoader(GLTFLoader) {
  const loader = new GLTFLoader();
  loader.register(() => ({ name: 'VDG_node_no_textures', loadTexture: () => Promise.resolve(null) }));
  return loader;
}
