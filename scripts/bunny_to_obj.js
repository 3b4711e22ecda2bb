#!/usr/bin/env node
// Writes the Stanford bunny from the npm package `bunny` (positions and cells as JS arrays,
// public domain) as a Wavefront OBJ, untouched: the scene file scales and places it.
// Usage: node scripts/bunny_to_obj.js <folder holding node_modules> <out.obj>
'use strict';
const fs = require('fs');
const path = require('path');

if (process.argv.length !== 4) {
  console.error('usage: node bunny_to_obj.js <npm prefix> <out.obj>');
  process.exit(2);
}
const bunny = require(path.resolve(process.argv[2], 'node_modules', 'bunny'));
const out = process.argv[3];

const lines = ['# Stanford bunny (npm package "bunny"), ' + bunny.positions.length +
               ' vertices, ' + bunny.cells.length + ' triangles; written by scripts/bunny_to_obj.js'];
for (const p of bunny.positions) lines.push('v ' + p.join(' '));
// OBJ indices are 1-based.
for (const c of bunny.cells) lines.push('f ' + c.map((i) => i + 1).join(' '));

// Write beside the target and rename, so a concurrent build never reads a half-written file.
const tmp = out + '.' + process.pid + '.tmp';
fs.mkdirSync(path.dirname(out), { recursive: true });
fs.writeFileSync(tmp, lines.join('\n') + '\n');
fs.renameSync(tmp, out);
