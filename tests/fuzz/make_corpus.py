#!/usr/bin/env python3
"""Writes the fuzz target's seed corpus, tests/fuzz/corpus/*.bundle (format: tests/fuzz/bundle.h).

Every file is made here or taken from snell's own test scenes, so the corpus is ours to
redistribute. The scenes are small and render fast (few primitives, short integrator settings);
each covers part of the loader: includes, defaults, refs, PLY (ASCII and binary, with vertex
colours), OBJ, serialized meshes, EXR and PNG images, .vol grids, every integrator, sensor,
sampler and filter, instancing, textures and most BSDFs and emitters.
Run from anywhere: python3 tests/fuzz/make_corpus.py (it rewrites the folder).
"""
import pathlib
import struct
import zlib

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
OUT = HERE / "corpus"


def bundle(files):
    """files: list of (name, bytes or str), the scene first."""
    out = b""
    for i, (name, data) in enumerate(files):
        if isinstance(data, str):
            data = data.encode()
        out += (b"\n" if i else b"") + b"@@file " + name.encode() + b"\n" + data
    return out


def exr(width, height, pixel):
    """Uncompressed scanline EXR, float channels B, G, R; pixel(x, y) -> (r, g, b)."""
    def attr(name, typ, value):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(value)) + value

    chlist = b"".join(c + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in (b"B", b"G", b"R")) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (struct.pack("<ii", 20000630, 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    lines = []
    for y in range(height):
        px = [pixel(x, y) for x in range(width)]
        data = b"".join(struct.pack("<f", p[c]) for c in (2, 1, 0) for p in px)
        lines.append(struct.pack("<ii", y, len(data)) + data)
    offset = len(header) + 8 * height
    table = b""
    for line in lines:
        table += struct.pack("<Q", offset)
        offset += len(line)
    return header + table + b"".join(lines)


def png(width, height, pixel):
    """8-bit RGB PNG; pixel(x, y) -> (r, g, b) in 0..255."""
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xffffffff)

    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def hdr_rle(width, height, value=100):
    """Radiance .hdr, new-style run-length scanlines (2, 2, width, then one run per channel)."""
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width)
    line = bytes([2, 2, width >> 8, width & 255]) + b"".join(bytes([128 + width, 128 if c == 3 else value])
                                                            for c in range(4))
    return head + line * height


def vol(res, values):
    """Mitsuba .vol grid, version 3, float32, one channel, bounding box [0, 1]^3."""
    return b"VOL\x03" + struct.pack("<5i", 1, res, res, res, 1) + struct.pack("<6f", 0, 0, 0, 1, 1, 1) + \
        struct.pack("<%df" % len(values), *values)


PLY_ASCII = """ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
property float u
property float v
property uchar red
property uchar green
property uchar blue
element face 2
property list uchar int vertex_indices
end_header
-1 -1 0 0 0 255 0 0
1 -1 0 1 0 0 255 0
1 1 0 1 1 0 0 255
-1 1 0 0 1 255 255 255
3 0 1 2
3 0 2 3
"""


def ply_binary():
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n").encode()
    verts = [(-1, -1, 0), (1, -1, 0), (0, 1, 0)]
    body = b"".join(struct.pack("<6f", *v, 0, 0, 1) for v in verts)
    return head + body + struct.pack("<B3i", 3, 0, 1, 2)


OBJ = """# a quad with uv and normals, and a triangle with negative indices
v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f -4 -3 -2
"""


def scene(body, integrator='<integrator type="path"><integer name="max_depth" value="4"/></integrator>',
          sensor_type="perspective", sensor_extra='<float name="fov" value="45"/>', sampler="independent",
          rfilter="box"):
    return f"""<scene version="3.0.0">
    {integrator}
    <sensor type="{sensor_type}">
        {sensor_extra}
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm">
            <integer name="width" value="8"/>
            <integer name="height" value="8"/>
            <rfilter type="{rfilter}"/>
        </film>
        <sampler type="{sampler}"><integer name="sample_count" value="4"/></sampler>
    </sensor>
{body}
</scene>
"""


LIGHT = """    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><translate value="0, 0, 3"/></transform>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter>
    </shape>"""

GLASS = """    <shape type="sphere">
        <point name="center" x="0" y="0" z="0.5"/>
        <float name="radius" value="0.4"/>
        <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>"""


def main():
    OUT.mkdir(exist_ok=True)
    for old in OUT.glob("*.bundle"):
        old.unlink()
    corpus = {}
    data = ROOT / "tests/data/scenes"

    # snell's own test scenes: includes, defaults, refs, OBJ, an include cycle.
    full = data / "full"
    corpus["full_scene"] = [("scene.xml", (full / "scene.xml").read_text()),
                            ("meshes/part.xml", (full / "meshes/part.xml").read_text()),
                            ("meshes/tri.obj", (full / "meshes/tri.obj").read_text())]
    parser = data / "parser"
    sensor = '<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/></film></sensor>'
    main_xml = (parser / "main.xml").read_text().replace("</scene>", sensor + "\n</scene>")
    corpus["include_defaults_refs"] = [("main.xml", main_xml),
                                       ("sub/shapes.xml", (parser / "sub/shapes.xml").read_text()),
                                       ("sub/mesh.obj", OBJ)]
    corpus["include_cycle"] = [("cycle_a.xml", (parser / "cycle_a.xml").read_text()),
                               ("cycle_b.xml", (parser / "cycle_b.xml").read_text())]
    for name in ("droplet", "glass_sphere", "offcentre_caustic"):
        corpus["scene_" + name] = [("scene.xml", (ROOT / "scenes" / name / (name + ".xml")).read_text())]

    # Every integrator on a glass sphere over a floor, with short settings.
    integrators = {
        "path": '<integrator type="path"><integer name="max_depth" value="5"/></integrator>',
        "pt": '<integrator type="pt"/>',
        "nee": '<integrator type="nee"/>',
        "direct": '<integrator type="direct"><integer name="emitter_samples" value="2"/></integrator>',
        "mnee": '<integrator type="mnee"><integer name="max_depth" value="5"/></integrator>',
        "bdpt": '<integrator type="bdpt"><integer name="max_depth" value="5"/></integrator>',
        "pssmlt": '<integrator type="pssmlt"><integer name="bootstrap_samples" value="64"/>'
                  '<integer name="mutations_per_pixel" value="4"/><integer name="chains" value="2"/></integrator>',
        "erpt": '<integrator type="erpt"><integer name="bootstrap_samples" value="64"/>'
                '<integer name="mutations" value="4"/></integrator>',
        "moment": '<integrator type="moment"><integrator type="path"/></integrator>',
    }
    for name, integ in integrators.items():
        corpus["integrator_" + name] = [("scene.xml", scene(GLASS + "\n" + LIGHT, integrator=integ))]

    # Sensors, samplers, filters.
    corpus["sensor_thinlens_sobol_gaussian"] = [("scene.xml", scene(
        GLASS + "\n" + LIGHT, sensor_type="thinlens", sampler="sobol", rfilter="gaussian",
        sensor_extra='<float name="fov" value="45"/><float name="aperture_radius" value="0.1"/>'
        '<float name="focus_distance" value="4"/>'))]
    corpus["sensor_orthographic_stratified_tent"] = [("scene.xml", scene(
        GLASS + "\n" + LIGHT, sensor_type="orthographic", sampler="stratified", rfilter="tent", sensor_extra=""))]
    for s in ("multijitter", "orthogonal", "ldsampler"):
        corpus["sampler_" + s] = [("scene.xml", scene(GLASS + "\n" + LIGHT, sampler=s))]

    # Meshes: PLY (ASCII with uv and vertex colours read by mesh_attribute; binary with
    # normals), OBJ with a PNG texture, serialized.
    corpus["ply_ascii_mesh_attribute"] = [("scene.xml", scene(LIGHT + """
    <shape type="ply">
        <string name="filename" value="quad.ply"/>
        <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance">
            <string name="name" value="vertex_color"/></texture></bsdf>
    </shape>""")), ("quad.ply", PLY_ASCII)]
    corpus["ply_binary"] = [("scene.xml", scene(LIGHT + """
    <shape type="ply">
        <string name="filename" value="meshes/tri.ply"/>
        <boolean name="face_normals" value="false"/>
        <bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.2"/></bsdf>
    </shape>""")), ("meshes/tri.ply", ply_binary())]
    corpus["obj_png_texture"] = [("scene.xml", scene(LIGHT + """
    <shape type="obj">
        <string name="filename" value="quad.obj"/>
        <bsdf type="diffuse"><texture type="bitmap" name="reflectance">
            <string name="filename" value="tex.png"/><string name="filter_type" value="nearest"/>
        </texture></bsdf>
    </shape>""")), ("quad.obj", OBJ),
        ("tex.png", png(2, 2, lambda x, y: (255 * x, 255 * y, 128)))]
    corpus["serialized"] = [("scene.xml", scene(LIGHT + """
    <shape type="serialized">
        <string name="filename" value="two.serialized"/>
        <integer name="shape_index" value="1"/>
    </shape>""")), ("two.serialized", (full / "meshes/two.serialized").read_bytes())]

    # Images: an EXR environment map, EXR textures through bump and normal maps, a projector.
    corpus["envmap_exr"] = [("scene.xml", scene(GLASS + """
    <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="2"/></emitter>""")),
        ("sky.exr", exr(6, 4, lambda x, y: (0.2 + x, 0.5, 1.0 + y)))]
    corpus["exr_bump_normal"] = [("scene.xml", scene(LIGHT + """
    <shape type="sphere">
        <bsdf type="bumpmap">
            <texture type="bitmap"><string name="filename" value="h.exr"/><boolean name="raw" value="true"/></texture>
            <bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.3, 0.5, 0.7"/></bsdf>
        </bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><translate value="0, 0, -1"/><scale value="3"/></transform>
        <bsdf type="normalmap">
            <texture type="bitmap" name="normalmap"><string name="filename" value="n.exr"/>
                <boolean name="raw" value="true"/></texture>
            <bsdf type="conductor"/>
        </bsdf>
    </shape>""")), ("h.exr", exr(2, 2, lambda x, y: (x, y, 0))),
        ("n.exr", exr(2, 2, lambda x, y: (0.5, 0.5, 1.0)))]
    corpus["lights"] = [("scene.xml", scene(GLASS + """
    <emitter type="point"><point name="position" value="0, 1, 2"/><rgb name="intensity" value="5"/></emitter>
    <emitter type="spot"><transform name="to_world"><lookat origin="1, 1, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <float name="cutoff_angle" value="30"/></emitter>
    <emitter type="directional"><vector name="direction" value="0, -1, -1"/></emitter>
    <emitter type="constant"><rgb name="radiance" value="0.1"/></emitter>
    <emitter type="projector"><float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <texture type="bitmap" name="irradiance"><string name="filename" value="p.png"/></texture>
    </emitter>""", integrator='<integrator type="bdpt"><integer name="max_depth" value="4"/></integrator>')),
        ("p.png", png(3, 2, lambda x, y: (80 * x, 100 * y, 200)))]

    # Issue 30's features: a run-length .hdr environment map (through the texture reader), JPEG
    # and EXR textures as emission (area radiance above 1, a spot light's pattern), an include
    # chain, a serialized mesh in an instanced shape group.
    corpus["envmap_hdr_rle"] = [("scene.xml", scene(GLASS + """
    <emitter type="envmap"><string name="filename" value="sky.hdr"/></emitter>""")), ("sky.hdr", hdr_rle(16, 4))]
    corpus["emission_textures"] = [("scene.xml", scene(GLASS + """
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><translate value="0, 0, 3"/></transform>
        <emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="e.exr"/>
        </texture></emitter>
    </shape>
    <emitter type="spot"><transform name="to_world"><lookat origin="1, 1, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <texture type="bitmap" name="texture"><string name="filename" value="s.jpg"/></texture></emitter>""")),
        ("e.exr", exr(2, 2, lambda x, y: (10.0, 2.0 + x, 100.0 * y))),
        ("s.jpg", (HERE / "assets/tiny.jpg").read_bytes())]
    corpus["include_chain"] = [("scene.xml", scene(LIGHT + """
    <shape type="sphere"><include filename="a.xml"/></shape>""")),
        ("a.xml", '<scene version="3.0.0"><bsdf type="twosided"><include filename="b.xml"/></bsdf></scene>\n'),
        ("b.xml", '<scene version="3.0.0"><bsdf type="diffuse"/></scene>\n')]
    corpus["serialized_instance"] = [("scene.xml", scene(LIGHT + """
    <shape type="shapegroup" id="g">
        <shape type="serialized"><string name="filename" value="two.serialized"/></shape>
    </shape>
    <shape type="instance"><ref id="g"/><transform name="to_world"><scale value="0.5"/></transform></shape>""")),
        ("two.serialized", (full / "meshes/two.serialized").read_bytes())]

    # BSDFs, instancing, checkerboard, a volume texture, spectra.
    corpus["bsdfs"] = [("scene.xml", scene(LIGHT + """
    <bsdf type="principled" id="p"><rgb name="base_color" value="0.8, 0.2, 0.1"/>
        <float name="metallic" value="0.3"/><float name="clearcoat" value="0.5"/></bsdf>
    <shape type="sphere"><point name="center" x="-1" y="0" z="0"/><float name="radius" value="0.4"/><ref id="p"/></shape>
    <shape type="sphere"><point name="center" x="1" y="0" z="0"/><float name="radius" value="0.4"/>
        <bsdf type="blendbsdf"><float name="weight" value="0.3"/>
            <bsdf type="roughdielectric"><float name="alpha" value="0.1"/><string name="distribution" value="ggx"/></bsdf>
            <bsdf type="twosided"><bsdf type="plastic"/></bsdf>
        </bsdf>
    </shape>
    <shape type="cylinder"><float name="radius" value="0.2"/>
        <bsdf type="thindielectric"/></shape>
    <shape type="disk"><transform name="to_world"><translate value="0, -1, 0"/></transform>
        <bsdf type="principledthin"/></shape>
    <shape type="cube"><transform name="to_world"><scale value="0.2"/><translate value="0, 1, 0"/></transform>
        <bsdf type="diffuse"><spectrum name="reflectance" value="400:0.1, 500:0.5, 700:0.9"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><translate value="0, 0, -1"/><scale value="3"/></transform>
        <bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <rgb name="color0" value="0.1"/><rgb name="color1" value="0.9"/></texture></bsdf></shape>"""))]
    corpus["instances"] = [("scene.xml", scene(LIGHT + """
    <shape type="shapegroup" id="g">
        <shape type="sphere"><float name="radius" value="0.3"/><bsdf type="dielectric"/></shape>
        <shape type="cube"><transform name="to_world"><scale value="0.2"/></transform></shape>
    </shape>
    <shape type="instance"><ref id="g"/><transform name="to_world"><translate value="-0.5, 0, 0"/></transform></shape>
    <shape type="instance"><ref id="g"/><transform name="to_world"><scale value="0.5, 1, 2"/><rotate y="1" angle="30"/>
        </transform></shape>""", integrator='<integrator type="mnee"/>'))]
    corpus["gridvolume"] = [("scene.xml", scene(LIGHT + """
    <shape type="rectangle"><transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><texture type="volume" name="reflectance"><volume type="gridvolume" name="volume">
            <string name="filename" value="g.vol"/><string name="filter_type" value="trilinear"/>
            <transform name="to_world"><translate value="-0.5, -0.5, -0.5"/></transform>
        </volume></texture></bsdf>
    </shape>""")), ("g.vol", vol(2, [0.1 * i for i in range(8)]))]

    total = 0
    for name, files in sorted(corpus.items()):
        data = bundle(files)
        total += len(data)
        (OUT / (name + ".bundle")).write_bytes(data)
    print(f"make_corpus: {len(corpus)} bundles, {total} bytes in {OUT}")


if __name__ == "__main__":
    main()
