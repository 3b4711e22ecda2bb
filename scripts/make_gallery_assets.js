#!/usr/bin/env node
// Writes the assets of the caustic gallery (scenes/caustics/): meshes as Wavefront OBJ with
// smooth (per-vertex) normals, the way users' scenes bring them, and an environment map:
//   ball.obj   a UV sphere of radius 1 (128 slices, 64 stacks: 16,128 triangles), exact normals
//   pool.obj   a wavy water height field over [-2, 2]^2 at y = 0 (192 x 192 cells: 73,728
//              triangles), a sum of sines with analytic normals
//   bunny.obj  the Stanford bunny with area-weighted vertex normals, when the npm package `bunny`
//              is installed under NPM_PREFIX (scripts/make_bunny_mesh.sh installs it)
//   sky.hdr    a 256 x 128 equirectangular sky (Radiance RGBE): a blue gradient and a sun of
//              about 3 degrees, 30 degrees above the horizon, that carries most of the light
// Usage: node scripts/make_gallery_assets.js OUT_DIR [NPM_PREFIX]
'use strict';
const fs = require('fs');
const path = require('path');

if (process.argv.length < 3 || process.argv.length > 4) {
  console.error('usage: node make_gallery_assets.js OUT_DIR [NPM_PREFIX]');
  process.exit(2);
}
const outDir = process.argv[2];
const npmPrefix = process.argv[3];
fs.mkdirSync(outDir, { recursive: true });

const f6 = (x) => x.toFixed(6);

// Writes positions, normals and triangles (0-based vertex indices; position i has normal i).
function writeObj(name, comment, pos, nrm, tris) {
  const lines = ['# ' + comment + '; written by scripts/make_gallery_assets.js'];
  for (const p of pos) lines.push('v ' + p.map(f6).join(' '));
  for (const n of nrm) lines.push('vn ' + n.map(f6).join(' '));
  for (const t of tris) lines.push('f ' + t.map((i) => (i + 1) + '//' + (i + 1)).join(' '));
  const out = path.join(outDir, name);
  // Beside the target and renamed, so a concurrent reader never sees half a file.
  const tmp = out + '.' + process.pid + '.tmp';
  fs.writeFileSync(tmp, lines.join('\n') + '\n');
  fs.renameSync(tmp, out);
  console.log('make_gallery_assets: wrote ' + out + ' (' + tris.length + ' triangles)');
}

function normalize(v) {
  const l = Math.hypot(v[0], v[1], v[2]);
  return [v[0] / l, v[1] / l, v[2] / l];
}

// UV sphere: poles at +-y, one fan of triangles at each pole.
function ball() {
  const slices = 128, stacks = 64;
  const pos = [[0, 1, 0]];
  for (let i = 1; i < stacks; ++i) {
    const theta = (Math.PI * i) / stacks;
    for (let j = 0; j < slices; ++j) {
      const phi = (2 * Math.PI * j) / slices;
      pos.push([Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi)]);
    }
  }
  pos.push([0, -1, 0]);
  const south = pos.length - 1;
  const at = (i, j) => 1 + (i - 1) * slices + (j % slices);
  const tris = [];
  for (let j = 0; j < slices; ++j) tris.push([0, at(1, j + 1), at(1, j)]);
  for (let i = 1; i < stacks - 1; ++i)
    for (let j = 0; j < slices; ++j) {
      tris.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
      tris.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
    }
  for (let j = 0; j < slices; ++j) tris.push([south, at(stacks - 1, j), at(stacks - 1, j + 1)]);
  writeObj('ball.obj', 'UV sphere, radius 1, 128 x 64', pos, pos.map(normalize), tris);
}

// Water: h(x, z) = sum_i a_i sin(k_i . (x, z) + phase_i); normal (-dh/dx, 1, -dh/dz).
function pool() {
  const waves = [
    [0.030, 5.0, 1.3, 0.0],
    [0.022, -2.4, 6.1, 1.1],
    [0.016, 7.9, -3.2, 2.3],
    [0.010, 3.1, 9.7, 0.7],
  ];
  const n = 192, half = 2.0;
  const pos = [], nrm = [];
  for (let i = 0; i <= n; ++i)
    for (let j = 0; j <= n; ++j) {
      const x = -half + (2 * half * j) / n, z = -half + (2 * half * i) / n;
      let h = 0, hx = 0, hz = 0;
      for (const [a, kx, kz, ph] of waves) {
        const s = kx * x + kz * z + ph;
        h += a * Math.sin(s);
        hx += a * kx * Math.cos(s);
        hz += a * kz * Math.cos(s);
      }
      pos.push([x, h, z]);
      nrm.push(normalize([-hx, 1, -hz]));
    }
  const at = (i, j) => i * (n + 1) + j;
  const tris = [];
  // Wound so that the geometric normal faces +y, as the shading normals do.
  for (let i = 0; i < n; ++i)
    for (let j = 0; j < n; ++j) {
      tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
      tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
    }
  writeObj('pool.obj', 'wavy water height field over [-2, 2]^2, 192 x 192 cells', pos, nrm, tris);
}

// The bunny's vertex normals: the sum of its faces' area-weighted normals.
function bunny() {
  let b;
  try {
    b = require(path.resolve(npmPrefix, 'node_modules', 'bunny'));
  } catch (e) {
    console.error('make_gallery_assets: no npm package bunny under ' + npmPrefix + ', bunny.obj not written');
    return;
  }
  const nrm = b.positions.map(() => [0, 0, 0]);
  for (const [a, c, d] of b.cells) {
    const p = b.positions[a], q = b.positions[c], r = b.positions[d];
    const u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]], v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
    const cr = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    for (const i of [a, c, d]) for (let k = 0; k < 3; ++k) nrm[i][k] += cr[k];
  }
  writeObj('bunny.obj', 'Stanford bunny (npm package "bunny"), smooth normals', b.positions,
           nrm.map((n) => (Math.hypot(n[0], n[1], n[2]) > 0 ? normalize(n) : [0, 1, 0])), b.cells);
}

// Radiance RGBE, flat scanlines (readers take them when no run-length marker starts a line).
function sky() {
  const w = 256, h = 128;
  // The sun: 30 degrees above the horizon (+y is up, as in the map's rows), at azimuth 40
  // degrees in the map's own longitude.
  const el = (30 * Math.PI) / 180, az = (40 * Math.PI) / 180;
  const sun = [Math.cos(el) * Math.cos(az), Math.sin(el), Math.cos(el) * Math.sin(az)];
  const cosSun = Math.cos((1.5 * Math.PI) / 180);
  const header = Buffer.from('#?RADIANCE\n# snell caustic gallery sky, scripts/make_gallery_assets.js\n' +
                             'FORMAT=32-bit_rle_rgbe\n\n-Y ' + h + ' +X ' + w + '\n', 'ascii');
  const data = Buffer.alloc(w * h * 4);
  for (let y = 0; y < h; ++y)
    for (let x = 0; x < w; ++x) {
      const theta = (Math.PI * (y + 0.5)) / h, phi = (2 * Math.PI * (x + 0.5)) / w;
      const d = [Math.sin(theta) * Math.cos(phi), Math.cos(theta), Math.sin(theta) * Math.sin(phi)];
      const up = Math.max(d[1], 0);
      let rgb = d[1] > 0 ? [0.25 + 0.35 * (1 - up), 0.45 + 0.3 * (1 - up), 0.9] : [0.08, 0.07, 0.06];
      if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] > cosSun) rgb = [4000, 3700, 3300];
      const m = Math.max(rgb[0], rgb[1], rgb[2]);
      const e = Math.ceil(Math.log2(m));
      const s = Math.pow(2, -e) * 256;
      const o = 4 * (y * w + x);
      for (let k = 0; k < 3; ++k) data[o + k] = Math.min(255, Math.floor(rgb[k] * s));
      data[o + 3] = e + 128;
    }
  const out = path.join(outDir, 'sky.hdr');
  const tmp = out + '.' + process.pid + '.tmp';
  fs.writeFileSync(tmp, Buffer.concat([header, data]));
  fs.renameSync(tmp, out);
  console.log('make_gallery_assets: wrote ' + out);
}

ball();
pool();
sky();
if (npmPrefix) bunny();
