#!/usr/bin/env python3
"""Writes issue 30's regression inputs, tests/fuzz/regressions/issue30_*.bundle (bundle.h).

Each is one defect of that round, as a bundle the fuzz target loads (and renders tiny, when it
loads): before the fixes they hung, crashed, read out of bounds, or took gigabytes. The CLI
defects (output names, `compare` ranks) are tested in tests/cli/test_cli.sh instead.
Run from anywhere: python3 tests/fuzz/make_regressions.py (it writes only issue30_* files).
"""
import struct
import zlib

import make_corpus as mc

OUT = mc.HERE / "regressions"


def serialized(vertices, triangles, body=b"", version=4):
    """One mesh: the header's counts as given, then `body` (the arrays, or not)."""
    flags = 0x2000  # single precision
    stream = struct.pack("<I", flags) + (b"m\0" if version == 4 else b"") + struct.pack("<QQ", vertices, triangles)
    z = zlib.compress(stream + body, 9)
    entry = struct.pack("<Q" if version == 4 else "<I", 0)
    return struct.pack("<HH", 0x041C, version) + z + entry + struct.pack("<I", 1)


def main():
    full = mc.ROOT / "tests/data/scenes/full"
    two = (full / "meshes/two.serialized").read_bytes()
    shape = lambda f: mc.scene(mc.LIGHT + f"""
    <shape type="serialized"><string name="filename" value="{f}"/></shape>""")
    envmap = lambda f: mc.scene(mc.GLASS + f"""
    <emitter type="envmap"><string name="filename" value="{f}"/></emitter>""")
    rle = mc.hdr_rle(64, 8)
    # The SOF0 frame header's height and width set to 8192 (FF C0, length, precision, h, w).
    jpg = bytearray((mc.HERE / "assets/tiny.jpg").read_bytes())
    sof = jpg.find(b"\xff\xc0")
    jpg[sof + 5:sof + 9] = struct.pack(">HH", 8192, 8192)
    # Two meshes' offset table with the second entry near 2^64 (begin + 4 wrapped).
    wrapped = bytearray(two)
    wrapped[-12:-4] = struct.pack("<Q", 0xfffffffffffffffe)
    nest = lambda n, inner: '<bsdf type="twosided">' * n + inner + "</bsdf>" * n
    cases = {
        # 1 and 8: a truncated run-length .hdr as an envmap hung in stb, or loaded black.
        "issue30_envmap_hdr_truncated_53_bytes": [("scene.xml", envmap("sky.hdr")), ("sky.hdr", rle[:53])],
        "issue30_envmap_hdr_truncated_mid_scanline": [("scene.xml", envmap("sky.hdr")), ("sky.hdr", rle[:101])],
        # 2: an offset-table entry near 2^64.
        "issue30_serialized_offset_near_2e64": [("scene.xml", mc.scene(mc.LIGHT + """
    <shape type="serialized"><string name="filename" value="two.serialized"/>
        <integer name="shape_index" value="1"/></shape>""")), ("two.serialized", bytes(wrapped))],
        # 3: an instance scaled by 1e-20 (Embree's ray.valid() abort).
        "issue30_instance_scaled_1e-20": [("scene.xml", mc.scene(mc.LIGHT + """
    <shape type="shapegroup" id="g"><shape type="sphere"><float name="radius" value="0.3"/></shape></shape>
    <shape type="instance"><ref id="g"/><transform name="to_world"><scale value="1e-20"/></transform></shape>"""))],
        # 4: an include chain, each file nesting 200 levels (3 files overflowed ASan's stack).
        "issue30_include_chain_nesting_600": [
            ("scene.xml", '<scene version="3.0.0"><shape type="sphere"><include filename="a.xml"/></shape></scene>\n'),
            ("a.xml", '<scene version="3.0.0">' + nest(200, '<include filename="b.xml"/>') + "</scene>\n"),
            ("b.xml", '<scene version="3.0.0">' + nest(200, '<include filename="c.xml"/>') + "</scene>\n"),
            ("c.xml", '<scene version="3.0.0">' + nest(200, '<bsdf type="diffuse"/>') + "</scene>\n")],
        # 5: an area light's radiance texture of 10 (it clipped at 1).
        "issue30_area_radiance_texture_10": [("scene.xml", mc.scene(mc.GLASS + """
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.5"/><translate value="0, 0, 3"/></transform>
        <emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="e.exr"/>
        </texture></emitter>
    </shape>""")), ("e.exr", mc.exr(2, 2, lambda x, y: (10.0, 10.0, 10.0)))],
        # 6: inflation bombs: a 3-vertex header over 64 MB of zeros (inflated whole before), and
        #    a header claiming 2^40 vertices over a few bytes (allocated before).
        "issue30_serialized_bomb_64mb_stream": [("scene.xml", shape("bomb.serialized")),
                                                ("bomb.serialized", serialized(3, 1, bytes(64 << 20)))],
        "issue30_serialized_counts_2e40": [("scene.xml", shape("claim.serialized")),
                                           ("claim.serialized", serialized(1 << 40, 1 << 40))],
        # 7: a JPEG texture whose header claims 8192 x 8192 (1.7 GB, 24 s, grey).
        "issue30_jpeg_claims_8192x8192": [("scene.xml", mc.scene(mc.LIGHT + """
    <shape type="rectangle"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="t.jpg"/></texture></bsdf></shape>""")), ("t.jpg", bytes(jpg))],
        # 9: 5,000 <path value="."/> (quadratic before; 20,000 do not fit the fuzzer's max_len).
        "issue30_paths_5000": [("scene.xml", mc.scene(mc.LIGHT).replace(
            '<scene version="3.0.0">', '<scene version="3.0.0">\n' + '<path value="."/>\n' * 5000))],
    }
    total = 0
    for name, files in sorted(cases.items()):
        data = mc.bundle(files)
        total += len(data)
        (OUT / (name + ".bundle")).write_bytes(data)
    print(f"make_regressions: {len(cases)} bundles, {total} bytes in {OUT}")


if __name__ == "__main__":
    main()
