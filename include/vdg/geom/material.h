// Materials of a mesh: a base colour per surface, optionally modulated by a texture.
//
// Colours here are display values in [0, 1] (what an 8-bit image or the framebuffer holds, i.e.
// sRGB-encoded), the values the paper's lighting equation (Rademacher 99, section 3.2.4) takes as
// Cbase: vdg's renderer, like the paper's OpenGL, shades and writes them without a colour-space
// conversion. Readers of formats that store linear factors (glTF baseColorFactor) encode them.
//
// A texture is decoded pixel data, not a file: readers (vdg/io) decode PNG or JPEG with their
// size limits; the mathematics never opens a file.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vdg {

// RGBA8 pixels, row-major, top row first (as image files store them), width * height * 4 bytes.
// Texture coordinates (TriMesh::uvs) have their origin at the bottom-left: (u, v) = (0, 0) is the
// first pixel of the *last* row.
struct TextureImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  // The PNG or JPEG file the pixels were decoded from, when a reader kept it (exports write these
  // bytes as they are instead of re-encoding the pixels); empty otherwise.
  std::string file_bytes;
};

struct Material {
  std::string name;                          // as the file names it (messages, `vdg info`)
  std::array<float, 3> base_color{1, 1, 1};  // display RGB in [0, 1]; multiplies the texture
  std::string texture_path;                  // the texture as the file names it; empty: none
  // Decoded texture, shared between copies of the mesh; null when there is none or it could not
  // be loaded (the reader then warned, and the surface shows base_color alone).
  std::shared_ptr<const TextureImage> texture;
};

}  // namespace vdg
