#!/usr/bin/env python3
"""strata's pt against Blender's Cycles (Debian's `blender`) on the same glTF file.

Writes a small textured glTF scene (a checker-textured floor, a box with a colour-ramp texture, a
plain box, a double-sided emissive quad over them, a constant sky in extras.strata.environment),
renders it with `stratad render --method pt` and with Cycles (imported by Blender's glTF importer),
and compares the two linear EXRs: the mean per channel over the image and over a 4 x 4 grid of
tiles. The materials are Lambert (metallic 0, roughness 1, KHR_materials_specular factor 0), which
both renderers evaluate exactly: in Cycles each imported material is rewired to a Diffuse BSDF
(roughness 0: Lambert) fed by the same base-colour factor and texture, plus an Emission shader
with the glTF emission (emissiveFactor x KHR_materials_emissive_strength). Cycles is set to match
strata's estimator where it matters for the mean: no clamping, no denoising, a box pixel filter,
caustics on, max bounces = strata's max depth - 1. Textures are sRGB; Cycles gets each as a float
image of its decoded texels, so that it filters linear values as strata does (it would interpolate
an 8-bit image's sRGB values before decoding them).

    tests/bench/cycles_compare.py --out /tmp/cycles [--stratad build/release/server/stratad]
        [--size 256] [--strata-spp 1024] [--cycles-spp 1024] [--untextured]

Prints (and writes to OUT/compare.json) the means, their ratios and the largest tile difference.
Run this file with python3; it runs itself inside Blender for the Cycles side.
"""
import argparse
import base64
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import zlib

# ---- the scene -------------------------------------------------------------------------------


def png_rgb8(width, height, pixel):
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


class Mesh:
    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []

    def quad(self, corner, u, v, normal, uv_scale=(1.0, 1.0)):
        base = len(self.positions)
        for (a, b) in ((0, 0), (1, 0), (1, 1), (0, 1)):
            self.positions.append([corner[i] + a * u[i] + b * v[i] for i in range(3)])
            self.normals.append(list(normal))
            self.uvs.append([a * uv_scale[0], (1 - b) * uv_scale[1]])
        self.indices += [base, base + 1, base + 2, base, base + 2, base + 3]

    def box(self, lo, hi):
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
        self.quad((x0, y0, z1), (dx, 0, 0), (0, dy, 0), (0, 0, 1))      # +z
        self.quad((x1, y0, z0), (-dx, 0, 0), (0, dy, 0), (0, 0, -1))    # -z
        self.quad((x1, y0, z1), (0, 0, -dz), (0, dy, 0), (1, 0, 0))     # +x
        self.quad((x0, y0, z0), (0, 0, dz), (0, dy, 0), (-1, 0, 0))     # -x
        self.quad((x0, y1, z1), (dx, 0, 0), (0, 0, -dz), (0, 1, 0))     # +y
        self.quad((x0, y0, z0), (dx, 0, 0), (0, 0, dz), (0, -1, 0))     # -y


def write_scene(out, textured):
    checker = png_rgb8(8, 8, lambda x, y: (204, 77, 51) if (x + y) % 2 == 0 else (51, 128, 204))
    ramp = png_rgb8(16, 16, lambda x, y: (16 * x + 8, 16 * y + 8, 128))
    with open(os.path.join(out, "checker.png"), "wb") as f:
        f.write(checker)
    with open(os.path.join(out, "ramp.png"), "wb") as f:
        f.write(ramp)

    floor, box_a, box_b, light = Mesh(), Mesh(), Mesh(), Mesh()
    floor.quad((-4, 0, 4), (8, 0, 0), (0, 0, -8), (0, 1, 0), uv_scale=(4, 4))
    box_a.box((-1.6, 0, -0.5), (-0.4, 1.2, 0.7))
    box_b.box((0.5, 0, -1.2), (1.5, 2.0, -0.2))
    light.quad((-0.6, 3.0, -0.6), (0, 0, 1.2), (1.2, 0, 0), (0, -1, 0))

    blob = bytearray()
    views, accessors = [], []

    def add(values, fmt, kind, comp, target, minmax=None):
        """One accessor over `values` (flat components) in its own buffer view."""
        while len(blob) % 4:
            blob.append(0)
        off = len(blob)
        blob.extend(struct.pack("<" + fmt * len(values), *values))
        views.append({"buffer": 0, "byteOffset": off, "byteLength": len(blob) - off, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": comp,
               "count": len(values) // {"VEC3": 3, "VEC2": 2, "SCALAR": 1}[kind], "type": kind}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    meshes = []
    for name, m, material in (("floor", floor, 0), ("box_a", box_a, 1), ("box_b", box_b, 2), ("light", light, 3)):
        lo = [min(p[i] for p in m.positions) for i in range(3)]
        hi = [max(p[i] for p in m.positions) for i in range(3)]
        pos = add([c for p in m.positions for c in p], "f", "VEC3", 5126, 34962, (lo, hi))
        nrm = add([c for n in m.normals for c in n], "f", "VEC3", 5126, 34962)
        uv = add([c for t in m.uvs for c in t], "f", "VEC2", 5126, 34962)
        idx = add(m.indices, "I", "SCALAR", 5125, 34963)
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv},
                                                     "indices": idx, "material": material}]})

    def lambert(name, colour, texture=None):
        pbr = {"baseColorFactor": colour + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}
        if texture is not None and textured:
            pbr["baseColorTexture"] = {"index": texture}
        return {"name": name, "pbrMetallicRoughness": pbr, "doubleSided": True,
                "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}

    materials = [lambert("floor", [1.0, 1.0, 1.0] if textured else [0.5, 0.35, 0.3], 0),
                 lambert("box_a", [0.9, 0.9, 0.9] if textured else [0.4, 0.45, 0.5], 1),
                 lambert("box_b", [0.6, 0.6, 0.55]),
                 dict(lambert("light", [0.0, 0.0, 0.0]), emissiveFactor=[1.0, 0.9, 0.75])]
    materials[3]["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": 12.0}

    # Camera at (0, 2.4, 6.5) looking at (0, 0.7, 0): a rotation about +X by the pitch.
    pitch = math.atan2(2.4 - 0.7, 6.5)
    cam_rot = [-math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]
    gltf = {
        "asset": {"version": "2.0", "generator": "strata tests/bench/cycles_compare.py"},
        "extensionsUsed": ["KHR_materials_specular", "KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4], "extras": {"strata": {"name": "cycles-compare", "environment": [0.25, 0.3, 0.4]}}}],
        "nodes": [{"name": n["name"], "mesh": i} for i, n in enumerate(meshes)] +
                 [{"name": "camera", "camera": 0, "translation": [0.0, 2.4, 6.5], "rotation": cam_rot}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1.0, "znear": 0.01}}],
        "meshes": meshes,
        "materials": materials,
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "images": [{"uri": "checker.png"}, {"uri": "ramp.png"}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    if not textured:
        del gltf["textures"], gltf["images"], gltf["samplers"]
    path = os.path.join(out, "scene.gltf")
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
    return path, gltf


# ---- inside Blender --------------------------------------------------------------------------


def blender_main(argv):
    import bpy
    import numpy as np

    args = json.loads(argv[0])
    # Debian 12 pairs Blender 3.4, whose glTF importer still uses the alias np.bool, with NumPy 1.24,
    # which removed it: restore the alias for the importer.
    if "bool" not in np.__dict__:
        np.bool = np.bool_
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=args["scene"])
    gltf = json.load(open(args["scene"]))
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = args["spp"]
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.seed = 1
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.max_bounces = cy.diffuse_bounces = args["bounces"]
    cy.glossy_bounces = cy.transmission_bounces = cy.volume_bounces = cy.transparent_max_bounces = args["bounces"]
    cy.caustics_reflective = cy.caustics_refractive = True
    cy.blur_glossy = 0.0
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    scene.render.resolution_x = scene.render.resolution_y = args["size"]
    scene.render.resolution_percentage = 100
    scene.render.threads_mode = "FIXED"
    scene.render.threads = os.cpu_count() or 1
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.film_transparent = False
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    scene.camera = cams[0]
    cams[0].data.sensor_fit = "VERTICAL"

    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    env = gltf["scenes"][0]["extras"]["strata"]["environment"]
    world.node_tree.nodes["Background"].inputs["Color"].default_value = env + [1.0]
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world

    # Each material: Lambert (Diffuse BSDF at roughness 0) with the imported base colour (factor and
    # texture, as the importer wired them), plus the glTF emission.
    by_name = {m["name"]: m for m in gltf["materials"]}
    for mat in bpy.data.materials:
        src = by_name.get(mat.name)
        if src is None or not mat.use_nodes:
            continue
        nt = mat.node_tree
        principled = next(n for n in nt.nodes if n.type == "BSDF_PRINCIPLED")
        output = next(n for n in nt.nodes if n.type == "OUTPUT_MATERIAL")
        diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Roughness"].default_value = 0.0
        base = principled.inputs["Base Color"]
        if base.is_linked:
            nt.links.new(base.links[0].from_socket, diffuse.inputs["Color"])
        else:
            diffuse.inputs["Color"].default_value = base.default_value
        emission = nt.nodes.new("ShaderNodeEmission")
        e = src.get("emissiveFactor", [0.0, 0.0, 0.0])
        strength = src.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
        emission.inputs["Color"].default_value = e + [1.0]
        emission.inputs["Strength"].default_value = strength
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(diffuse.outputs["BSDF"], add.inputs[0])
        nt.links.new(emission.outputs["Emission"], add.inputs[1])
        nt.links.new(add.outputs["Shader"], output.inputs["Surface"])

    # Cycles interpolates an 8-bit image's stored (sRGB) values and converts the result to linear;
    # strata, like Vulkan's sRGB formats and glTF, decodes each texel first and interpolates linear
    # values. Each sRGB image becomes a float image of its decoded texels (colour space Linear),
    # which Cycles interpolates as it stores them: the same filter as strata's.
    def linear_copy(img):
        w, h = img.size
        px = np.array(img.pixels[:], dtype=np.float64).reshape(-1, 4)
        rgb = px[:, :3]
        px[:, :3] = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
        out = bpy.data.images.new(img.name + " linear", w, h, alpha=True, float_buffer=True)
        out.colorspace_settings.name = "Linear"
        out.pixels[:] = px.astype(np.float32).ravel().tolist()
        out.pack()
        return out
    linear = {}
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        for node in mat.node_tree.nodes:
            if node.type == "TEX_IMAGE" and node.image is not None and node.image.colorspace_settings.name == "sRGB":
                if node.image.name not in linear:
                    linear[node.image.name] = linear_copy(node.image)
                node.image = linear[node.image.name]

    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = args["out"]
    bpy.ops.render.render(write_still=True)

    def pixels(path):
        img = bpy.data.images.load(path)
        img.colorspace_settings.name = "Non-Color"
        a = np.array(img.pixels[:], dtype=np.float64).reshape(img.size[1], img.size[0], 4)[:, :, :3]
        return a[::-1]  # Blender's rows start at the bottom

    c = pixels(args["out"])
    s = pixels(args["strata"])
    result = {"size": args["size"], "cycles_spp": args["spp"], "bounces": args["bounces"]}
    result["strata_mean"] = s.mean(axis=(0, 1)).tolist()
    result["cycles_mean"] = c.mean(axis=(0, 1)).tolist()
    result["ratio_strata_over_cycles"] = (s.mean(axis=(0, 1)) / c.mean(axis=(0, 1))).tolist()
    n = args["size"] // 4
    tiles = []
    for ty in range(4):
        for tx in range(4):
            ts = s[ty * n:(ty + 1) * n, tx * n:(tx + 1) * n].mean(axis=(0, 1))
            tc = c[ty * n:(ty + 1) * n, tx * n:(tx + 1) * n].mean(axis=(0, 1))
            tiles.append((ts / np.maximum(tc, 1e-6) - 1.0).tolist())
    result["tile_relative_difference"] = tiles
    result["tile_max_abs_relative_difference"] = float(np.max(np.abs(np.array(tiles))))
    with open(args["result"], "w") as f:
        json.dump(result, f, indent=1)


# ---- the driver ------------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--stratad", default="build/release/server/stratad")
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--strata-spp", type=int, default=1024)
    ap.add_argument("--cycles-spp", type=int, default=1024)
    ap.add_argument("--max-depth", type=int, default=16, help="strata's --max-depth (path segments)")
    ap.add_argument("--untextured", action="store_true", help="plain colours instead of the two textures")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene, _ = write_scene(a.out, not a.untextured)
    strata_dir = os.path.join(a.out, "strata")
    # strata: frames of pt at the same camera accumulate (the still scene's frames are independent
    # samples); spp per frame times frames = --strata-spp.
    per_frame = min(a.strata_spp, 64)
    frames = max(1, a.strata_spp // per_frame)
    subprocess.run([a.stratad, "render", "--scene", scene, "--method", "pt", "--spp", str(per_frame), "--frames", str(frames),
                    "--accumulate", "--max-depth", str(a.max_depth), "--width", str(a.size), "--height", str(a.size),
                    "--out", strata_dir], check=True)
    strata_exr = os.path.join(strata_dir, sorted(f for f in os.listdir(strata_dir) if f.endswith(".exr"))[0])
    args = {"scene": scene, "spp": a.cycles_spp, "size": a.size, "bounces": a.max_depth - 1,
            "out": os.path.join(a.out, "cycles.exr"), "strata": strata_exr, "result": os.path.join(a.out, "compare.json")}
    # Blender's embedded Python finds its modules from the python3 on PATH: a pyenv or virtualenv
    # python3 first on PATH hides Debian's (and NumPy, which the glTF importer needs).
    blender = shutil.which(a.blender) or a.blender
    env = dict(os.environ, PATH="/usr/bin:/bin")
    subprocess.run([blender, "-b", "--factory-startup", "-noaudio", "--python", os.path.abspath(__file__), "--", json.dumps(args)],
                   check=True, env=env)
    print(open(args["result"]).read())


if __name__ == "__main__":
    try:
        import bpy  # noqa: F401  (present only when Blender runs this file)
    except ImportError:
        main()
    else:
        blender_main(sys.argv[sys.argv.index("--") + 1:])
