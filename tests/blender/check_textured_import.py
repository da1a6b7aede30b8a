"""Blender imports a textured vdg export as vdg means it (run by run_blender_check.sh).

blender -b --factory-startup --python check_textured_import.py -- EXPORT.glb|.gltf SPOT_DIR

SPOT_DIR holds the model the export came from (examples/spot: spot.vdg.json, its base OBJ and
texture). Checks, each printed as a "check:" line, any failure an exception (exit 1):
  - an image texture node feeds the Principled BSDF's Base Color, its image the texture's size;
  - every imported vertex lies on a base vertex and every base vertex is imported (Blender keeps
    the export's seam splits; glTF's +Y up is Blender's +Z: (x, y, z) -> (x, -z, y));
  - the shape keys are the Basis and the model's keys, by name, in key order, and each puts every
    imported vertex where the key's mesh has its base vertex.
"""
import json
import os
import struct
import sys

import bpy
from mathutils import kdtree

POSITION_TOL = 1e-5  # float32 positions of a model about 1 unit across, after Blender's axis swap


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:]
    if len(argv) != 2:
        raise SystemExit("usage: blender -b --python check_textured_import.py -- EXPORT SPOT_DIR")
    return argv


def obj_positions(path):
    out = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("v "):
                out.append(tuple(float(x) for x in line.split()[1:4]))
    return out


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        raise AssertionError(f"{path}: not a PNG")
    return struct.unpack(">II", head[16:24])


def upstream_image(socket, depth=0):
    """The image texture node feeding `socket`, through at most a few other nodes."""
    for link in socket.links:
        node = link.from_node
        if node.type == "TEX_IMAGE":
            return node
        if depth < 3:
            for inp in node.inputs:
                found = upstream_image(inp, depth + 1)
                if found:
                    return found
    return None


def main():
    export, spot_dir = arguments()
    with open(os.path.join(spot_dir, "spot.vdg.json"), encoding="utf-8") as f:
        manifest = json.load(f)
    base = obj_positions(os.path.join(spot_dir, manifest["base"]))
    key_names = [k["name"] for k in manifest["keys"]]
    texture_size = png_size(os.path.join(spot_dir, "spot_texture.png"))

    bpy.ops.wm.read_factory_settings(use_empty=True)
    # SMOOTH shading: vdg's normals are smooth vertex normals, and the importer's default guess
    # ("NORMALS") uses numpy.bool, which Debian's numpy 1.24 no longer has.
    bpy.ops.import_scene.gltf(filepath=export, import_shading="SMOOTH")
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if len(meshes) != 1:
        raise AssertionError(f"expected one mesh object, got {len(meshes)}")
    obj = meshes[0]

    # The material: Principled BSDF with an image texture on Base Color.
    material = obj.active_material
    if material is None or not material.use_nodes:
        raise AssertionError("the mesh has no node material")
    bsdf = next((n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        raise AssertionError(f"material '{material.name}' has no Principled BSDF")
    image_node = upstream_image(bsdf.inputs["Base Color"])
    if image_node is None or image_node.image is None:
        raise AssertionError("no image texture feeds the Principled BSDF's Base Color")
    size = tuple(image_node.image.size)
    if size != tuple(texture_size):
        raise AssertionError(f"image '{image_node.image.name}' is {size}, the texture {texture_size}")
    metallic = bsdf.inputs["Metallic"].default_value
    if metallic != 0.0:
        raise AssertionError(f"metallic is {metallic}, expected 0 (a dielectric)")
    print(f"check: material '{material.name}': image texture {size[0]}x{size[1]} -> Base Color, metallic 0")

    # Positions: the imported vertices (seams split) and the base's, as two sets, to POSITION_TOL.
    verts = [(v.co.x, v.co.z, -v.co.y) for v in obj.data.vertices]  # back to glTF's +Y up
    tree = kdtree.KDTree(len(base))
    for i, p in enumerate(base):
        tree.insert(p, i)
    tree.balance()
    worst, hit, base_of = 0.0, set(), []
    for p in verts:
        _, index, dist = tree.find(p)
        worst = max(worst, dist)
        hit.add(index)
        base_of.append(index)
    if worst > POSITION_TOL:
        raise AssertionError(f"an imported vertex lies {worst:.3g} from every base vertex (tolerance {POSITION_TOL})")
    if len(hit) != len(base):
        raise AssertionError(f"{len(base) - len(hit)} of {len(base)} base vertices have no imported vertex")
    print(f"check: {len(verts)} imported vertices on the {len(base)} base vertices (worst {worst:.2g})")

    # Shape keys: Basis, then the keys by name.
    keys = obj.data.shape_keys
    names = [kb.name for kb in keys.key_blocks] if keys else []
    if names != ["Basis"] + key_names:
        raise AssertionError(f"shape keys {names}, expected {['Basis'] + key_names}")
    # Each shape key moves every imported vertex (split copies alike) to its base vertex's place in
    # the key's mesh.
    worst = 0.0
    for k, key in enumerate(manifest["keys"]):
        key_positions = obj_positions(os.path.join(spot_dir, key["mesh"]))
        data = keys.key_blocks[k + 1].data
        for i, b in enumerate(base_of):
            co = data[i].co
            q = key_positions[b]
            worst = max(worst, abs(co.x - q[0]), abs(co.z - q[1]), abs(-co.y - q[2]))
    if worst > POSITION_TOL:
        raise AssertionError(f"a shape key's vertex lies {worst:.3g} from its key mesh's (tolerance {POSITION_TOL})")
    print(f"check: shape keys {names[1:]} at their key meshes' positions (worst {worst:.2g})")


main()
